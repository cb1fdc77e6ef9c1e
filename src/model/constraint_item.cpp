#include "boomdyn/constraint_item.hpp"

namespace boomdyn {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

ConstraintItem::ConstraintItem(std::shared_ptr<const Constraint> constraint, PetscInt firstRow)
  : constraint_(std::move(constraint)), firstRow_(firstRow)
{
}

void ConstraintItem::multiplierRows(std::vector<PetscInt> &rows) const
{
  rows.resize(constraint_->numRows());
  for (int i = 0; i < constraint_->numRows(); ++i) rows[i] = firstRow_ + i;
}

void ConstraintItem::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  if (!ctx.constraintBlocks) return; // B pencil: the item contributes explicit zeros only
  const int m = constraint_->numRows();
  const Eigen::Map<const Eigen::VectorXd> lam(in.lambda, m);
  const bool needHessian = J && ctx.kin.cQ != 0.0;
  // This item's own ConstraintEval, reused: its arrays keep their sizes
  // from one residual to the next, so evaluating allocates nothing. Every
  // constraint assigns C and C_q, and gamma, Ct and H whenever it is asked
  // for them (v, w non-null), which is when they are read below.
  ConstraintEval &ev = eval_;
  constraint_->evaluate(ctx.t, in.q, ctx.accelerationLevel ? in.v : nullptr, needHessian ? in.lambda : nullptr, ev);
  // The coordinate count from C_q (columns over coordinates()), without
  // building the coordinate list.
  const int nc = static_cast<int>(ev.Cq.cols()), n = nc + m;
  const double sigma = ctx.sigma;
  Eigen::Map<Eigen::VectorXd> r(residual, n);
  Eigen::VectorXd &p = product_;
  p.noalias() = ev.Cq.transpose() * lam;
  r.head(nc) += sigma * p;
  if (ctx.accelerationLevel) {
    const Eigen::Map<const Eigen::VectorXd> a(in.a, nc);
    if (!ctx.velocityLevel) {
      p.noalias() = ev.Cq * a;
      p += ev.gamma;
      r.tail(m) += sigma * p;
    } else { // velocity jump a: C_q (v + a) + C_t = 0
      r.tail(m) += sigma * ev.Cq * (a + Eigen::Map<const Eigen::VectorXd>(in.v, nc));
      if (ev.Ct.size() == m) r.tail(m) += sigma * ev.Ct;
    }
  } else {
    r.tail(m) += sigma * ev.C;
  }
  if (!J) return;
  Eigen::Map<RowMajor> Jm(J, n, n);
  if (needHessian) Jm.topLeftCorner(nc, nc) += ctx.kin.cQ * sigma * ev.H;
  Jm.topRightCorner(nc, m) += sigma * ev.Cq.transpose();
  Jm.bottomLeftCorner(m, nc) += sigma * (ctx.accelerationLevel ? ctx.kin.cA : ctx.kin.cQ) * ev.Cq;
}

void ConstraintItem::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  // The constraint forces -C_q^T lambda do work -lambda . C_q v = lambda . C_t
  // (C_q v + C_t = 0 along the motion): zero unless C depends on time
  // explicitly, as a drive's does. C_t by a central difference in t, which
  // is exact (zero) for constraints without time dependence.
  if (!constraint_->dependsOnTime()) return;
  const double dt = 1e-6 * std::max(1.0, std::abs(ctx.t));
  ConstraintEval plus, minus;
  constraint_->evaluate(ctx.t + dt, in.q, nullptr, nullptr, plus);
  constraint_->evaluate(ctx.t - dt, in.q, nullptr, nullptr, minus);
  const Eigen::Map<const Eigen::VectorXd> lam(in.lambda, constraint_->numRows());
  e.inputPower += lam.dot(plus.C - minus.C) / (2.0 * dt);
}

double ConstraintItem::constraintViolation(const AssemblyContext &ctx, const ItemValues &in) const
{
  ConstraintEval &ev = eval_; // the residual's work arrays (after every step: no allocation)
  constraint_->evaluate(ctx.t, in.q, nullptr, nullptr, ev);
  return ev.C.cwiseAbs().maxCoeff();
}

} // namespace boomdyn
