// Type `point_mass` (section masses, which has no `type:` key): a
// concentrated mass at a material point of an ANCF beam or on the axis of a
// rigid body (a payload = rigid body + masses), with its weight; with
// `release_at` the mass leaves the system at that time (quick release:
// inertia and weight gone, velocities unchanged; the integrator lands a
// step there and restarts with consistent accelerations) and the event
// `release` is written to /type_events.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/point_load.hpp"
#include "boomdyn/rigid_body.hpp"

namespace boomdyn {

namespace {

void buildPointMass(const ComponentSpec &spec, ModelBuilder &b)
{
  const Body &body = b.body(spec.text("body"));
  Release release;
  if (spec.has("release_at")) release.at = spec.number("release_at");
  const double s = spec.number("at"), mass = spec.number("mass");
  std::unique_ptr<WorkItem> item;
  if (dynamic_cast<const RigidBody *>(&body)) // nonlinear centerline: its own exact kernel
    item = std::make_unique<RigidPointMass>(spec.name, body, s, mass, b.gravity(), release);
  else
    item = std::make_unique<PointMass>(spec.name, body, s, mass, b.gravity(), release);
  std::vector<PetscInt> dofs;
  item->coordinates(dofs);
  b.addItem(std::move(item));
  if (!spec.has("release_at")) return;
  // The release as a type event, at the breakpoint the step landed on.
  EventSource source{spec.name, {"release"}, dofs, nullptr};
  source.detect = [at = release.at, name = spec.name, done = std::make_shared<bool>(false)](
                      double t, double, const double *, const double *, bool first, std::vector<TypeEvent> &events) {
    if (first) *done = t >= at; // a restarted run after the release
    else if (!*done && t >= at) {
      events.push_back({at, name, "release", -1});
      *done = true;
    }
  };
  b.addEventSource(std::move(source));
}

} // namespace

PhysicsType pointMassType()
{
  PhysicsType t;
  t.schema.section = "masses";
  t.schema.type = "point_mass";
  t.schema.defaultName = "mass";
  t.schema.summary = "A concentrated mass at a material point of an ANCF beam or on a rigid body's axis (with its "
                     "weight under gravity), optionally released at a given time.";
  t.schema.keys = {
      bodyKey("body", "the body that carries the mass (an ANCF beam or a rigid body)"),
      atKey("at", "body", "material point of the mass"),
      key("mass", ValueKind::Number, "kg", Need::Required, "the mass").positive(),
      key("release_at", ValueKind::Number, "s", Need::Optional,
          "quick release: from this time on the mass and its weight are gone (velocities unchanged); event "
          "'release' in /type_events")
          .positive()
          .derived("never"),
  };
  t.build = buildPointMass;
  return t;
}

} // namespace boomdyn
