// The cross-section keys shared by the body types (ancf_beam_type.cpp,
// rigid_body_type.cpp): the two forms of a section (stiffnesses, or
// material and geometry) and the products that turn the second into the
// first.
#pragma once

#include "boomdyn/physics_type.hpp"

namespace boomdyn::body_section {

// The section schema of a flexible body (EA, EI, rhoA or E, A, I, rho) or,
// with stiffness false, of a rigid body (rhoA or rho, A).
TypeSchema schema(const std::string &bodyType, bool stiffness);

// A product of the material form (rho * A, ...) that overflows or
// underflows, reported at the key of its first factor.
std::optional<SpecIssue> checkProducts(const ComponentSpec &body, bool stiffness);

// The section in the stiffness form, whichever form the scene used.
SectionSpec fromSpec(const ComponentSpec &section, bool stiffness);

// The keys every body type has (name, length, origin, angle, section) into
// the typed view; the caller sets what is its own (elements).
void describeBody(const ComponentSpec &spec, BodySpec::Type type, BodySpec &body);

} // namespace boomdyn::body_section
