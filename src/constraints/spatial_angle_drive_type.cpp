// Type `angle_drive` of spatial scenes (section constraints, dimension 3):
// turns a body about an axis by a prescribed angle theta(t), relative to the
// ground or to another body; one row (spatial_joint.hpp). The driven
// direction is the section's x axis at `at` (its part across the drive
// axis; the y axis if x lies along it); theta is measured about the axis
// from `zero`, fixed in the other body or the ground. With a revolute_joint
// about the same axis this is the slewing or luffing drive of a crane.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_joint.hpp"

#include <cmath>

namespace boomdyn {

namespace {

Vec3 vec(const Vec3d &a) { return Vec3(a[0], a[1], a[2]); }

void completeSpatialAngleDrive(ComponentSpec &spec, const Scene &)
{
  if (!spec.has("axis")) spec.set("axis", Vec3d{0, 0, 1});
  if (!spec.has("angle")) spec.set("angle", TimeFunction::constant(0.0));
}

std::optional<SpecIssue> checkSpatialAngleDrive(const ComponentSpec &spec, const Scene &)
{
  if (!(vec(spec.vec3("axis")).norm() > 0)) return SpecIssue{"axis", "must not be the zero vector"};
  if (spec.has("zero")) {
    const Vec3 a = vec(spec.vec3("axis")).normalized(), z = vec(spec.vec3("zero"));
    if (!((z - z.dot(a) * a).norm() > 1e-9 * z.norm()) || !(z.norm() > 0))
      return SpecIssue{"zero", "must have a part across 'axis' (the angle is measured about the axis from it)"};
  }
  return std::nullopt;
}

void buildSpatialAngleDrive(const ComponentSpec &spec, ModelBuilder &b)
{
  const SpatialBody &body = b.spatialBody(spec.text("body"));
  const double s = spec.number("at");
  const Vec3 axis = vec(spec.vec3("axis")).normalized();
  const Mat3 Ta = body.initialTriad(s);
  // The driven direction: the section x axis across the drive axis (or y).
  Vec3 f = Ta.col(0) - Ta.col(0).dot(axis) * axis;
  if (f.norm() < 1e-6) f = Ta.col(1) - Ta.col(1).dot(axis) * axis;
  f.normalize();
  Vec3 n1, n2;
  frameAcross(axis, spec.has("zero") ? vec(spec.vec3("zero")) : f, n1, n2);
  SpatialEnd other = SpatialEnd::ground(Vec3::Zero());
  Mat3 Tb = Mat3::Identity();
  if (spec.has("other")) {
    const SpatialBody &ob = b.spatialBody(spec.text("other"));
    other = SpatialEnd::onBody(ob, spec.number("other_at"));
    Tb = ob.initialTriad(other.s);
  }
  SpatialDotRow row;
  row.u = Ta.transpose() * f;
  row.n1 = Tb.transpose() * n1;
  row.n2 = Tb.transpose() * n2;
  row.theta = spec.function("angle");
  b.addConstraint(std::make_shared<SpatialJoint>(spec.name, SpatialEnd::onBody(body, s), other, false,
                                                 std::vector<SpatialDotRow>{row}, true),
                  spec.mark);
}

} // namespace

PhysicsType spatialAngleDriveType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "angle_drive";
  t.schema.summary = "Turns a body about an axis by a prescribed angle theta(t) relative to the ground or another "
                     "body (one row; pair it with a revolute_joint about the same axis).";
  t.schema.keys = {
      bodyKey("body", "the driven body"),
      atKey("at", "body", "material point whose section x axis is the driven direction"),
      key("other", ValueKind::Body, "", Need::Optional, "the body the angle is measured against (default: ground)")
          .unlike("body"),
      atKey("other_at", "other", "material point of the other body").requiredWith("other"),
      key("axis", ValueKind::Vec3, "", Need::Optional,
          "drive axis in the global axes at t = 0 (any length), fixed in the other body or the ground")
          .derived("[0, 0, 1]"),
      key("zero", ValueKind::Vec3, "", Need::Optional,
          "direction across the axis (global axes at t = 0) from which the angle is measured")
          .derived("the driven direction at t = 0"),
      key("angle", ValueKind::AngleFunction, "deg", Need::Optional,
          "angle of the driven direction about the axis, from 'zero'; a number or a time function")
          .derived("0"),
  };
  t.schema.rules = {
      forbid("point", "not allowed for an angle_drive (it prescribes only a rotation)"),
      forbidIfAbsent("other", "other_at", "only allowed together with 'other'"),
  };
  t.complete = completeSpatialAngleDrive;
  t.check = checkSpatialAngleDrive;
  t.build = buildSpatialAngleDrive;
  return t;
}

} // namespace boomdyn
