// Type `pin` (section constraints): a material point of a body stays at a
// ground point, or at a material point of another body; rotation is free.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/pin.hpp"

namespace boomdyn {

namespace {

void completePin(ComponentSpec &spec, const Scene &scene)
{
  // Default ground point: where the material point starts.
  if (!spec.has("other") && !spec.has("point")) spec.set("point", initialPoint(scene, spec.point()));
}

void buildPin(const ComponentSpec &spec, ModelBuilder &b)
{
  const Body &body = b.body(spec.text("body"));
  const double s = spec.number("at");
  if (spec.has("other")) {
    b.addConstraint(std::make_shared<Pin>(spec.name, body, s, b.body(spec.text("other")), spec.number("other_at")),
                    spec.mark);
    return;
  }
  const Vec2d p = spec.vec2("point");
  b.addConstraint(std::make_shared<Pin>(spec.name, body, s, Vec2(p[0], p[1])), spec.mark);
}

} // namespace

PhysicsType pinType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "pin";
  t.schema.summary = "A material point stays at a ground point, or at a material point of another body; the "
                     "rotation is free.";
  t.schema.keys = {
      bodyKey("body", "the pinned body"),
      atKey("at", "body", "material point of the body"),
      key("other", ValueKind::Body, "", Need::Optional, "second body (pin between two bodies)").unlike("body"),
      atKey("other_at", "other", "material point of the second body").requiredWith("other"),
      key("point", ValueKind::Vec2, "m", Need::Optional, "ground point [x, y] (pin to ground)")
          .derived("where the point starts"),
  };
  t.schema.rules = {
      forbid("angle", "not allowed for a pin (a pin leaves the rotation free; use a clamp or an angle_drive)"),
      forbidIfPresent("other", "point",
                      "not allowed together with 'other' (the pin joins two bodies, not a body to the ground)"),
      forbidIfAbsent("other", "other_at", "only allowed together with 'other'"),
  };
  t.complete = completePin;
  t.build = buildPin;
  return t;
}

} // namespace boomdyn
