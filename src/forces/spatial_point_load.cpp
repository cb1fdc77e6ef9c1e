#include "boomdyn/spatial_point_load.hpp"

#include "boomdyn/euler_parameters.hpp"

namespace boomdyn {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

SpatialPointLoad::SpatialPointLoad(std::string name, const SpatialBody &body, double s, Parts parts, TimeFunction scale)
  : name_(std::move(name)), body_(&body), s_(s), loc_(body.locate(s)), parts_(parts), scale_(std::move(scale))
{
}

void SpatialPointLoad::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.assign(loc_.dofs.begin(), loc_.dofs.begin() + loc_.count);
}

void SpatialPointLoad::generalizedForce(const double *q, Eigen::VectorXd &Q, Eigen::MatrixXd *K) const
{
  const int n = loc_.count;
  SpatialSample p;
  body_->sample(loc_, s_, q, p);
  const Vec3 f = parts_.force + p.triad * parts_.followerForce;
  const Vec3 m = parts_.moment + p.triad * parts_.followerMoment;
  const bool anyMoment = !m.isZero(0);
  Q = p.r_q.leftCols(n).transpose() * f;
  // W^T m = 1/2 sum_k d(d_k)/dq^T (m x d_k).
  if (anyMoment)
    for (int k = 0; k < 3; ++k) Q += 0.5 * p.d_q[k].leftCols(n).transpose() * m.cross(p.triad.col(k));
  if (!K) return;
  SpatialHessian h;
  K->setZero(n, n);
  body_->curvatureTerm(loc_, s_, q, SpatialField::Position, f, h);
  *K += h.topLeftCorner(n, n);
  // Follower parts: df/dq = sum_j f'_j d(d_j)/dq, likewise dm/dq.
  Eigen::MatrixXd fq = Eigen::MatrixXd::Zero(3, n), mq = Eigen::MatrixXd::Zero(3, n);
  for (int j = 0; j < 3; ++j) {
    fq += parts_.followerForce[j] * p.d_q[j].leftCols(n);
    mq += parts_.followerMoment[j] * p.d_q[j].leftCols(n);
  }
  *K += p.r_q.leftCols(n).transpose() * fq;
  if (!anyMoment) return;
  const Mat3 M = euler::skew(m);
  for (int k = 0; k < 3; ++k) {
    const Vec3 dk = p.triad.col(k);
    body_->curvatureTerm(loc_, s_, q, static_cast<SpatialField>(k + 1), 0.5 * m.cross(dk), h);
    *K += h.topLeftCorner(n, n);
    // d(m x d_k)/dq = [m]x d(d_k)/dq - [d_k]x dm/dq.
    *K += 0.5 * p.d_q[k].leftCols(n).transpose() * (M * p.d_q[k].leftCols(n) - euler::skew(dk) * mq);
  }
}

void SpatialPointLoad::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  const int n = loc_.count;
  const double scale = ctx.loadFactor * scale_.value(ctx.t);
  Eigen::VectorXd Q;
  Eigen::MatrixXd K;
  generalizedForce(in.q, Q, J ? &K : nullptr);
  Eigen::Map<Eigen::VectorXd>(residual, n) -= scale * Q;
  if (J) Eigen::Map<RowMajor>(J, n, n) -= (ctx.kin.cQ * scale) * K;
}

void SpatialPointLoad::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  // The fixed force has the potential -s(t) F . r (as the planar point
  // force); follower parts and moments have none: their power Q . v is
  // fed in as input power.
  SpatialSample p;
  body_->sample(loc_, s_, in.q, p);
  const double scale = ctx.loadFactor * scale_.value(ctx.t);
  e.potential -= scale * parts_.force.dot(p.r);
  e.inputPower -= ctx.loadFactor * scale_.rate(ctx.t) * parts_.force.dot(p.r);
  if (const double before = scale_.rateBefore(ctx.t), after = scale_.rate(ctx.t); before != after)
    e.inputPowerJump -= ctx.loadFactor * (before - after) * parts_.force.dot(p.r);
  if (parts_.followerForce.isZero(0) && parts_.moment.isZero(0) && parts_.followerMoment.isZero(0)) return;
  Parts rest = parts_;
  rest.force.setZero();
  const SpatialPointLoad other(name_, *body_, s_, rest, scale_);
  Eigen::VectorXd Q;
  other.generalizedForce(in.q, Q, nullptr);
  e.inputPower += scale * Q.dot(Eigen::Map<const Eigen::VectorXd>(in.v, loc_.count));
}

