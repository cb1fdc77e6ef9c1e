#include "boomdyn/pad_contact.hpp"

#include <cmath>
#include <cstring>

namespace boomdyn {

PadContact::PadContact(std::shared_ptr<const PadGap> gap, const PadSpec &spec)
  : joint_(std::move(gap)), spec_(spec)
{
}

PadState PadContact::state(const double *q, const double *v) const
{
  double d;
  Eigen::VectorXd &dq = dq_;
  joint_->normalGap(q, d, dq);
  PadState s;
  s.gap = d;
  s.side = sideOf(d, spec_.clearance);
  s.penetration = std::abs(d) - spec_.clearance;
  if (s.side != 0) {
    const double ddot = v ? dq.dot(Eigen::Map<const Eigen::VectorXd>(v, dq.size())) : 0.0;
    s.force = -spec_.stiffness * s.side * s.penetration - spec_.damping * ddot;
  }
  return s;
}

void PadContact::force(const double *q, const double *v, double &f, Eigen::VectorXd &fq, Eigen::VectorXd &fv) const
{
  double d;
  Eigen::VectorXd &dq = dq_;
  Eigen::MatrixXd &dqq = dqq_;
  joint_->normalGap(q, d, dq, dqq);
  const Eigen::Index n = dq.size();
  const int side = sideOf(d, spec_.clearance);
  fq = Eigen::VectorXd::Zero(n);
  fv = Eigen::VectorXd::Zero(n);
  f = 0;
  if (side == 0) return;
  const Eigen::Map<const Eigen::VectorXd> vv(v, n);
  const double c = spec_.damping;
  f = -spec_.stiffness * (d - side * spec_.clearance) - c * dq.dot(vv);
  fq = -spec_.stiffness * dq - c * (dqq * vv);
  fv = -c * dq;
}

void PadContact::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  const Kinematics &k = ctx.kin;
  // The mass pencil of an eigen-analysis: a pad has no inertia.
  if (k.cQ == 0 && k.cV == 0 && !ctx.accelerationLevel) return;
  double d;
  // The pad's own work arrays (no heap traffic per residual); the Hessian
  // only for the tangent.
  if (J) joint_->normalGap(in.q, d, dq_, dqq_);
  else joint_->normalGap(in.q, d, dq_);
  evaluateAtGap(ctx, in, d, residual, J);
}

void PadContact::evaluatePencil(const PencilPass (&pass)[kPencilPasses], int n, double *scratch) const
{
  // The passes that reach the gap (all but the mass pass, see evaluate())
  // share one normalGap when their q are bitwise the same (the maps differ
  // only in the sign of zero entries; then one gap per pass). The rest of
  // each pass is evaluate()'s own code (evaluateAtGap) on the same values.
  // n: the pad's coordinates (it has no multiplier rows).
  const double *gapAt = nullptr;
  double d = 0;
  for (const PencilPass &p : pass) {
    if (!p.J) continue;
    const Kinematics &k = p.ctx.kin;
    if (k.cQ == 0 && k.cV == 0 && !p.ctx.accelerationLevel) continue;
    if (!gapAt || std::memcmp(gapAt, p.in.q, n * sizeof(double)) != 0) {
      joint_->normalGap(p.in.q, d, dq_, dqq_);
      gapAt = p.in.q;
    }
    std::fill(scratch, scratch + n, 0.0);
    evaluateAtGap(p.ctx, p.in, d, scratch, p.J);
  }
}

void PadContact::evaluateAtGap(const AssemblyContext &ctx, const ItemValues &in, double d, double *residual,
                               double *J) const
{
  const Kinematics &k = ctx.kin;
  const Eigen::VectorXd &dq = dq_;
  const Eigen::MatrixXd &dqq = dqq_;
  const int side = sideOf(d, spec_.clearance);
  const Eigen::Index n = dq.size();
  if (side == 0) { // free within the clearance: no force, no stiffness ...
    // ... except in a static tangent (cV = cA = 0), where a body held only
    // by pads would make the matrix singular while an iterate is in the
    // clearance: there the tangent gets gapStiffness * k_pad along d_q, a
    // modified Newton step that crosses the clearance in a few iterations
    // (the residual, and so the converged solution, is exact).
    if (J && k.cV == 0 && k.cA == 0 && k.cQ > 0) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Jm(J, n, n);
      Jm += (k.cQ * gapStiffness * spec_.stiffness) * dq * dq.transpose();
    }
    return;
  }
  const Eigen::Map<const Eigen::VectorXd> v(in.v, n);
  const double c = spec_.damping, kp = spec_.stiffness;
  const double f = -kp * (d - side * spec_.clearance) - c * dq.dot(v);
  // residual = -Q = -f d_q
  Eigen::Map<Eigen::VectorXd>(residual, n) -= f * dq;
  if (!J) return;
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Jm(J, n, n);
  const Eigen::VectorXd fx = k.cQ * (kp * dq + c * (dqq * v)) + k.cV * c * dq; // -df/dx
  Jm += dq * fx.transpose() - (k.cQ * f) * dqq;
}

void PadContact::energy(const AssemblyContext &, const ItemValues &in, EnergyParts &parts) const
{
  double d;
  Eigen::VectorXd &dq = dq_;
  joint_->normalGap(in.q, d, dq);
  const int side = sideOf(d, spec_.clearance);
  if (side == 0) return;
  const double penetration = std::abs(d) - spec_.clearance;
  parts.strain += 0.5 * spec_.stiffness * penetration * penetration;
  if (in.v) {
    const double ddot = dq.dot(Eigen::Map<const Eigen::VectorXd>(in.v, dq.size()));
    parts.dissipation += spec_.damping * ddot * ddot;
  }
}

} // namespace boomdyn
