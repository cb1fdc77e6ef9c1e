// Type `spherical_joint` (section constraints, spatial scenes): a material
// point of a body stays at a ground point or at a material point of
// another body; all rotations are free (3 rows, spatial_joint.hpp).
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_joint.hpp"

namespace boomdyn {

namespace {

void completeSpherical(ComponentSpec &spec, const Scene &scene)
{
  if (!spec.has("other") && !spec.has("point")) spec.set("point", initialPoint3(scene, spec.point()));
}

void buildSpherical(const ComponentSpec &spec, ModelBuilder &b)
{
  const SpatialEnd a = SpatialEnd::onBody(b.spatialBody(spec.text("body")), spec.number("at"));
  SpatialEnd other;
  if (spec.has("other")) other = SpatialEnd::onBody(b.spatialBody(spec.text("other")), spec.number("other_at"));
  else {
    const Vec3d p = spec.vec3("point");
    other = SpatialEnd::ground(Vec3(p[0], p[1], p[2]));
  }
  b.addConstraint(std::make_shared<SpatialJoint>(spec.name, a, other, true, std::vector<SpatialDotRow>{}), spec.mark);
}

} // namespace

PhysicsType sphericalJointType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "spherical_joint";
  t.schema.summary = "A material point stays at a ground point, or at a material point of another body; all "
                     "rotations are free (ball joint).";
  t.schema.keys = {
      bodyKey("body", "the joined body"),
      atKey("at", "body", "material point of the body"),
      key("other", ValueKind::Body, "", Need::Optional, "second body (joint between two bodies)").unlike("body"),
      atKey("other_at", "other", "material point of the second body").requiredWith("other"),
      key("point", ValueKind::Vec3, "m", Need::Optional, "ground point [x, y, z] (joint to ground)")
          .derived("where the point starts"),
  };
  t.schema.rules = {
      forbidIfPresent("other", "point", "not allowed together with 'other' (the joint joins two bodies)"),
      forbidIfAbsent("other", "other_at", "only allowed together with 'other'"),
  };
  t.complete = completeSpherical;
  t.build = buildSpherical;
  return t;
}

} // namespace boomdyn
