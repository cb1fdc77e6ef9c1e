// Type `point_moment` (section loads, spatial scenes): a moment at a
// material point, fixed in the global axes (`moment`) or following the
// section (`follower_moment`, in section axes), times scale(t)
// (spatial_point_load.hpp).
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_point_load.hpp"

namespace boomdyn {

namespace {

void completeSpatialPointMoment(ComponentSpec &spec, const Scene &)
{
  if (!spec.has("scale")) spec.set("scale", TimeFunction::constant(1.0));
}

void buildSpatialPointMoment(const ComponentSpec &spec, ModelBuilder &b)
{
  SpatialPointLoad::Parts parts;
  const Vec3d m = spec.vec3(spec.has("moment") ? "moment" : "follower_moment");
  (spec.has("moment") ? parts.moment : parts.followerMoment) = Vec3(m[0], m[1], m[2]);
  b.addItem(std::make_unique<SpatialPointLoad>(spec.name, b.spatialBody(spec.text("body")), spec.number("at"), parts,
                                               spec.function("scale")));
}

} // namespace

PhysicsType spatialPointMomentType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "loads";
  t.schema.type = "point_moment";
  t.schema.defaultName = "moment";
  t.schema.summary = "A moment at a material point, fixed in the global axes or following the section, times "
                     "scale(t).";
  t.schema.keys = {
      bodyKey("body", "the loaded body"),
      atKey("at", "body", "material point where the moment acts"),
      key("moment", ValueKind::Vec3, "N m", Need::Optional, "moment [Mx, My, Mz] in the global axes")
          .requiredWithout("follower_moment"),
      key("follower_moment", ValueKind::Vec3, "N m", Need::Optional,
          "moment in the section axes at the point: it turns with the body"),
      key("scale", ValueKind::TimeFunction, "", Need::Optional, "factor on the moment; a number or a time function")
          .derived("1"),
  };
  t.schema.rules = {forbidIfPresent("moment", "follower_moment",
                                    "not allowed together with 'moment' (give one point_moment per kind)")};
  t.complete = completeSpatialPointMoment;
  t.build = buildSpatialPointMoment;
  return t;
}

} // namespace boomdyn