SpatialPointMass::SpatialPointMass(std::string name, const SpatialBody &body, double s, double mass, const Mat3 &rotary,
                                   const Vec3 &gravity, Release release)
  : name_(std::move(name)), body_(&body), s_(s), loc_(body.locate(s)), mass_(mass), rotary_(rotary),
    hasRotary_(!rotary.isZero(0)), gravity_(gravity), release_(release)
{
}

void SpatialPointMass::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.assign(loc_.dofs.begin(), loc_.dofs.begin() + loc_.count);
}

void SpatialPointMass::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  if (release_.gone(ctx)) return;
  const int n = loc_.count;
  SpatialSample p;
  body_->sample(loc_, s_, in.q, p);
  const Eigen::Map<const Eigen::VectorXd> v(in.v, n), a(in.a, n);
  const auto rq = p.r_q.leftCols(n);
  // r'' = r_q a + (v^T H_c v)_c, H_c = d2 r_c / dq2 (constant in q).
  SpatialHessian h[3];
  Vec3 quad;
  for (int c = 0; c < 3; ++c) {
    body_->curvatureTerm(loc_, s_, in.q, SpatialField::Position, Vec3::Unit(c), h[c]);
    quad[c] = v.dot(h[c].topLeftCorner(n, n) * v);
  }
  const Vec3 f = mass_ * (rq * a + quad - ctx.loadFactor * gravity_);
  Eigen::Map<Eigen::VectorXd> r(residual, n);
  r += rq.transpose() * f;
  euler::RotaryInertia rot;
  // Rotary inertia through the Euler parameters of a rigid body (coordinates 3..6).
  if (hasRotary_) {
    euler::rotaryInertia(rotary_, Eigen::Map<const euler::Vec4>(in.q + 3), Eigen::Map<const euler::Vec4>(in.v + 3),
                         Eigen::Map<const euler::Vec4>(in.a + 3), rot, J != nullptr);
    r.segment<4>(3) += rot.force;
  }
  if (!J) return;
  Eigen::Map<RowMajor> Jm(J, n, n);
  const Kinematics &k = ctx.kin;
  Eigen::MatrixXd dv(3, n);
  for (int c = 0; c < 3; ++c) dv.row(c) = 2.0 * (h[c].topLeftCorner(n, n) * v).transpose();
  SpatialHessian hf;
  body_->curvatureTerm(loc_, s_, in.q, SpatialField::Position, f, hf);
  Jm += k.cA * mass_ * rq.transpose() * rq + k.cV * mass_ * rq.transpose() * dv + k.cQ * hf.topLeftCorner(n, n);
  // d(r_q a)/dq = sum_c a^T H_c: the mass times r_q^T of it.
  Eigen::MatrixXd da(3, n);
  for (int c = 0; c < 3; ++c) da.row(c) = (h[c].topLeftCorner(n, n) * a).transpose();
  Jm += k.cQ * mass_ * rq.transpose() * da;
  if (hasRotary_) Jm.block<4, 4>(3, 3) += k.cA * rot.dA + k.cV * rot.dV + k.cQ * rot.dP;
}

void SpatialPointMass::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  if (release_.gone(ctx)) return;
  const int n = loc_.count;
  SpatialSample p;
  body_->sample(loc_, s_, in.q, p);
  const Vec3 vel = p.r_q.leftCols(n) * Eigen::Map<const Eigen::VectorXd>(in.v, n);
  e.kinetic += 0.5 * mass_ * vel.squaredNorm();
  if (hasRotary_)
    e.kinetic += euler::rotaryKineticEnergy(rotary_, Eigen::Map<const euler::Vec4>(in.q + 3),
                                            Eigen::Map<const euler::Vec4>(in.v + 3));
  e.potential -= ctx.loadFactor * mass_ * gravity_.dot(p.r);
}

void SpatialPointMass::scales(const ItemValues &, double &massDiag, double &, int &count) const
{
  massDiag += 3.0 * mass_;
  count += 3;
}

} // namespace boomdyn
