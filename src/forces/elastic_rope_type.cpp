// Type `elastic_rope` (section constraints, beside the inextensible `rope`
// it replaces in a scene): an elastic tension-only rope from a point over
// zero, one or two point pulleys to a far point (elastic_rope.hpp). It is a
// force element, not a constraint (no multiplier), but it joins bodies as
// the rope and distance constraints do, so it is listed with them.
// Outputs per rope and step: tension, length, stretch (state channels), and
// with a winch (`winch`: the paid-out length dL0(t)) also payout (dL0(t))
// and winch_power; events: taut / slack
// (direction +1 / -1) at the interpolated crossing.
#include "boomdyn/elastic_rope.hpp"
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace boomdyn {

namespace {

// The time inside the step [t - h, t] at which the stretch crossed zero: the
// cubic Hermite interpolant of the stretch from its values and rates at the
// two ends (exact for a free fall, whose stretch is a parabola), by bisection.
double stretchCrossing(double t, double h, double d0, double r0, double d1, double r1)
{
  auto at = [&](double x) {
    const double x2 = x * x, x3 = x2 * x;
    return (2 * x3 - 3 * x2 + 1) * d0 + (x3 - 2 * x2 + x) * h * r0 + (-2 * x3 + 3 * x2) * d1 + (x3 - x2) * h * r1;
  };
  double a = 0, b = 1;
  if ((at(a) > 0) == (at(b) > 0)) return t; // no sign change of the interpolant: at the step's end
  for (int it = 0; it < 60; ++it) {
    const double m = 0.5 * (a + b);
    ((at(m) > 0) == (at(a) > 0) ? a : b) = m;
  }
  return t - h + 0.5 * (a + b) * h;
}

// The plausible range of a rope (docs/scenes.md, elastic_rope): beyond it
// the numbers describe no rope, and the run would fail far from the cause
// (a "singular" system, or tens of thousands of step cuts on a spring
// 1e10 times stiffer than the boom).
// EA at most 1e12 N (the schema's limit, checked by the reader): a steel
// bar of about 5 m^2 metallic area; the largest wire ropes have about 1e9 N.
constexpr double kMaxRopeEA = 1e12;
// Initial strain (pretension / EA, or (l0 - L0) / L0 with `length`) at most
// 0.2: beyond the breaking elongation of steel (a few %) and fibre ropes
// (about 10-20 %); the linear law T = EA eps means nothing there.
constexpr double kMaxRopeStrain = 0.2;

// The initial strain, from the pretension (relative to EA) or from the
// length: a check across keys, at the build.
void checkRopeStrain(const ComponentSpec &spec, double EA, double L0, double spanned)
{
  const std::string rope = ModelBuilder::where(spec.mark) + "elastic_rope '" + spec.name + "': ";
  const double strain = spec.has("length") ? (spanned - L0) / L0 : spec.numberOr("pretension", 0.0) / EA;
  if (!(strain <= kMaxRopeStrain)) {
    const std::string key = spec.has("length") ? "length" : "pretension";
    throw ModelError(rope + "key '" + key + "': the rope starts stretched by " + numberText(strain) +
                     " of its unstretched length (" +
                     (spec.has("length") ? "spanned " + numberText(spanned) + " m, length " + numberText(L0) + " m"
                                         : "pretension " + numberText(spec.number("pretension")) + " N, EA " +
                                               numberText(EA) + " N") +
                     "): at most " + numberText(kMaxRopeStrain) +
                     ", beyond the breaking elongation of steel and fibre ropes");
  }
}

void buildElasticRope(const ComponentSpec &spec, ModelBuilder &b)
{
  // The points and the keys that place them (for the messages).
  std::vector<RopePath::Point> points{{&b.body(spec.text("from")), spec.number("from_at")}};
  std::vector<std::string> keys{"from_at"};
  for (const char *pulley : {"pulley", "pulley2"})
    if (spec.has(pulley)) {
      points.push_back({&b.body(spec.text(pulley)), spec.number(std::string(pulley) + "_at")});
      keys.push_back(std::string(pulley) + "_at");
    }
  if (spec.has("pulleys")) { // the list form: any number of sheaves, in the order the rope runs over them
    const ComponentSpec &list = spec.map("pulleys");
    for (std::size_t i = 0; list.has(std::to_string(i)); ++i) {
      const ComponentSpec &sheave = list.map(std::to_string(i));
      points.push_back({&b.body(sheave.text("body")), sheave.number("at")});
      keys.push_back("pulleys[" + std::to_string(i) + "].at");
    }
  }
  points.push_back({&b.body(spec.text("to")), spec.number("to_at")});
  keys.push_back("to_at");
  RopePath path(points);
  std::vector<PetscInt> dofs;
  path.coordinates(dofs);
  std::vector<double> q0;
  for (PetscInt d : dofs) q0.push_back(b.bodyCoordinates()[d]);
  const double spanned = path.length(q0.data()), EA = spec.number("EA");
  // Pretension T0 at the initial configuration: (EA/L0)(l0 - L0) = T0.
  const double L0 = spec.has("length") ? spec.number("length") : spanned / (1 + spec.numberOr("pretension", 0.0) / EA);
  if (!(spanned > 0))
    throw ModelError(ModelBuilder::where(spec.mark) + "elastic_rope '" + spec.name +
                     "': its points coincide at t = 0 (spanned length 0)");
  // A segment of zero length has no direction: its force would be NaN.
  if (const int j = path.shortSegment(q0.data()); j >= 0)
    throw ModelError(ModelBuilder::where(spec.mark) + "elastic_rope '" + spec.name + "': key '" + keys[j + 1] +
                     "': the rope's segment from '" + keys[j] + "' to '" + keys[j + 1] +
                     "' has zero length at t = 0 (" +
                     numberText(path.segmentLengths(q0.data())[j]) + " m of " + numberText(spanned) +
                     " m): its direction is undefined; move the point or leave the pulley out");
  checkRopeStrain(spec, EA, L0, spanned);
  // The winch: L0(t) = L0 + dL0(t), and the rope must not be paid in below nothing.
  const TimeFunction payout = spec.has("winch") ? spec.function("winch") : TimeFunction();
  auto rope = std::make_unique<ElasticRope>(spec.name, std::move(path), EA, L0, spec.number("damping"), payout);
  if (rope->hasWinch()) {
    // The least rope length over the whole profile: from t = 0 to the run's
    // end or the profile's own end, whichever is later (a restart may run
    // on), from the time function's bounds (a sine's troughs, a table's
    // knots), not only its end points.
    const Scene &scene = b.scene();
    const double tEnd = std::max({scene.dynamic.t_end, scene.statics.time, payout.endTime(), 0.0});
    double least, most;
    payout.bounds(0.0, tEnd, &least, &most);
    if (!(L0 + least > 0))
      throw ModelError(ModelBuilder::where(spec.mark) + "elastic_rope '" + spec.name + "': key 'winch': the winch " +
                       "hauls in more rope than there is (unstretched length " + numberText(L0) + " m, the winch's " +
                       "least payout " + numberText(least) + " m over t in [0, " + numberText(tEnd) +
                       "] s leaves " + numberText(L0 + least) + " m)");
  }
  const ElasticRope *r = rope.get(); // owned by the Model, which also holds the channels and the source
  b.addItem(std::move(rope));
  // The channels and the event source ask for the state at the same (t, q, v)
  // every step: the rope's state is computed once per (t, q, v).
  struct Memo {
    bool valid = false;
    double t = 0;
    std::vector<double> q, v;
    ElasticRope::State state;
  };
  auto memo = std::make_shared<Memo>();
  auto stateAt = [r, memo, n = dofs.size()](double t, const double *q, const double *v) {
    Memo &m = *memo;
    if (!(m.valid && m.t == t && std::equal(q, q + n, m.q.begin()) && std::equal(v, v + n, m.v.begin()))) {
      m.state = r->state(t, q, v);
      m.t = t, m.q.assign(q, q + n), m.v.assign(v, v + n), m.valid = true;
    }
    return m.state;
  };
  auto channel = [&](const char *quantity, const char *unit, double (*pick)(const ElasticRope::State &)) {
    b.addOutputChannel(OutputChannel::ofTimedState(
        "elastic_rope", spec.name, quantity, unit, dofs,
        [stateAt, pick](double t, const double *q, const double *v) { return pick(stateAt(t, q, v)); }));
  };
  channel("tension", "N", [](const ElasticRope::State &s) { return s.tension; });
  channel("length", "m", [](const ElasticRope::State &s) { return s.length; });
  channel("stretch", "m", [](const ElasticRope::State &s) { return s.stretch; });
  if (r->hasWinch()) { // only with a winch, so that the outputs of ropes without one stay as they were
    channel("payout", "m", [](const ElasticRope::State &s) { return s.payout; });
    channel("winch_power", "W", [](const ElasticRope::State &s) { return s.winchPower; });
  }
  // Slack/taut events: +1 taut, -1 slack.
  struct Last {
    double t = 0;
    ElasticRope::State state;
  };
  auto last = std::make_shared<Last>();
  EventSource source{spec.name, {"taut", "slack"}, dofs, nullptr};
  source.detect = [stateAt, last, name = spec.name](double t, double h, const double *q, const double *v, bool first,
                                                   std::vector<TypeEvent> &events) {
    const ElasticRope::State now = stateAt(t, q, v), &before = last->state;
    if (!first && now.taut != before.taut) {
      double when = t;
      if ((before.stretch > 0) != (now.stretch > 0)) // by length: the stretch crossed zero
        when = stretchCrossing(t, h, before.stretch, before.rate - before.payoutRate, now.stretch,
                               now.rate - now.payoutRate);
      else if (before.force != now.force) // by damping: f crossed zero (linear in the step)
        when = t - h * now.force / (now.force - before.force);
      events.push_back({when, name, now.taut ? "taut" : "slack", now.taut ? 1 : -1});
    }
    last->t = t, last->state = now;
  };
  b.addEventSource(std::move(source));
}

} // namespace

// Sheaves of one rope: 8 coordinates per sheave on a beam element, a
// dense block of (8 n)^2 entries: 5 MB at 100, 51 GB at 10^4.
constexpr int kMaxSheaves = 100;

// One sheave of the list form `pulleys: [{body, at}, ...]`.
const TypeSchema &sheaveSchema()
{
  static const TypeSchema schema = [] {
    TypeSchema s;
    s.section = "constraints";
    s.type = "sheave";
    s.summary = "one point pulley (sheave) of the list `pulleys`, in the order the rope runs over them";
    s.keys = {bodyKey("body", "body that carries the sheave"), atKey("at", "body", "material point of the sheave")};
    return s;
  }();
  return schema;
}

PhysicsType elasticRopeType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "elastic_rope";
  t.schema.summary = "An elastic tension-only wire rope from a point over point pulleys (sheaves) to a far point, "
                     "optionally paid out or hauled in by a winch at its first end: tension (EA/L0)(l - L0) + "
                     "c d(l - L0)/dt while taut, none while slack; slack/taut events.";
  t.schema.keys = {
      bodyKey("from", "body of the rope's first end"),
      atKey("from_at", "from", "material point of the first end"),
      key("pulley", ValueKind::Body, "", Need::Optional, "body that carries the first pulley (a point, no radius)"),
      atKey("pulley_at", "pulley", "material point of the first pulley").requiredWith("pulley"),
      key("pulley2", ValueKind::Body, "", Need::Optional, "body that carries a second pulley, after the first"),
      atKey("pulley2_at", "pulley2", "material point of the second pulley").requiredWith("pulley2"),
      key("pulleys", ValueKind::MapList, "", Need::Optional,
          "sheaves [{body, at}, ...] in the order the rope runs over them (instead of pulley/pulley2)")
          .holding(sheaveSchema())
          .between(1, kMaxSheaves)
          .tooLargeMeans("the rope couples every sheave's body coordinates with every other's, so its Jacobian "
                         "block grows with the square of their number (a real reeving has a few dozen)"),
      bodyKey("to", "body of the rope's far end"),
      atKey("to_at", "to", "material point of the far end"),
      key("EA", ValueKind::Number, "N", Need::Required, "axial stiffness of the rope (metallic area times the rope's "
                                                       "modulus)")
          .positive()
          .atMost(kMaxRopeEA, "a steel bar of 5 m^2; the largest wire ropes have about 1e9 N"),
      key("length", ValueKind::Number, "m", Need::Optional,
          "unstretched length L0; the initial strain (l0 - L0)/L0 at most 0.2")
          .positive()
          .derived("from the pretension and the initial spanned length l0: L0 = l0 / (1 + pretension/EA)"),
      key("pretension", ValueKind::Number, "N", Need::Optional,
          "tension in the initial configuration; at most 0.2 EA (an initial strain beyond the breaking elongation of "
          "steel and fibre ropes is refused)")
          .nonNegative()
          .byDefault(0.0),
      key("damping", ValueKind::Number, "N s/m", Need::Optional,
          "damping c of the tension c d(l - L0)/dt (the stretch rate)")
          .nonNegative()
          .byDefault(0.0),
      key("winch", ValueKind::TimeFunction, "m", Need::Optional,
          "winch at the first end: the rope length dL0(t) it has paid out since t = 0, so that L0(t) = L0 + dL0(t) "
          "(hoisting: decreasing; hoisting at speed v from t0: a ramp to -v (t1 - t0) at t1); L0(t) must stay "
          "positive over the whole profile up to the run's or the profile's end; adds the outputs payout (dL0(t)) "
          "and winch_power")
          .derived("none (L0 fixed)"),
  };
  t.schema.rules = {
      forbidIfPresent("length", "pretension", "not allowed together with 'length' (the pretension sets the length)"),
      forbidIfAbsent("pulley", "pulley2", "only allowed together with 'pulley' (the second pulley follows the first)"),
      forbidIfAbsent("pulley", "pulley_at", "only allowed together with 'pulley'"),
      forbidIfAbsent("pulley2", "pulley2_at", "only allowed together with 'pulley2'"),
      forbidIfPresent("pulleys", "pulley", "not allowed together with 'pulleys' (list every sheave there)"),
      forbidIfPresent("pulleys", "pulley2", "not allowed together with 'pulleys' (list every sheave there)"),
  };
  const std::string reason = "not allowed for an elastic_rope (it names its points with from/from_at, "
                             "pulley/pulley_at, pulley2/pulley2_at or pulleys, to/to_at)";
  for (const char *k : {"body", "at", "point", "angle", "other", "other_at"}) t.schema.rules.push_back(forbid(k, reason));
  t.build = buildElasticRope;
  return t;
}

} // namespace boomdyn
