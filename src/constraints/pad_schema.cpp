// The pad map's schema, shared by the planar and the spatial sliding joint types.
#include "boomdyn/pad_schema.hpp"
#include "boomdyn/physics_type.hpp"

#include <map>

namespace boomdyn {

const TypeSchema &padSchema(const std::string &type)
{
  // One schema per map name, built on first use (the schema docs list each).
  static std::map<std::string, TypeSchema> schemas;
  auto found = schemas.find(type);
  if (found != schemas.end()) return found->second;
  TypeSchema s;
  s.section = "constraints";
  s.type = type;
  s.summary = "Compliant slide pad with clearance at a sliding joint (the map under a sliding_joint's `" + type +
              "` key): the slider point moves freely across the track within +-clearance and meets an elastic pad on "
              "either side.";
  s.keys = {
      key("stiffness", ValueKind::Number, "N/m", Need::Required, "pad stiffness k_pad").positive(),
      key("clearance", ValueKind::Number, "m", Need::Optional, "free play g on either side of the track")
          .nonNegative()
          .byDefault(0.0),
      key("damping", ValueKind::Number, "N s/m", Need::Optional, "pad damping c_pad while in contact")
          .nonNegative()
          .byDefault(0.0),
  };
  return schemas.emplace(type, std::move(s)).first->second;
}

PadSpec padSpecOf(const ComponentSpec &p)
{
  return PadSpec{p.number("stiffness"), p.number("clearance"), p.number("damping")};
}

} // namespace boomdyn
