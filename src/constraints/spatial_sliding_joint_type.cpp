// Type `sliding_joint` of spatial scenes (section constraints, dimension 3):
// a point of the slider body moves along the deformable axis of a spatial
// beam (spatial_sliding_joint.hpp). Adds the slack coordinate s, the
// reactions as output channels in the track's section frame, and the
// post-step hook that moves the contact point between track elements (or
// stops the run when the slider leaves its track). With `pad` the two
// lateral position rows give way to compliant pads with clearance along the
// track's section directions d2 and d3 (PadContact on SpatialPadGap); `pad_3`
// gives the d3 pad its own values.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/pad_schema.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/slack_coordinate.hpp"
#include "boomdyn/spatial_sliding_joint.hpp"


namespace boomdyn {

namespace {

// `rotation`: which rotation rows the joint adds to the three position rows.
enum class SleeveRotation { Free, Aligned, Locked };

SleeveRotation rotationOf(const ComponentSpec &spec)
{
  const std::string r = spec.has("rotation") ? spec.text("rotation") : "free";
  return r == "locked" ? SleeveRotation::Locked : r == "aligned" ? SleeveRotation::Aligned : SleeveRotation::Free;
}

std::optional<SpecIssue> checkSpatialSlidingJoint(const ComponentSpec &spec, const Scene &scene)
{
  if (spec.has("rotation")) {
    const std::string &r = spec.text("rotation");
    if (r != "free" && r != "aligned" && r != "locked")
      return SpecIssue{"rotation", "must be free, aligned or locked (got '" + r + "')"};
  }
  const BodySpec &track = bodySpec(scene, spec.text("track"));
  if (track.type != BodySpec::Type::SpatialAncfBeam)
    return SpecIssue{"track", "'" + track.name + "' is not an ancf_beam: a sliding joint runs along a beam's axis"};
  return std::nullopt;
}

// The slack coordinate starts where the slider point projects onto the
// (straight) initial track.
void addSpatialSlack(const ComponentSpec &spec, ModelBuilder &b)
{
  const SpatialBody &track = b.spatialBody(spec.text("track")), &slider = b.spatialBody(spec.text("body"));
  const Vec3 origin = track.initialPosition(0.0), axis = track.initialTriad(0.0).col(0);
  const double s0 = (slider.initialPosition(spec.number("at")) - origin).dot(axis);
  addSlackCoordinate(spec, b, track, s0);
}

// The reactions on the slider in the track's section frame at s are the
// multipliers themselves (spatial_sliding_joint.hpp): force lambda_k along
// d_k; moments lambda_A2 about d3, -lambda_A3 about d2; torque lambda_R.
// A padded direction's force is the pad's (PadContact::state, the force on
// the slider along d_k), read from the watched coordinates: both bodies
// whole, then s (the contact point moves between track elements).
struct SpatialPadWatch {
  std::vector<PetscInt> watched;
  PetscInt sliderOffset = 0;
};

SpatialPadWatch spatialPadWatch(const SpatialSlidingJoint &joint)
{
  SpatialPadWatch w;
  for (const SpatialBody *body : {static_cast<const SpatialBody *>(&joint.track()), &joint.slider()}) {
    if (body == &joint.slider()) w.sliderOffset = static_cast<PetscInt>(w.watched.size());
    for (PetscInt k = 0; k < body->numCoordinates(); ++k) w.watched.push_back(body->firstCoordinate() + k);
  }
  w.watched.push_back(joint.slackIndex());
  return w;
}

// The joint's coordinates (coordinates() order) picked from the watched values.
std::vector<double> padLocal(const SpatialSlidingJoint &joint, const SpatialPadWatch &w, const double *x)
{
  std::vector<PetscInt> dofs;
  joint.coordinates(dofs);
  std::vector<double> out(dofs.size());
  const SpatialLocation &tl = joint.trackLocation();
  const PetscInt t0 = joint.track().firstCoordinate(), b0 = joint.slider().firstCoordinate();
  for (int i = 0; i < tl.count; ++i) out[i] = x[dofs[i] - t0];
  for (std::size_t i = tl.count; i + 1 < dofs.size(); ++i) out[i] = x[w.sliderOffset + dofs[i] - b0];
  out.back() = x[w.watched.size() - 1];
  return out;
}

// Per pad every step: force (on the slider along d_k, N; also the joint's
// force_k), penetration (|g_k| - clearance: > 0 in contact) and side.
void addPadOutputs(std::shared_ptr<const SpatialSlidingJoint> joint, const PadContact *pad, int k, ModelBuilder &b)
{
  const SpatialPadWatch w = spatialPadWatch(*joint);
  auto state = [joint, pad, w](const double *q, const double *v) {
    const std::vector<double> ql = padLocal(*joint, w, q), vl = padLocal(*joint, w, v);
    return pad->state(ql.data(), vl.data());
  };
  const std::string &name = joint->name(), sub = "_" + std::to_string(k);
  b.addOutputChannel(OutputChannel::ofState("sliding_joint", name, "force" + sub, "N", w.watched,
                                            [state](const double *q, const double *v) { return state(q, v).force; }));
  b.addOutputChannel(OutputChannel::ofState("pad", name, "force" + sub, "N", w.watched,
                                            [state](const double *q, const double *v) { return state(q, v).force; }));
  b.addOutputChannel(OutputChannel::ofState(
      "pad", name, "penetration" + sub, "m", w.watched,
      [state](const double *q, const double *v) { return state(q, v).penetration; }));
  b.addOutputChannel(OutputChannel::ofState("pad", name, "side" + sub, "", w.watched,
                                            [state](const double *q, const double *v) {
                                              return static_cast<double>(state(q, v).side);
                                            }));
}

void addReactionOutputs(std::shared_ptr<const SpatialSlidingJoint> joint, const ConstraintItem &item,
                        const std::array<const PadContact *, 2> &pads, ModelBuilder &b)
{
  const std::string &name = joint->name();
  PetscInt row = item.firstRow() - b.numCoordinates();
  b.addOutputChannel(OutputChannel::ofState("sliding_joint", name, "s", "m", {joint->slackIndex()},
                                            [](const double *q, const double *) { return q[0]; }));
  b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "force_tangential", "N", row++, 1.0));
  for (int k = 2; k <= 3; ++k) {
    if (joint->rigidAlong(k))
      b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "force_" + std::to_string(k), "N",
                                                     row++, 1.0));
    else addPadOutputs(joint, pads[k - 2], k, b);
  }
  if (joint->aligned()) {
    b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "moment_2", "N m", row + 1, -1.0));
    b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "moment_3", "N m", row, 1.0));
    row += 2;
  }
  if (joint->rolled())
    b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "torque", "N m", row, 1.0));
}

