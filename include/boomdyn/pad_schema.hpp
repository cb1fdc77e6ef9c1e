// The `pad` map of a sliding joint (planar and spatial): its keys and the
// PadSpec they give (pad_contact.hpp).
#pragma once

#include "boomdyn/pad_contact.hpp"
#include "boomdyn/physics_type.hpp"

namespace boomdyn {

// The keys stiffness, clearance and damping, titled by `type` (pad, pad_3, ...).
const TypeSchema &padSchema(const std::string &type = "pad");
PadSpec padSpecOf(const ComponentSpec &pad);

} // namespace boomdyn
