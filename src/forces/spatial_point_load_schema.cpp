#include "spatial_point_load_schema.hpp"

#include "boomdyn/model_builder.hpp"
#include "boomdyn/spatial_point_load.hpp"

namespace boomdyn {

namespace {

Vec3 vecOr(const ComponentSpec &spec, const std::string &key)
{
  if (!spec.has(key)) return Vec3::Zero();
  const Vec3d a = spec.vec3(key);
  return Vec3(a[0], a[1], a[2]);
}

void completeSpatialPointLoad(ComponentSpec &spec, const Scene &)
{
  if (!spec.has("scale")) spec.set("scale", TimeFunction::constant(1.0));
}

// Each type's schema admits only its own two vectors; the others stay zero.
void buildSpatialPointLoad(const ComponentSpec &spec, ModelBuilder &b)
{
  SpatialPointLoad::Parts parts;
  parts.force = vecOr(spec, "force");
  parts.followerForce = vecOr(spec, "follower_force");
  parts.moment = vecOr(spec, "moment");
  parts.followerMoment = vecOr(spec, "follower_moment");
  b.addItem(std::make_unique<SpatialPointLoad>(spec.name, b.spatialBody(spec.text("body")), spec.number("at"), parts,
                                               spec.function("scale")));
}

} // namespace

PhysicsType spatialPointLoadType(const SpatialPointLoadWords &w)
{
  const std::string q = w.quantity, follower = "follower_" + q;
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "loads";
  t.schema.type = w.type;
  t.schema.defaultName = w.defaultName;
  t.schema.summary = "A " + q + " at a material point, fixed in the global axes or following the section, times "
                     "scale(t).";
  t.schema.keys = {
      bodyKey("body", "the loaded body"),
      atKey("at", "body", "material point where the " + q + " acts"),
      key(q, ValueKind::Vec3, w.unit, Need::Optional, q + " " + w.components + " in the global axes")
          .requiredWithout(follower),
      key(follower, ValueKind::Vec3, w.unit, Need::Optional, w.followerHelp),
      key("scale", ValueKind::TimeFunction, "", Need::Optional,
          "factor on the " + q + "; a number or a time function")
          .derived("1"),
  };
  t.schema.rules = {forbidIfPresent(q, follower,
                                    "not allowed together with '" + q + "' (give one " + w.type + " per kind)")};
  t.complete = completeSpatialPointLoad;
  t.build = buildSpatialPointLoad;
  return t;
}

} // namespace boomdyn