void buildSpatialSlidingJoint(const ComponentSpec &spec, ModelBuilder &b)
{
  const auto &mine = b.scratch(spec.type, spec.name);
  const auto &track = static_cast<const SpatialAncfBeam &>(b.spatialBody(spec.text("track")));
  const SpatialBody &slider = b.spatialBody(spec.text("body"));
  const double at = spec.number("at"), s0 = mine.at("s0");
  // The sleeve's axes across the track: the track's section axes at s0, in
  // the slider's section axes at the slider point.
  const Mat3 across = slider.initialTriad(at).transpose() * track.initialTriad(s0);
  const SleeveRotation rot = rotationOf(spec);
  const bool padded = spec.has("pad");
  auto joint = std::make_shared<SpatialSlidingJoint>(spec.name, track, slider, at,
                                                     static_cast<PetscInt>(mine.at("slack")), s0,
                                                     rot != SleeveRotation::Free, rot == SleeveRotation::Locked,
                                                     across.col(1), across.col(2),
                                                     std::array<bool, 2>{!padded, !padded});
  const ConstraintItem &item = b.addConstraint(joint, spec.mark);
  std::array<const PadContact *, 2> pads{nullptr, nullptr};
  if (padded)
    for (int k = 2; k <= 3; ++k) {
      const ComponentSpec &p = spec.map(k == 3 && spec.has("pad_3") ? "pad_3" : "pad");
      pads[k - 2] = b.addPad(std::make_unique<PadContact>(std::make_shared<SpatialPadGap>(joint, k), padSpecOf(p)));
    }
  addReactionOutputs(joint, item, pads, b);
  b.addPostStepHook(followTrack(joint));
}

} // namespace

PhysicsType spatialSlidingJointType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "sliding_joint";
  t.schema.summary = "A material point of the slider body (a sleeve, or a point of another beam) moves along the "
                     "deformable axis of a beam; its contact coordinate s is an unknown. Optionally the sleeve's "
                     "axis stays along the tangent and its rotation about the axis follows the twisted section.";
  t.schema.keys = {
      bodyKey("body", "the slider body"),
      atKey("at", "body", "the slider point"),
      key("track", ValueKind::Body, "", Need::Required, "the beam (ancf_beam) the slider runs along").unlike("body"),
      key("rotation", ValueKind::Name, "", Need::Optional,
          "free: a point on the axis (3 rows); aligned: the slider's axes across the track stay normal to its "
          "tangent (5 rows); locked: also the rotation about the axis follows the track's section (6 rows)")
          .derived("free"),
      key("pad", ValueKind::Map, "", Need::Optional,
          "compliant pads with clearance in place of the two rigid lateral position rows: one pair of one-sided "
          "pads along each section direction d2, d3 of the track at s (table below)")
          .holding(padSchema()),
      key("pad_3", ValueKind::Map, "", Need::Optional,
          "the pads along d3 with their own values (stiffness, clearance, damping); without it they take `pad`'s")
          .holding(padSchema("pad_3")),
  };
  const std::string reason =
      "not allowed for a sliding_joint (it names the slider point with body/at and the track with 'track')";
  const std::string later = "not available for sliding joints of spatial scenes yet (frictionless contact)";
  t.schema.rules = {forbid("point", reason), forbid("angle", reason), forbid("other", reason),
                    forbid("other_at", reason), forbid("friction", later),
                    forbidIfAbsent("pad", "pad_3", "needs `pad` (the d2 pads); pad_3 only gives the d3 pads their own values")};
  t.check = checkSpatialSlidingJoint;
  t.addCoordinates = addSpatialSlack;
  t.build = buildSpatialSlidingJoint;
  return t;
}

} // namespace boomdyn
