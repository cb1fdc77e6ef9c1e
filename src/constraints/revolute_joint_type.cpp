// Type `revolute_joint` (section constraints, spatial scenes): a hinge. The
// material point stays at a ground point or at a material point of another
// body (3 rows) and the hinge axis, fixed in both, stays common (2 rows: the
// axis in body a is normal to two directions across it fixed in body b or
// the ground); the rotation about the axis is free (spatial_joint.hpp).
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_joint.hpp"
#include "spatial_axis_joint.hpp"

namespace boomdyn {

namespace {

void completeRevolute(ComponentSpec &spec, const Scene &scene)
{
  if (!spec.has("other") && !spec.has("point")) spec.set("point", initialPoint3(scene, spec.point()));
  if (!spec.has("axis")) spec.set("axis", Vec3d{0, 0, 1});
}

void buildRevolute(const ComponentSpec &spec, ModelBuilder &b)
{
  const AxisJointFrame f = axisJointFrame(spec, b);
  b.addConstraint(std::make_shared<SpatialJoint>(spec.name, f.a, f.other, true, axisAlignmentRows(f)), spec.mark);
}

} // namespace

PhysicsType revoluteJointType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "revolute_joint";
  t.schema.summary = "A hinge: a material point stays at a ground point, or at a material point of another body, "
                     "and the bodies turn only about the common axis.";
  t.schema.keys = {
      bodyKey("body", "the hinged body"),
      atKey("at", "body", "material point of the body on the hinge axis"),
      key("other", ValueKind::Body, "", Need::Optional, "second body (hinge between two bodies)").unlike("body"),
      atKey("other_at", "other", "material point of the second body").requiredWith("other"),
      key("point", ValueKind::Vec3, "m", Need::Optional, "ground point [x, y, z] on the axis (hinge to ground)")
          .derived("where the point starts"),
      key("axis", ValueKind::Vec3, "", Need::Optional,
          "direction of the hinge axis in the global axes at t = 0 (any length); it turns with the bodies")
          .derived("[0, 0, 1]"),
  };
  t.schema.rules = {
      forbidIfPresent("other", "point", "not allowed together with 'other' (the hinge joins two bodies)"),
      forbidIfAbsent("other", "other_at", "only allowed together with 'other'"),
  };
  t.complete = completeRevolute;
  t.check = checkJointAxis;
  t.build = buildRevolute;
  return t;
}

} // namespace boomdyn
