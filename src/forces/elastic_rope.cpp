#include "boomdyn/elastic_rope.hpp"

#include "boomdyn/schema.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace boomdyn {

ElasticRope::ElasticRope(std::string name, RopePath path, double EA, double restLength, double damping,
                         TimeFunction payout)
  : name_(std::move(name)), path_(std::move(path)), EA_(EA), L0_(restLength), c_(damping),
    payout_(std::move(payout)), winch_(payout_.kind() != TimeFunction::Kind::Constant || payout_.value(0) != 0)
{
}

ElasticRope::State ElasticRope::state(double t, const double *q, const double *v) const
{
  State st;
  const RopePath::Geometry &g = path_.geometry(q); // l and l_q, no arrays allocated
  st.length = g.length;
  st.rate = g.lq.dot(Eigen::Map<const Eigen::VectorXd>(v, path_.numCoordinates()));
  st.restLength = restLength(t);
  st.payout = payout_.value(t);
  st.payoutRate = payout_.rate(t);
  st.stretch = st.length - st.restLength;
  st.force = stiffness(t) * st.stretch + c_ * (st.rate - st.payoutRate);
  // Tension only, and only while longer than unstretched: a rope shorter
  // than L0 carries nothing even while it lengthens fast (no damping pull).
  st.taut = st.stretch > 0 && st.force > 0;
  st.tension = st.taut || std::isnan(st.force) ? st.force : 0.0; // a NaN is reported as one, not as slack
  if (st.stretch > 0) {
    const double eps = st.stretch / st.restLength;
    st.winchPower = -(st.tension + 0.5 * EA_ * eps * eps) * st.payoutRate;
  }
  return st;
}

void ElasticRope::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  const int n = path_.numCoordinates();
  // l and l_q from the path's own Geometry (no arrays allocated per
  // residual); the Hessian only for the tangent.
  const RopePath::Geometry &g = path_.geometry(in.q);
  Eigen::MatrixXd lqq;
  if (J) {
    lqq.setZero(n, n);
    lqq += 1.0 * RopePath::segmentHessian(g);
    path_.addCurvature(in.q, g, 1.0, lqq);
  }
  evaluateAt(ctx, in, g, lqq, residual, J);
}

void ElasticRope::evaluatePencil(const PencilPass (&pass)[kPencilPasses], int n, double *scratch) const
{
  // Geometry and Hessian (most of a pass) once for the passes whose q are
  // bitwise the same (the maps differ only in the sign of zero entries; then
  // one geometry per pass), each from the same code as evaluate(); the rest
  // of each pass is evaluate()'s own (evaluateAt) on the same values. n: the
  // path's coordinates (a rope has no multiplier rows).
  const double *at = nullptr;
  const RopePath::Geometry *g = nullptr;
  Eigen::MatrixXd lqq;
  for (const PencilPass &p : pass) {
    if (!p.J) continue;
    if (!at || std::memcmp(at, p.in.q, n * sizeof(double)) != 0) {
      g = &path_.geometry(p.in.q);
      lqq.setZero(n, n);
      lqq += 1.0 * RopePath::segmentHessian(*g);
      path_.addCurvature(p.in.q, *g, 1.0, lqq);
      at = p.in.q;
    }
    std::fill(scratch, scratch + n, 0.0);
    evaluateAt(p.ctx, p.in, *g, lqq, scratch, p.J);
  }
}

void ElasticRope::evaluateAt(const AssemblyContext &ctx, const ItemValues &in, const RopePath::Geometry &g,
                             const Eigen::MatrixXd &lqq, double *residual, double *J) const
{
  const int n = path_.numCoordinates();
  const Eigen::RowVectorXd &lq = g.lq;
  const double l = g.length;
  const Eigen::Map<const Eigen::VectorXd> v(in.v, n);
  const double L0 = restLength(ctx.t), k = EA_ / L0;
  const double rate = lq.dot(v), f = k * (l - L0) + c_ * (rate - payout_.rate(ctx.t));
  if (!std::isfinite(f)) {
    // A NaN is not "slack": the residual says so, and the run's failure
    // names the rope (fault()).
    if (fault_.empty())
      fault_ = "elastic_rope '" + name_ + "': its force is not finite at t = " + numberText(ctx.t) +
               " s (spanned length " + numberText(l) + " m; a segment of zero length has no direction)";
    for (int i = 0; i < n; ++i) residual[i] = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  if (!(l > L0 && f > 0)) return; // slack: no force, no stiffness
  // The active set is that of the current Newton iterate (a semismooth
  // Newton step); a step whose iteration does not converge is cut by the
  // step controller.
  for (int i = 0; i < n; ++i) residual[i] += f * lq[i];
  if (!J) return;
  const Kinematics &kin = ctx.kin;
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Jm(J, n, n);
  const Eigen::VectorXd lqqv = lqq * v; // d(dl/dt)/dq = (l_qq v)^T
  Jm += kin.cQ * (f * lqq + k * lq.transpose() * lq + c_ * lq.transpose() * lqqv.transpose()) +
        kin.cV * c_ * lq.transpose() * lq;
}

void ElasticRope::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  const State st = state(ctx.t, in.q, in.v);
  const double k = stiffness(ctx.t), elastic = st.stretch > 0 ? k * st.stretch : 0.0;
  if (st.stretch > 0) e.strain += 0.5 * k * st.stretch * st.stretch;
  // Power into the rope T s' minus the rate of its strain energy at fixed
  // L0: >= 0 in every case of the cut (s = l - L0).
  const double stretchRate = st.rate - st.payoutRate;
  e.dissipation += st.tension * stretchRate - elastic * stretchRate;
  e.inputPower += st.winchPower;
  // At a jump of the winch's rate (a ramp's ends) the power just before t:
  // the same rope with the rate of the segment that ends at t.
  if (const double before = payout_.rateBefore(ctx.t); before != st.payoutRate && st.stretch > 0) {
    const double f = k * st.stretch + c_ * (st.rate - before), tension = f > 0 ? f : 0.0;
    const double eps = st.stretch / st.restLength;
    e.inputPowerJump += -(tension + 0.5 * EA_ * eps * eps) * before - st.winchPower;
  }
}

} // namespace boomdyn
