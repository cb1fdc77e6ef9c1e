// Type `clamp` (section constraints): holds a material point of a body at a
// ground point with a prescribed axis direction. Built as a Pin to ground
// ("<name>.pin") and an AngleDrive ("<name>.angle").
#include "boomdyn/angle_drive.hpp"
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/pin.hpp"

namespace boomdyn {

namespace {

void completeClamp(ComponentSpec &spec, const Scene &scene)
{
  // Default: the point stays where it starts, at the body's initial angle.
  if (!spec.has("point")) spec.set("point", initialPoint(scene, spec.point()));
  if (!spec.has("angle")) spec.set("angle", TimeFunction::constant(bodySpec(scene, spec.text("body")).angle));
}

void buildClamp(const ComponentSpec &spec, ModelBuilder &b)
{
  const Body &body = b.body(spec.text("body"));
  const double s = spec.number("at");
  const Vec2d p = spec.vec2("point");
  b.addConstraint(std::make_shared<Pin>(spec.name + ".pin", body, s, Vec2(p[0], p[1])), spec.mark);
  b.addConstraint(std::make_shared<AngleDrive>(spec.name + ".angle", body, s, spec.function("angle")), spec.mark);
}

} // namespace

PhysicsType clampType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "clamp";
  t.schema.summary = "Holds a material point at a ground point with a prescribed axis direction (a pin to ground "
                     "plus an angle_drive).";
  t.schema.keys = {
      bodyKey("body", "the clamped body"),
      atKey("at", "body", "material point of the body that is held"),
      key("point", ValueKind::Vec2, "m", Need::Optional, "ground point [x, y]")
          .derived("where the point starts"),
      key("angle", ValueKind::AngleFunction, "deg", Need::Optional,
          "direction of the body axis at the point, counter-clockwise from x; a number or a time function")
          .derived("the body's initial angle"),
  };
  const std::string reason = "not allowed for a clamp (a clamp holds a body to the ground; join two bodies with a pin)";
  t.schema.rules = {forbid("other", reason), forbid("other_at", reason)};
  t.complete = completeClamp;
  t.build = buildClamp;
  return t;
}

} // namespace boomdyn
