#include "boomdyn/point_load.hpp"

namespace boomdyn {

namespace {
void locationDofs(const CenterlineLocation &loc, std::vector<PetscInt> &dofs)
{
  dofs.assign(loc.dofs.begin(), loc.dofs.begin() + loc.count);
}
} // namespace

PointForce::PointForce(std::string name, const Body &body, double s, Vec2 force, TimeFunction scale)
  : name_(std::move(name)), body_(&body), s_(s), loc_(body.locate(s)), force_(force), scale_(std::move(scale))
{
}

void PointForce::coordinates(std::vector<PetscInt> &dofs) const { locationDofs(loc_, dofs); }

void PointForce::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  // Dead load: r_q^T F, no Jacobian for linear centerlines. A rigid body's
  // r_q depends on q, which would add F . d2r/dq2 to the tangent.
  CenterlineSample p;
  body_->sample(loc_, s_, in.q, p);
  const int n = loc_.count;
  const Vec2 F = ctx.loadFactor * scale_.value(ctx.t) * force_;
  Eigen::Map<Eigen::VectorXd>(residual, n) -= p.r_q[0].leftCols(n).transpose() * F;
  if (J && !p.linear) {
    Eigen::Matrix<double, 8, 8> H;
    body_->curvatureTerm(loc_, s_, in.q, 0, F, H);
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(J, n, n) -=
      ctx.kin.cQ * H.topLeftCorner(n, n);
  }
}

void PointForce::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  // Potential of a dead force, exact while the force is constant in time.
  CenterlineSample p;
  body_->sample(loc_, s_, in.q, p);
  e.potential -= (ctx.loadFactor * scale_.value(ctx.t) * force_).dot(p.r[0]);
  // U = -s(t) F . r changes at fixed r when the load does: dU/dt = -s'(t) F . r.
  e.inputPower -= (ctx.loadFactor * scale_.rate(ctx.t) * force_).dot(p.r[0]);
  // Where the rate jumps (a ramp's ends), the power just before t as well.
  if (const double before = scale_.rateBefore(ctx.t), after = scale_.rate(ctx.t); before != after)
    e.inputPowerJump -= (ctx.loadFactor * (before - after) * force_).dot(p.r[0]);
}

PointMass::PointMass(std::string name, const Body &body, double s, double mass, Vec2 gravity, Release release)
  : name_(std::move(name)), body_(&body), s_(s), loc_(body.locate(s)), mass_(mass), gravity_(gravity),
    release_(release)
{
}

void PointMass::coordinates(std::vector<PetscInt> &dofs) const { locationDofs(loc_, dofs); }

void PointMass::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  // Written for linear centerlines (ANCF): m S^T (S a - g).
  if (release_.gone(ctx)) return;
  CenterlineSample p;
  body_->sample(loc_, s_, in.q, p);
  const int n = loc_.count;
  const auto S = p.r_q[0].leftCols(n);
  const Eigen::Map<const Eigen::VectorXd> a(in.a, n);
  Eigen::Map<Eigen::VectorXd>(residual, n) += mass_ * S.transpose() * (S * a - ctx.loadFactor * gravity_);
  if (J)
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(J, n, n) +=
      ctx.kin.cA * mass_ * S.transpose() * S;
}

void PointMass::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  if (release_.gone(ctx)) return;
  CenterlineSample p;
  body_->sample(loc_, s_, in.q, p);
  const int n = loc_.count;
  const Vec2 vel = p.r_q[0].leftCols(n) * Eigen::Map<const Eigen::VectorXd>(in.v, n);
  e.kinetic += 0.5 * mass_ * vel.squaredNorm();
  e.potential -= ctx.loadFactor * mass_ * gravity_.dot(p.r[0]);
}

} // namespace boomdyn
