// Type `point_mass` (section masses, which has no `type:` key): a
// concentrated mass at a material point of an ANCF beam, with its weight.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/point_load.hpp"
#include "boomdyn/rigid_body.hpp"

namespace boomdyn {

namespace {

void buildPointMass(const ComponentSpec &spec, ModelBuilder &b)
{
  const Body &body = b.body(spec.text("body"));
  // PointMass uses the linear centerline of ANCF beams (no centripetal term).
  if (dynamic_cast<const RigidBody *>(&body))
    throw ModelError(ModelBuilder::where(spec.mark) + "point mass '" + spec.name + "' on rigid body '" + body.name() +
                     "': not supported; add its mass to the body's section instead");
  b.addItem(std::make_unique<PointMass>(spec.name, body, spec.number("at"), spec.number("mass"), b.gravity()));
}

} // namespace

PhysicsType pointMassType()
{
  PhysicsType t;
  t.schema.section = "masses";
  t.schema.type = "point_mass";
  t.schema.defaultName = "mass";
  t.schema.summary = "A concentrated mass at a material point of an ANCF beam (with its weight under gravity).";
  t.schema.keys = {
      bodyKey("body", "the body that carries the mass (an ANCF beam)"),
      atKey("at", "body", "material point of the mass"),
      key("mass", ValueKind::Number, "kg", Need::Required, "the mass").positive(),
  };
  t.build = buildPointMass;
  return t;
}

} // namespace boomdyn
