// Type `ground_contact` (section constraints, like the elastic rope a force
// element that joins a body to something else, here the ground): a material
// point of a body rests on the horizontal ground line y = level through a
// one-sided spring-damper (ground_contact.hpp), e.g. a payload on the
// ground before a lift-off. Outputs per contact and step: force (>= 0) and
// gap (y - level); events: contact (+1) and lift_off (-1), at the time the
// gap crossed zero (linear interpolation in the step).
#include "boomdyn/ground_contact.hpp"
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

#include <memory>

namespace boomdyn {

namespace {

void buildGroundContact(const ComponentSpec &spec, ModelBuilder &b)
{
  auto contact = std::make_unique<GroundContact>(spec.name, b.body(spec.text("body")), spec.number("at"),
                                                 spec.number("level"), spec.number("stiffness"),
                                                 spec.number("damping"));
  const GroundContact *c = contact.get(); // owned by the Model, which also holds the channels and the source
  std::vector<PetscInt> dofs;
  c->coordinates(dofs);
  // A point that starts inside the ground would be fired out by the spring's
  // stored energy k d^2 / 2: refused beyond ten times the contact's
  // deflection under the whole model's weight (a payload placed at its
  // static penetration is accepted; 1e-9 m of round-off without gravity).
  {
    std::vector<double> q0, v0(dofs.size(), 0.0);
    for (PetscInt d : dofs) q0.push_back(b.bodyCoordinates()[d]);
    const double gap = c->state(q0.data(), v0.data()).gap, k = spec.number("stiffness");
    const double allowed = 10.0 * b.totalMass() * b.gravity().norm() / k + 1e-9;
    if (gap < -allowed)
      throw ModelError(ModelBuilder::where(spec.mark) + "ground_contact '" + spec.name + "': the point at " +
                       numberText(spec.number("at")) + " m of body '" + spec.text("body") + "' starts " +
                       numberText(-gap) + " m below the ground line (key 'level': " + numberText(spec.number("level")) +
                       " m), more than ten times the contact's deflection under the model's whole weight (" +
                       numberText(allowed) + " m): place the body on or above the ground");
  }
  b.addItem(std::move(contact));
  auto channel = [&](const char *quantity, const char *unit, double (*pick)(const GroundContact::State &)) {
    b.addOutputChannel(OutputChannel::ofState("ground_contact", spec.name, quantity, unit, dofs,
                                              [c, pick](const double *q, const double *v) { return pick(c->state(q, v)); }));
  };
  channel("force", "N", [](const GroundContact::State &s) { return s.force; });
  channel("gap", "m", [](const GroundContact::State &s) { return s.gap; });
  auto last = std::make_shared<GroundContact::State>();
  EventSource source{spec.name, {"contact", "lift_off"}, dofs, nullptr};
  source.detect = [c, last, name = spec.name](double t, double h, const double *q, const double *v, bool first,
                                             std::vector<TypeEvent> &events) {
    const GroundContact::State now = c->state(q, v);
    if (!first && now.contact != last->contact) {
      double when = t;
      if ((last->gap < 0) != (now.gap < 0) && now.gap != last->gap) when = t - h * now.gap / (now.gap - last->gap);
      events.push_back({when, name, now.contact ? "contact" : "lift_off", now.contact ? 1 : -1});
    }
    *last = now;
  };
  b.addEventSource(std::move(source));
}

} // namespace

PhysicsType groundContactType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "ground_contact";
  t.schema.summary = "A material point of a body on the horizontal ground line y = level: a one-sided "
                     "spring-damper (force k (level - y) - c y' while below the line and pushing, none after "
                     "lift-off); no friction; contact/lift_off events.";
  t.schema.keys = {
      bodyKey("body", "body whose point touches the ground"),
      atKey("at", "body", "material point that touches the ground"),
      key("level", ValueKind::Number, "m", Need::Required,
          "height y_g of the ground line; the point may start below it by at most ten times the contact's "
          "deflection under the model's whole weight"),
      key("stiffness", ValueKind::Number, "N/m", Need::Required, "contact stiffness k").positive(),
      key("damping", ValueKind::Number, "N s/m", Need::Optional, "contact damping c").nonNegative().byDefault(0.0),
  };
  const std::string reason = "not allowed for a ground_contact (the ground is the line y = level)";
  for (const char *k : {"point", "angle", "other", "other_at"}) t.schema.rules.push_back(forbid(k, reason));
  t.build = buildGroundContact;
  return t;
}

} // namespace boomdyn
