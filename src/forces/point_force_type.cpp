// Type `point_force` (section loads): a force at a material point, in the
// global frame, times a dimensionless scale(t).
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/point_load.hpp"

namespace boomdyn {

namespace {

void completePointForce(ComponentSpec &spec, const Scene &)
{
  if (!spec.has("scale")) spec.set("scale", TimeFunction::constant(1.0));
}

void buildPointForce(const ComponentSpec &spec, ModelBuilder &b)
{
  const Vec2d f = spec.vec2("force");
  b.addItem(std::make_unique<PointForce>(spec.name, b.body(spec.text("body")), spec.number("at"), Vec2(f[0], f[1]),
                                         spec.function("scale")));
}

} // namespace

PhysicsType pointForceType()
{
  PhysicsType t;
  t.schema.section = "loads";
  t.schema.type = "point_force";
  t.schema.defaultName = "force";
  t.schema.summary = "A force at a material point, fixed in direction in the global frame, times scale(t).";
  t.schema.keys = {
      bodyKey("body", "the loaded body"),
      atKey("at", "body", "material point where the force acts"),
      key("force", ValueKind::Vec2, "N", Need::Required, "force [Fx, Fy] in the global frame"),
      key("scale", ValueKind::TimeFunction, "", Need::Optional, "factor on the force; a number or a time function")
          .derived("1"),
  };
  t.complete = completePointForce;
  t.build = buildPointForce;
  return t;
}

} // namespace boomdyn
