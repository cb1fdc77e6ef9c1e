// Type `angle_drive` (section constraints): the tangent of a body at a
// material point points along theta(t).
#include "boomdyn/angle_drive.hpp"
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

namespace boomdyn {

namespace {

void completeAngleDrive(ComponentSpec &spec, const Scene &scene)
{
  if (!spec.has("angle")) spec.set("angle", TimeFunction::constant(bodySpec(scene, spec.text("body")).angle));
}

void buildAngleDrive(const ComponentSpec &spec, ModelBuilder &b)
{
  b.addConstraint(std::make_shared<AngleDrive>(spec.name, b.body(spec.text("body")), spec.number("at"),
                                               spec.function("angle")),
                  spec.mark);
}

} // namespace

PhysicsType angleDriveType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "angle_drive";
  t.schema.summary = "The body axis at a material point points along a prescribed angle theta(t).";
  t.schema.keys = {
      bodyKey("body", "the driven body"),
      atKey("at", "body", "material point whose tangent is driven"),
      key("angle", ValueKind::AngleFunction, "deg", Need::Optional,
          "direction of the tangent, counter-clockwise from x; a number or a time function")
          .derived("the body's initial angle"),
  };
  const std::string reason = "not allowed for an angle_drive (it prescribes only the direction of the body axis)";
  t.schema.rules = {forbid("point", reason), forbid("other", reason), forbid("other_at", reason)};
  t.complete = completeAngleDrive;
  t.build = buildAngleDrive;
  return t;
}

} // namespace boomdyn
