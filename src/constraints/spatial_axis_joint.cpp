#include "spatial_axis_joint.hpp"

#include "boomdyn/model_builder.hpp"

#include <memory>

namespace boomdyn {

namespace {
Vec3 vec(const Vec3d &a) { return Vec3(a[0], a[1], a[2]); }
} // namespace

AxisJointFrame axisJointFrame(const ComponentSpec &spec, const ModelBuilder &b)
{
  AxisJointFrame f;
  const SpatialBody &body = b.spatialBody(spec.text("body"));
  const double s = spec.number("at");
  f.a = SpatialEnd::onBody(body, s);
  f.Ta = body.initialTriad(s);
  f.ra = body.initialPosition(s);
  f.axis = vec(spec.vec3("axis")).normalized();
  frameAcross(f.axis, f.Ta.col(0), f.n1, f.n2);
  f.Tb = Mat3::Identity();
  if (spec.has("other")) {
    const SpatialBody &ob = b.spatialBody(spec.text("other"));
    f.other = SpatialEnd::onBody(ob, spec.number("other_at"));
    f.Tb = ob.initialTriad(f.other.s);
    f.rb = ob.initialPosition(f.other.s);
  } else {
    f.rb = spec.has("point") ? vec(spec.vec3("point")) : f.ra;
    f.other = SpatialEnd::ground(f.rb);
  }
  return f;
}

std::vector<SpatialDotRow> axisAlignmentRows(const AxisJointFrame &f)
{
  const Vec3 u = f.Ta.transpose() * f.axis;
  std::vector<SpatialDotRow> rows(2);
  rows[0].u = rows[1].u = u;
  rows[0].n1 = rows[1].n1 = Vec3::Zero();
  rows[0].n2 = f.Tb.transpose() * f.n1;
  rows[1].n2 = f.Tb.transpose() * f.n2;
  return rows;
}

SpatialDotRow axisRollRow(const AxisJointFrame &f)
{
  SpatialDotRow row;
  row.u = f.Ta.transpose() * f.n1;
  row.n1 = Vec3::Zero();
  row.n2 = f.Tb.transpose() * f.n2;
  return row;
}

SpatialOffsetRow axisOffsetRow(const AxisJointFrame &f, const Vec3 &direction, const TimeFunction &shift)
{
  SpatialOffsetRow row;
  row.c = f.Tb.transpose() * direction;
  row.base = (f.ra - f.rb).dot(direction);
  row.shift = shift;
  return row;
}

namespace {

void buildAxisSlider(const ComponentSpec &spec, ModelBuilder &b, bool roll)
{
  const AxisJointFrame f = axisJointFrame(spec, b);
  std::vector<SpatialOffsetRow> offsets = {axisOffsetRow(f, f.n1), axisOffsetRow(f, f.n2)};
  const bool driven = spec.has("slide");
  if (driven) offsets.push_back(axisOffsetRow(f, f.axis, spec.function("slide")));
  std::vector<SpatialDotRow> rows = axisAlignmentRows(f);
  if (roll) rows.push_back(axisRollRow(f));
  b.addConstraint(std::make_shared<SpatialJoint>(spec.name, f.a, f.other, false, offsets, rows, driven), spec.mark);
}

void completeAxisSlider(ComponentSpec &spec, const Scene &)
{
  if (!spec.has("axis")) spec.set("axis", Vec3d{0, 0, 1});
}

void axisSliderSchema(TypeSchema &schema, const std::string &type, const std::string &summary)
{
  schema.section = "constraints";
  schema.type = schema.defaultName = type;
  schema.summary = summary;
  schema.keys = {
      bodyKey("body", "the sliding body"),
      atKey("at", "body", "material point of the body on the axis"),
      key("other", ValueKind::Body, "", Need::Optional, "the body the axis is fixed in (default: ground)")
          .unlike("body"),
      atKey("other_at", "other", "material point of the other body whose section carries the axis")
          .requiredWith("other"),
      key("axis", ValueKind::Vec3, "", Need::Optional,
          "direction of the axis in the global axes at t = 0 (any length); it passes through the point 'at' and "
          "turns with the other body")
          .derived("[0, 0, 1]"),
      key("slide", ValueKind::TimeFunction, "m", Need::Optional,
          "prescribed displacement of the point along the axis, relative to the other body, from its position at "
          "t = 0; a number or a time function (a slide drive: one more row)")
          .derived("free slide"),
  };
  const std::string why = "not allowed for a " + type + " (its axis passes through the material point 'at')";
  schema.rules = {
      forbid("point", why),
      forbid("angle", "not allowed for a " + type + " (prescribe the displacement along the axis with 'slide')"),
      forbidIfAbsent("other", "other_at", "only allowed together with 'other'"),
  };
}

void buildCylindrical(const ComponentSpec &spec, ModelBuilder &b) { buildAxisSlider(spec, b, false); }
void buildPrismatic(const ComponentSpec &spec, ModelBuilder &b) { buildAxisSlider(spec, b, true); }

} // namespace

PhysicsType axisSliderType(const std::string &type, const std::string &summary, bool roll)
{
  PhysicsType t;
  t.dimension = 3;
  axisSliderSchema(t.schema, type, summary);
  t.complete = completeAxisSlider;
  t.check = checkJointAxis;
  t.build = roll ? buildPrismatic : buildCylindrical;
  return t;
}

std::optional<SpecIssue> checkJointAxis(const ComponentSpec &spec, const Scene &)
{
  if (!(vec(spec.vec3("axis")).norm() > 0)) return SpecIssue{"axis", "must not be the zero vector"};
  return std::nullopt;
}

} // namespace boomdyn
