// Type `point_force` of spatial scenes (section loads, dimension 3): a force
// at a material point, fixed in the global axes (`force`) or following the
// section (`follower_force`, in section axes), times scale(t)
// (spatial_point_load.hpp).
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_point_load.hpp"

namespace boomdyn {

namespace {

Vec3 vecOr(const ComponentSpec &spec, const std::string &key)
{
  if (!spec.has(key)) return Vec3::Zero();
  const Vec3d a = spec.vec3(key);
  return Vec3(a[0], a[1], a[2]);
}

void completeSpatialPointForce(ComponentSpec &spec, const Scene &)
{
  if (!spec.has("scale")) spec.set("scale", TimeFunction::constant(1.0));
}

void buildSpatialPointForce(const ComponentSpec &spec, ModelBuilder &b)
{
  SpatialPointLoad::Parts parts;
  parts.force = vecOr(spec, "force");
  parts.followerForce = vecOr(spec, "follower_force");
  b.addItem(std::make_unique<SpatialPointLoad>(spec.name, b.spatialBody(spec.text("body")), spec.number("at"), parts,
                                               spec.function("scale")));
}

} // namespace

PhysicsType spatialPointForceType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "loads";
  t.schema.type = "point_force";
  t.schema.defaultName = "force";
  t.schema.summary = "A force at a material point, fixed in the global axes or following the section, times "
                     "scale(t).";
  t.schema.keys = {
      bodyKey("body", "the loaded body"),
      atKey("at", "body", "material point where the force acts"),
      key("force", ValueKind::Vec3, "N", Need::Optional, "force [Fx, Fy, Fz] in the global axes")
          .requiredWithout("follower_force"),
      key("follower_force", ValueKind::Vec3, "N", Need::Optional,
          "force in the section axes at the point: it turns with the body (a follower load)"),
      key("scale", ValueKind::TimeFunction, "", Need::Optional, "factor on the force; a number or a time function")
          .derived("1"),
  };
  t.schema.rules = {forbidIfPresent("force", "follower_force",
                                    "not allowed together with 'force' (give one point_force per kind)")};
  t.complete = completeSpatialPointForce;
  t.build = buildSpatialPointForce;
  return t;
}

} // namespace boomdyn
