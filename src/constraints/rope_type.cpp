// Type `rope` (section constraints): an inextensible rope from a point over
// a pulley to a third point, L - |r_from - r_pulley| - |r_pulley - r_to| = 0.
// Output: its tension, minus the multiplier of its row.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/rope.hpp"

namespace boomdyn {

namespace {

void buildRope(const ComponentSpec &spec, ModelBuilder &b)
{
  const Rope::Point P{&b.body(spec.text("from")), spec.number("from_at")},
      Q{&b.body(spec.text("pulley")), spec.number("pulley_at")}, R{&b.body(spec.text("to")), spec.number("to_at")};
  double length = spec.numberOr("length", 0.0);
  const Rope probe(spec.name, P, Q, R, 0.0);
  std::vector<PetscInt> dofs;
  probe.coordinates(dofs);
  std::vector<double> vals;
  for (PetscInt d : dofs) vals.push_back(b.bodyCoordinates()[d]);
  // A segment of zero length has no direction: C_q would be NaN.
  if (const int j = probe.path().shortSegment(vals.data()); j >= 0) {
    const char *keys[] = {"from_at", "pulley_at", "to_at"};
    throw ModelError(ModelBuilder::where(spec.mark) + "rope '" + spec.name + "': key '" + keys[j + 1] +
                     "': the rope's segment from '" + keys[j] + "' to '" + keys[j + 1] +
                     "' has zero length at t = 0 (" + numberText(probe.path().segmentLengths(vals.data())[j]) +
                     " m): its direction is undefined; move the point");
  }
  if (length <= 0) length = probe.spannedLength(vals.data()); // the rope is taut in the initial configuration
  const ConstraintItem &item = b.addConstraint(std::make_shared<Rope>(spec.name, P, Q, R, length), spec.mark);
  // C = L - l1 - l2: a pulling extension rope has a negative multiplier; a
  // positive one is the retraction rope's pull (rope_tensions.hpp).
  b.addOutputChannel(
      OutputChannel::ofMultiplier("rope", spec.name, "tension", "N", item.firstRow() - b.numCoordinates(), -1.0));
}

} // namespace

PhysicsType ropeType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "rope";
  t.schema.summary = "An inextensible rope from a point over a pulley point to a third point: an extension/retraction "
                     "rope pair idealized as one bilateral constraint (force > 0: the extension rope pulls; < 0: the "
                     "retraction rope pulls).";
  t.schema.keys = {
      bodyKey("from", "body of the rope's first end"),
      atKey("from_at", "from", "material point of the first end"),
      bodyKey("pulley", "body that carries the pulley"),
      atKey("pulley_at", "pulley", "material point of the pulley"),
      bodyKey("to", "body of the rope's far end"),
      atKey("to_at", "to", "material point of the far end"),
      key("length", ValueKind::Number, "m", Need::Optional, "rope length").positive().derived(
          "the initial spanned length (taut)"),
  };
  const std::string reason =
      "not allowed for a rope (it names its points with from/from_at, pulley/pulley_at, to/to_at)";
  for (const char *k : {"body", "at", "point", "angle", "other", "other_at"}) t.schema.rules.push_back(forbid(k, reason));
  t.build = buildRope;
  return t;
}

} // namespace boomdyn
