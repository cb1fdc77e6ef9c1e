// Type `sliding_joint` (section constraints): a material point of the
// slider body moves along the centerline of the track body. Adds the slack
// (contact) coordinate s, optionally LuGre friction with its bristle state
// z, and a post-step hook that moves the contact point to the track element
// that holds s (or stops the run when the slider leaves its track). With a
// `pad` map the normal row gives way to a compliant pad with clearance
// (PadContact): only the tangential row stays a constraint.
#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/lugre_friction.hpp"
#include "boomdyn/model_builder.hpp"
#include "boomdyn/pad_contact.hpp"
#include "boomdyn/pad_schema.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/slack_coordinate.hpp"
#include "boomdyn/sliding_joint.hpp"

#include <array>
#include <cmath>

namespace boomdyn {

namespace {

// LuGre parameters (docs/model.md §3); the defaults are FrictionSpec's.
const TypeSchema &frictionSchema()
{
  static const TypeSchema schema = [] {
    const FrictionSpec d;
    TypeSchema s;
    s.section = "constraints";
    s.type = "friction";
    s.summary = "LuGre friction at a sliding joint (the map under a sliding_joint's `friction` key).";
    s.keys = {
        key("mu_s", ValueKind::Number, "", Need::Required, "static friction coefficient").positive(),
        key("mu_c", ValueKind::Number, "", Need::Required, "kinetic (Coulomb) friction coefficient, <= mu_s")
            .positive(),
        key("v_s", ValueKind::Number, "m/s", Need::Optional, "Stribeck velocity").positive().byDefault(d.v_s),
        key("alpha", ValueKind::Number, "", Need::Optional, "Stribeck exponent").positive().byDefault(d.alpha),
        key("sigma0", ValueKind::Number, "1/m", Need::Optional, "bristle stiffness per unit normal force")
            .positive()
            .byDefault(d.sigma0),
        key("sigma1", ValueKind::Number, "s/m", Need::Optional, "bristle damping per unit normal force")
            .nonNegative()
            .byDefault(d.sigma1),
        key("sigma2", ValueKind::Number, "N s/m", Need::Optional, "viscous friction").nonNegative().byDefault(d.sigma2),
        key("stick_velocity", ValueKind::Number, "m/s", Need::Optional,
            "relative speed below which the output counts the joint as sticking")
            .positive()
            .derived("v_s / 10"),
    };
    return s;
  }();
  return schema;
}

std::optional<SpecIssue> checkSlidingJoint(const ComponentSpec &spec, const Scene &)
{
  if (!spec.has("friction")) return std::nullopt;
  const ComponentSpec &f = spec.map("friction");
  if (f.number("mu_c") > f.number("mu_s"))
    return SpecIssue{"friction.mu_c", "must be <= mu_s (" + numberText(f.number("mu_s")) + "): kinetic friction above static"};
  return std::nullopt;
}

FrictionSpec frictionOf(const ComponentSpec &f)
{
  FrictionSpec fr;
  fr.mu_s = f.number("mu_s");
  fr.mu_c = f.number("mu_c");
  fr.v_s = f.number("v_s");
  fr.alpha = f.number("alpha");
  fr.sigma0 = f.number("sigma0");
  fr.sigma1 = f.number("sigma1");
  fr.sigma2 = f.number("sigma2");
  fr.stick_velocity = f.numberOr("stick_velocity", fr.v_s / 10);
  return fr;
}

// The slack coordinate starts where the slider point projects onto the
// (straight) initial track.
void addSlack(const ComponentSpec &spec, ModelBuilder &b)
{
  const Body &track = b.body(spec.text("track")), &slider = b.body(spec.text("body"));
  const double at = spec.number("at");
  const std::vector<double> &q0 = b.bodyCoordinates();
  CenterlineSample origin, point;
  const CenterlineLocation l0 = track.locate(0.0), lp = slider.locate(at);
  std::vector<double> v0(8), vp(8);
  for (int i = 0; i < 8; ++i) v0[i] = q0[l0.dofs[i]], vp[i] = q0[lp.dofs[i]];
  track.sample(l0, 0.0, v0.data(), origin);
  slider.sample(lp, at, vp.data(), point);
  const double s0 = (point.r[0] - origin.r[0]).dot(origin.r[1].normalized());
  addSlackCoordinate(spec, b, track, s0);
}

void addFrictionState(const ComponentSpec &spec, ModelBuilder &b)
{
  if (spec.has("friction"))
    b.scratch(spec.type, spec.name)["z"] = static_cast<double>(b.addFirstOrderState(spec.name));
}

// A pad's state from the watched coordinates: both bodies whole, then s (the
// contact point moves between track elements, the watched list cannot).
struct PadWatch {
  std::vector<PetscInt> watched;
  PetscInt trackOffset = 0, sliderOffset = 0;
};

PadWatch padWatch(const SlidingJoint &joint)
{
  PadWatch w;
  for (const Body *body : {&joint.track(), &joint.slider()}) {
    (body == &joint.track() ? w.trackOffset : w.sliderOffset) = static_cast<PetscInt>(w.watched.size());
    for (PetscInt k = 0; k < body->numCoordinates(); ++k) w.watched.push_back(body->firstCoordinate() + k);
  }
  w.watched.push_back(joint.slackIndex());
  return w;
}

// The joint's coordinates (coordinates() order) picked from the watched values.
void padLocal(const SlidingJoint &joint, const PadWatch &w, const double *x, std::vector<double> &out)
{
  const CenterlineLocation &tl0 = joint.trackLocation(), &sl0 = joint.sliderLocation();
  out.resize(static_cast<std::size_t>(tl0.count + sl0.count + 1)); // coordinates().size()
  const CenterlineLocation &tl = joint.trackLocation();
  for (int i = 0; i < tl.count; ++i) out[i] = x[w.trackOffset + tl.dofs[i] - joint.track().firstCoordinate()];
  const CenterlineLocation &sl = joint.sliderLocation();
  for (int i = 0; i < sl.count; ++i)
    out[tl.count + i] = x[w.sliderOffset + sl.dofs[i] - joint.slider().firstCoordinate()];
  out.back() = x[w.watched.size() - 1];
}

// The last pad state computed and what it was computed from.
struct PadStateMemo {
  bool valid = false;
  std::vector<double> q, v;
  CenterlineLocation track, slider;
  PadState state;
  std::vector<double> ql, vl; // work arrays of the lookup, kept between steps
};

bool sameLocation(const CenterlineLocation &a, const CenterlineLocation &b)
{
  return a.count == b.count && a.dofs == b.dofs && a.element == b.element && a.xi == b.xi && a.s == b.s &&
         a.begin == b.begin && a.end == b.end;
}

// A pad whose penetration at the start is at most this (m) is on the edge
// of contact: round-off of coordinates of size 1e4 m, far below any pad's
// deflection under load (k_pad = 5e8 N/m: 0.05 N).
constexpr double kPadEdge = 1e-10;

// Per pad every step: contact force f (N, along the track normal, on the
// slider), penetration (|d| - g: > 0 in contact, else minus the free play
// left) and side (+1, -1 in contact, 0 free); lift-off / contact events
// with the time interpolated where the penetration crosses 0 inside the step.
void addPadOutputs(std::shared_ptr<SlidingJoint> joint, const PadContact *pad, ModelBuilder &b)
{
  const PadWatch w = padWatch(*joint);
  // The three channels and the event source ask for the state of the same
  // (q, v) every step: the gap's derivatives are computed once per state.
  auto memo = std::make_shared<PadStateMemo>();
  auto state = [joint, pad, w, memo](const double *q, const double *v) {
    std::vector<double> &ql = memo->ql, &vl = memo->vl;
    padLocal(*joint, w, q, ql), padLocal(*joint, w, v, vl);
    if (memo->valid && memo->q == ql && memo->v == vl && sameLocation(memo->track, joint->trackLocation()) &&
        sameLocation(memo->slider, joint->sliderLocation()))
      return memo->state;
    memo->state = pad->state(ql.data(), vl.data());
    memo->q.swap(ql), memo->v.swap(vl);
    memo->track = joint->trackLocation(), memo->slider = joint->sliderLocation();
    memo->valid = true;
    return memo->state;
  };
  const std::string &name = joint->name();
  b.addOutputChannel(OutputChannel::ofState("pad", name, "force", "N", w.watched,
                                            [state](const double *q, const double *v) { return state(q, v).force; }));
  b.addOutputChannel(OutputChannel::ofState(
      "pad", name, "penetration", "m", w.watched,
      [state](const double *q, const double *v) { return state(q, v).penetration; }));
  b.addOutputChannel(OutputChannel::ofState("pad", name, "side", "", w.watched, [state](const double *q, const double *v) {
    return static_cast<double>(state(q, v).side);
  }));
  auto previous = std::make_shared<PadState>();
  // A pad that starts on the edge of contact (penetration 0 to round-off:
  // with no clearance, the gap d = 0 belongs to both sides) has no side yet:
  // the first step decides it, without an event at the start.
  auto undecided = std::make_shared<bool>(false);
  EventSource source{name, {"lift_off", "contact"}, w.watched, nullptr};
  source.detect = [state, previous, undecided, name, pad](double t, double h, const double *q, const double *v,
                                                          bool first, std::vector<TypeEvent> &out) {
    const PadState now = state(q, v);
    const PadState before = *previous;
    *previous = now;
    if (first) {
      *undecided = std::abs(now.penetration) <= kPadEdge;
      return;
    }
    if (*undecided) { // the first step decides the side
      *undecided = false;
      return;
    }
    if (now.side == before.side) return;
    // Where the penetration on a side, sigma d - g, crosses zero inside the step (linear).
    const double g = pad->spec().clearance;
    auto crossing = [&](int sigma) {
      const double p0 = sigma * before.gap - g, p1 = sigma * now.gap - g;
      return p1 == p0 ? t : t - h * p1 / (p1 - p0);
    };
    if (before.side != 0) out.push_back({crossing(before.side), name, "lift_off", before.side}); // direction: side left
    if (now.side != 0) out.push_back({crossing(now.side), name, "contact", now.side});
  };
  b.addEventSource(source);
}

// Stress resultants of a beam at material point x from its element there:
// N = EA eps, M = EI kappa, Q = dM/dx = EI kappa' (docs/model.md §2.1), with
// kappa' = (r1 x r3) / |r1|^2 - 2 (r1 x r2)(r1 . r2) / |r1|^4.
enum class Resultant { Axial, Moment, Shear };

double resultantAt(const AncfBeam &beam, double x, const double *bodyValues, Resultant which)
{
  const CenterlineLocation loc = beam.locate(std::clamp(x, 0.0, beam.length()));
  ancf::Vec8 e;
  for (int k = 0; k < 8; ++k) e[k] = bodyValues[beam.elementDof(loc.element, k) - beam.firstCoordinate()];
  const double l = beam.elementLength();
  const ancf::Section &sec = beam.section();
  switch (which) {
  case Resultant::Axial: return sec.EA * ancf::axialStrain(e, loc.xi, l);
  case Resultant::Moment: return sec.EI * ancf::curvature(e, loc.xi, l);
  case Resultant::Shear: {
    const Vec2 r1 = ancf::position(e, loc.xi, l, 1), r2 = ancf::position(e, loc.xi, l, 2),
               r3 = ancf::position(e, loc.xi, l, 3);
    auto cross = [](const Vec2 &a, const Vec2 &c) { return a.x() * c.y() - a.y() * c.x(); };
    const double J2 = r1.squaredNorm();
    return sec.EI * (cross(r1, r3) / J2 - 2.0 * cross(r1, r2) * r1.dot(r2) / (J2 * J2));
  }
  }
  return 0.0;
}

// Every sliding joint, every step: the normal force on the slider along the
// track normal j(s) (lambda_n of a rigid joint, the pad force f of a padded
// one), and N, M, Q of each beam at the joint: the track at the contact
// point s, the slider at its slider point.
void addJointResultants(std::shared_ptr<SlidingJoint> joint, const ConstraintItem &item, const PadContact *pad,
                        ModelBuilder &b)
{
  const std::string &name = joint->name();
  if (!pad) // C_n = j . (r_i - r_j): the constraint force on the slider is +lambda_n j
    b.addOutputChannel(OutputChannel::ofMultiplier("joint_resultants", name, "normal_force", "N",
                                                   item.firstRow() + 1 - b.numCoordinates(), 1.0));
  const PadWatch w = padWatch(*joint);
  if (pad) {
    auto local = std::make_shared<std::array<std::vector<double>, 2>>(); // q, v picked: kept between steps
    b.addOutputChannel(OutputChannel::ofState("joint_resultants", name, "normal_force", "N", w.watched,
                                              [joint, pad, w, local](const double *q, const double *v) {
                                                std::vector<double> &ql = (*local)[0], &vl = (*local)[1];
                                                padLocal(*joint, w, q, ql), padLocal(*joint, w, v, vl);
                                                return pad->state(ql.data(), vl.data()).force;
                                              }));
  }
  const char *names[3] = {"N", "M", "Q"};
  const char *units[3] = {"N", "N m", "N"};
  const Resultant kinds[3] = {Resultant::Axial, Resultant::Moment, Resultant::Shear};
  for (int side = 0; side < 2; ++side) {
    const Body &body = side == 0 ? joint->track() : joint->slider();
    const auto *beam = dynamic_cast<const AncfBeam *>(&body);
    if (!beam) continue; // a rigid body has no stress resultants
    const PetscInt offset = side == 0 ? w.trackOffset : w.sliderOffset;
    const PetscInt slack = static_cast<PetscInt>(w.watched.size()) - 1;
    const double xP = joint->sliderPoint();
    for (int k = 0; k < 3; ++k)
      b.addOutputChannel(OutputChannel::ofState(
          "joint_resultants", name, std::string(side == 0 ? "track_" : "slider_") + names[k], units[k], w.watched,
          [beam, offset, slack, side, xP, which = kinds[k]](const double *q, const double *) {
            return resultantAt(*beam, side == 0 ? q[slack] : xP, q + offset, which);
          }));
  }
}

void buildSlidingJoint(const ComponentSpec &spec, ModelBuilder &b)
{
  const auto &mine = b.scratch(spec.type, spec.name);
  const bool padded = spec.has("pad");
  auto joint = std::make_shared<SlidingJoint>(spec.name, b.body(spec.text("track")), b.body(spec.text("body")),
                                              spec.number("at"), static_cast<PetscInt>(mine.at("slack")), mine.at("s0"),
                                              !padded);
  b.addSlidingJoint(joint);
  const ConstraintItem &item = b.addConstraint(joint, spec.mark);
  const PadContact *pad = nullptr;
  if (padded) {
    const ComponentSpec &p = spec.map("pad");
    pad = b.addPad(std::make_unique<PadContact>(
        joint, padSpecOf(p)));
    addPadOutputs(joint, pad, b);
  }
  addJointResultants(joint, item, pad, b);
  if (spec.has("friction")) { // the normal force: lambda_n (the joint's second row) or the pad's force
    const auto z = static_cast<PetscInt>(mine.at("z"));
    const FrictionSpec fr = frictionOf(spec.map("friction"));
    if (pad) b.addFriction(std::make_unique<LuGreFriction>(joint, z, pad, fr));
    else b.addFriction(std::make_unique<LuGreFriction>(joint, z, item.firstRow() + 1, fr));
  }
  b.addPostStepHook(followTrack(joint));
}

} // namespace

PhysicsType slidingJointType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "sliding_joint";
  t.schema.summary = "A material point of the slider body moves along the centerline of the track body; its contact "
                     "coordinate s is an unknown. Optional LuGre friction.";
  t.schema.keys = {
      bodyKey("body", "the slider body"),
      atKey("at", "body", "the slider point"),
      key("track", ValueKind::Body, "", Need::Required, "the body the slider runs along").unlike("body"),
      key("friction", ValueKind::Map, "", Need::Optional, "LuGre friction parameters (table below)")
          .holding(frictionSchema())
          .derived("frictionless"),
      key("pad", ValueKind::Map, "", Need::Optional,
          "compliant pad with clearance in place of the rigid normal condition (table below)")
          .holding(padSchema())
          .derived("rigid (bilateral, no clearance)"),
  };
  const std::string reason =
      "not allowed for a sliding_joint (it names the slider point with body/at and the track with 'track')";
  t.schema.rules = {forbid("point", reason), forbid("angle", reason), forbid("other", reason),
                    forbid("other_at", reason)};
  t.check = checkSlidingJoint;
  t.addCoordinates = addSlack;
  t.addStates = addFrictionState;
  t.build = buildSlidingJoint;
  return t;
}

} // namespace boomdyn
