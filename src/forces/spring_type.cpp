// Type `spring` (section springs, which has no `type:` key): a linear
// spring-damper from a material point to another body's point or to a
// ground point.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spring.hpp"

#include <cmath>

namespace boomdyn {

namespace {

void buildSpring(const ComponentSpec &spec, ModelBuilder &b)
{
  Spring::End a{&b.body(spec.text("body")), spec.number("at"), Vec2::Zero()}, end{nullptr, 0.0, Vec2::Zero()};
  if (spec.has("other")) {
    end = Spring::End{&b.body(spec.text("other")), spec.number("other_at"), Vec2::Zero()};
  } else {
    const Vec2d p = spec.vec2("point");
    end.ground = Vec2(p[0], p[1]);
  }
  double rest = spec.numberOr("rest_length", -1.0);
  if (rest < 0) { // the initial distance
    const Spring probe(spec.name, a, end, 1.0, 0.0, 0.0);
    std::vector<PetscInt> dofs;
    probe.coordinates(dofs);
    std::vector<double> vals, zero(dofs.size(), 0.0);
    for (PetscInt d : dofs) vals.push_back(b.bodyCoordinates()[d]);
    EnergyParts e;
    probe.energy(AssemblyContext{}, ItemValues{vals.data(), zero.data(), zero.data(), nullptr}, e);
    rest = std::sqrt(2.0 * e.strain); // with k = 1 and L0 = 0 the energy is l^2 / 2
  }
  b.addItem(std::make_unique<Spring>(spec.name, a, end, spec.number("stiffness"), rest, spec.number("damping")));
}

} // namespace

PhysicsType springType()
{
  PhysicsType t;
  t.schema.section = "springs";
  t.schema.type = "spring";
  t.schema.defaultName = "spring";
  t.schema.summary = "A linear spring-damper from a material point to a point of another body or to a ground point.";
  t.schema.keys = {
      bodyKey("body", "body of the first end"),
      atKey("at", "body", "material point of the first end"),
      key("other", ValueKind::Body, "", Need::Optional, "body of the second end (spring between two bodies)"),
      atKey("other_at", "other", "material point of the second end").requiredWith("other"),
      key("point", ValueKind::Vec2, "m", Need::Optional, "ground point [x, y] of the second end")
          .requiredWithout("other"),
      key("stiffness", ValueKind::Number, "N/m", Need::Required, "spring constant").positive(),
      key("rest_length", ValueKind::Number, "m", Need::Optional, "unstretched length").nonNegative().derived(
          "the initial distance"),
      key("damping", ValueKind::Number, "N s/m", Need::Optional, "damping constant").nonNegative().byDefault(0.0),
  };
  t.schema.rules = {
      forbidIfPresent("other", "point", "not allowed together with 'other' (the spring joins two bodies)"),
      forbidIfAbsent("other", "other_at", "only allowed together with 'other'"),
  };
  t.build = buildSpring;
  return t;
}

} // namespace boomdyn
