// Type `distance` (section constraints): the kernel (distance.hpp) and its
// scene type: schema, builder (default length: the initial distance) and
// output (the link's tension).
#include "boomdyn/distance.hpp"

#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

namespace boomdyn {

Distance::Distance(std::string name, const Body &a, double sa, Vec2 ground, double length)
  : name_(std::move(name)), a_(&a), sa_(sa), length_(length), la_(a.locate(sa)), ground_(ground)
{
}

Distance::Distance(std::string name, const Body &a, double sa, const Body &b, double sb, double length)
  : name_(std::move(name)), a_(&a), b_(&b), sa_(sa), sb_(sb), length_(length), la_(a.locate(sa)), lb_(b.locate(sb))
{
}

void Distance::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.assign(la_.dofs.begin(), la_.dofs.begin() + la_.count);
  if (b_) dofs.insert(dofs.end(), lb_.dofs.begin(), lb_.dofs.begin() + lb_.count);
}

double Distance::distance(const double *q) const
{
  CenterlineSample pa, pb;
  a_->sample(la_, sa_, q, pa);
  if (!b_) return (pa.r[0] - ground_).norm();
  b_->sample(lb_, sb_, q + la_.count, pb);
  return (pa.r[0] - pb.r[0]).norm();
}

void Distance::evaluate(double, const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  const int na = la_.count, nb = b_ ? lb_.count : 0, n = na + nb;
  // d = r_a - r_b (or r_a - p) and its Jacobian.
  CenterlineSample pa, pb;
  a_->sample(la_, sa_, q, pa);
  Vec2 d = pa.r[0] - ground_;
  Eigen::MatrixXd dq = Eigen::MatrixXd::Zero(2, n);
  dq.leftCols(na) = pa.r_q[0].leftCols(na);
  if (b_) {
    b_->sample(lb_, sb_, q + na, pb);
    d -= pb.r[0];
    dq.rightCols(nb) = -pb.r_q[0].leftCols(nb);
  }
  const double l = d.norm();
  const Vec2 e = d / l;
  out.C.setConstant(1, l - length_);
  out.Cq = e.transpose() * dq;
  // d2|d|/dd2 = (I - e e^T) / l, plus the curvature of nonlinear centerlines
  // (rigid bodies) weighted by d|d|/dr_a = e and d|d|/dr_b = -e.
  const Eigen::Matrix2d P = (Eigen::Matrix2d::Identity() - e * e.transpose()) / l;
  auto curvature = [&](double scale, Eigen::MatrixXd &H) {
    Eigen::Matrix<double, 8, 8> H8;
    if (!pa.linear) {
      a_->curvatureTerm(la_, sa_, q, 0, scale * e, H8);
      H.topLeftCorner(na, na) += H8.topLeftCorner(na, na);
    }
    if (b_ && !pb.linear) {
      b_->curvatureTerm(lb_, sb_, q + na, 0, -scale * e, H8);
      H.bottomRightCorner(nb, nb) += H8.topLeftCorner(nb, nb);
    }
  };
  if (v) {
    const Eigen::Map<const Eigen::VectorXd> vv(v, n);
    const Vec2 ddot = dq * vv;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
    curvature(1.0, H);
    out.gamma.setConstant(1, ddot.dot(P * ddot) + vv.dot(H * vv));
  }
  if (w) {
    out.H = w[0] * (dq.transpose() * P * dq);
    curvature(w[0], out.H);
  }
}

namespace {

void buildDistance(const ComponentSpec &spec, ModelBuilder &b)
{
  const Body &a = b.body(spec.text("body"));
  const double sa = spec.number("at");
  auto make = [&](double length) {
    if (spec.has("other"))
      return std::make_shared<Distance>(spec.name, a, sa, b.body(spec.text("other")), spec.number("other_at"), length);
    const Vec2d p = spec.vec2("point");
    return std::make_shared<Distance>(spec.name, a, sa, Vec2(p[0], p[1]), length);
  };
  double length = spec.numberOr("length", 0.0);
  if (!spec.has("length")) { // the initial distance
    const auto probe = make(0.0);
    std::vector<PetscInt> dofs;
    probe->coordinates(dofs);
    std::vector<double> vals;
    for (PetscInt d : dofs) vals.push_back(b.bodyCoordinates()[d]);
    length = probe->distance(vals.data());
  }
  if (!(length > 0))
    throw ModelError(ModelBuilder::where(spec.mark) + "distance '" + spec.name +
                     "': the two points coincide at t = 0 and no length is given; join coinciding points with a pin");
  const ConstraintItem &item = b.addConstraint(make(length), spec.mark);
  // C = |d| - L: a link that pulls its points together has a positive multiplier.
  b.addOutputChannel(
      OutputChannel::ofMultiplier("distance", spec.name, "tension", "N", item.firstRow() - b.numCoordinates(), 1.0));
}

} // namespace

PhysicsType distanceType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "distance";
  t.schema.summary = "A material point keeps its distance from a ground point or from a material point of another "
                     "body (a rigid link pinned at both ends).";
  t.schema.keys = {
      bodyKey("body", "body of the first end"),
      atKey("at", "body", "material point of the first end"),
      key("other", ValueKind::Body, "", Need::Optional, "body of the second end (link between two bodies)"),
      atKey("other_at", "other", "material point of the second end").requiredWith("other"),
      key("point", ValueKind::Vec2, "m", Need::Optional, "ground point [x, y] of the second end")
          .requiredWithout("other"),
      key("length", ValueKind::Number, "m", Need::Optional, "the distance kept").positive().derived(
          "the initial distance"),
  };
  t.schema.rules = {
      forbid("angle", "not allowed for a distance (the link leaves the rotation free)"),
      forbidIfPresent("other", "point", "not allowed together with 'other' (the link joins two bodies)"),
      forbidIfAbsent("other", "other_at", "only allowed together with 'other'"),
  };
  t.build = buildDistance;
  return t;
}

} // namespace boomdyn
