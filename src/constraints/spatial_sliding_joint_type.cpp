// Type `sliding_joint` of spatial scenes (section constraints, dimension 3):
// a point of the slider body moves along the deformable axis of a spatial
// beam (spatial_sliding_joint.hpp). Adds the slack coordinate s, the
// reactions as output channels in the track's section frame, and the
// post-step hook that moves the contact point between track elements (or
// stops the run when the slider leaves its track).
#include "boomdyn/model_builder.hpp"
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
void addReactionOutputs(const SpatialSlidingJoint &joint, const ConstraintItem &item, ModelBuilder &b)
{
  const std::string &name = joint.name();
  const PetscInt row = item.firstRow() - b.numCoordinates();
  b.addOutputChannel(OutputChannel::ofState("sliding_joint", name, "s", "m", {joint.slackIndex()},
                                            [](const double *q, const double *) { return q[0]; }));
  b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "force_tangential", "N", row, 1.0));
  b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "force_2", "N", row + 1, 1.0));
  b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "force_3", "N", row + 2, 1.0));
  if (joint.aligned()) {
    b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "moment_2", "N m", row + 4, -1.0));
    b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "moment_3", "N m", row + 3, 1.0));
  }
  if (joint.rolled())
    b.addOutputChannel(OutputChannel::ofMultiplier("sliding_joint", name, "torque", "N m", row + 5, 1.0));
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
  auto joint = std::make_shared<SpatialSlidingJoint>(spec.name, track, slider, at,
                                                     static_cast<PetscInt>(mine.at("slack")), s0,
                                                     rot != SleeveRotation::Free, rot == SleeveRotation::Locked,
                                                     across.col(1), across.col(2));
  const ConstraintItem &item = b.addConstraint(joint, spec.mark);
  addReactionOutputs(*joint, item, b);
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
  };
  const std::string reason =
      "not allowed for a sliding_joint (it names the slider point with body/at and the track with 'track')";
  const std::string later = "not available for sliding joints of spatial scenes yet (frictionless, rigid contact)";
  t.schema.rules = {forbid("point", reason), forbid("angle", reason), forbid("other", reason),
                    forbid("other_at", reason), forbid("friction", later), forbid("pad", later)};
  t.check = checkSpatialSlidingJoint;
  t.addCoordinates = addSpatialSlack;
  t.build = buildSpatialSlidingJoint;
  return t;
}

} // namespace boomdyn
