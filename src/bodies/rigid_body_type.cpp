// Type `rigid` (section bodies): a rigid bar with the centerline of a beam,
// so that joints, pins, drives, loads and sensors treat it like one.
#include "body_section.hpp"

#include "boomdyn/model_builder.hpp"
#include "boomdyn/rigid_body.hpp"

namespace boomdyn {

namespace {

void describeRigidBody(const ComponentSpec &spec, BodySpec &b)
{
  body_section::describeBody(spec, BodySpec::Type::Rigid, b);
  b.elements = 1; // no mesh
}

std::optional<SpecIssue> checkRigidBody(const ComponentSpec &spec, const Scene &)
{
  return body_section::checkProducts(spec, false);
}

void buildRigidBody(const BodySpec &b, BodyBuilder &builder)
{
  // Mass from the section's mass per length; EA and EI play no part.
  auto owned = std::make_unique<RigidBody>(b.name, b.length, b.section.rhoA * b.length, Vec2(b.origin[0], b.origin[1]),
                                           b.angle, builder.firstCoordinate());
  const RigidBody &body = *owned;
  builder.addBody(std::move(owned));
  builder.addItem(std::make_unique<RigidBodyItem>(body, builder.gravity()));
}

} // namespace

PhysicsType rigidBodyType()
{
  static const TypeSchema section = body_section::schema("rigid", false);
  PhysicsType t;
  t.schema.section = "bodies";
  t.schema.type = t.schema.defaultName = "rigid";
  t.schema.summary = "A rigid bar: the same centerline as a beam, without deformation.";
  t.schema.keys = {
      key("length", ValueKind::Number, "m", Need::Required, "length").positive(),
      key("origin", ValueKind::Vec2, "m", Need::Optional, "initial position of the start (s = 0)").derived("[0, 0]"),
      key("angle", ValueKind::Angle, "deg", Need::Optional, "initial direction of the axis, counter-clockwise from x")
          .byDefault(0),
      key("section", ValueKind::Map, "", Need::Required, "mass per length").holding(section),
  };
  t.schema.rules = {forbid("elements", "not allowed for a rigid body (it has no mesh)")};
  t.check = checkRigidBody;
  t.bodyKind = BodySpec::Type::Rigid;
  t.describeBody = describeRigidBody;
  t.buildBody = buildRigidBody;
  return t;
}

} // namespace boomdyn
