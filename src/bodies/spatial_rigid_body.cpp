#include "boomdyn/spatial_rigid_body.hpp"

#include "boomdyn/euler_parameters.hpp"

namespace boomdyn {

namespace {
// The mass along p in units of the mean moment of inertia: 4 G^T J' G
// gives the other directions 4 J.
constexpr double kMassAlongP = 4.0;
} // namespace


SpatialRigidBody::SpatialRigidBody(std::string name, double length, double mass, const Mat3 &inertia,
                                   const Vec3 &centerOfMass, const Vec3 &origin, const Mat3 &axes, PetscInt first)
  : SpatialBody(std::move(name), length, first), mass_(mass), inertia_(inertia), centerOfMass_(centerOfMass),
    origin_(origin), axes_(axes)
{
}

void SpatialRigidBody::initialCoordinates(double *q) const
{
  Eigen::Map<Vec3> x(q);
  Eigen::Map<euler::Vec4> p(q + 3);
  x = origin_ + axes_ * centerOfMass_;
  p = euler::fromRotation(axes_);
}

void SpatialRigidBody::initialVelocities(double *v) const
{
  // The centre of mass moves with v0 + omega x (R c'); pdot = 1/2 E(p)^T omega.
  const euler::Vec4 p = euler::fromRotation(axes_);
  Eigen::Map<Vec3> xd(v);
  Eigen::Map<euler::Vec4> pd(v + 3);
  xd = velocity_ + angularVelocity_.cross(axes_ * centerOfMass_);
  pd = 0.5 * euler::globalRateMatrix(p).transpose() * angularVelocity_;
}

SpatialLocation SpatialRigidBody::locate(double s) const
{
  SpatialLocation loc;
  loc.count = 7;
  loc.s = s;
  loc.end = length_;
  for (int k = 0; k < 7; ++k) loc.dofs[k] = first_ + k;
  return loc;
}

void SpatialRigidBody::sample(const SpatialLocation &, double s, const double *q, SpatialSample &out) const
{
  const euler::Vec4 p(q[3], q[4], q[5], q[6]);
  const Vec3 u = bodyPoint(s);
  out.triad = euler::rotation(p);
  out.r = Vec3(q[0], q[1], q[2]) + out.triad * u;
  out.r_q.setZero();
  out.r_q.leftCols<3>().setIdentity();
  out.r_q.block<3, 4>(0, 3) = euler::rotationDerivative(p, u);
  for (int k = 0; k < 3; ++k) {
    out.d_q[k].setZero();
    out.d_q[k].block<3, 4>(0, 3) = euler::rotationDerivative(p, Vec3::Unit(k));
  }
}

void SpatialRigidBody::curvatureTerm(const SpatialLocation &, double s, const double *, SpatialField field,
                                     const Vec3 &w, SpatialHessian &H) const
{
  H.setZero();
  const Vec3 u = field == SpatialField::Position ? bodyPoint(s) : Vec3::Unit(static_cast<int>(field) - 1);
  H.block<4, 4>(3, 3) = euler::rotationHessian(w, u);
}

void SpatialRigidInertia::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.resize(7);
  for (int k = 0; k < 7; ++k) dofs[k] = body_->firstCoordinate() + k;
}

void SpatialRigidInertia::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *r, double *J) const
{
  const double m = body_->mass();
  for (int i = 0; i < 3; ++i) r[i] += m * (in.a[i] - ctx.loadFactor * gravity_[i]);
  euler::RotaryInertia rot;
  const Eigen::Map<const euler::Vec4> p(in.q + 3), v(in.v + 3), a(in.a + 3);
  euler::rotaryInertia(body_->inertia(), p, v, a, rot, J != nullptr);
  // 4 G^T J' G is singular along p itself, whose motion only the
  // normalization row decides. k p (p . a + v . v), zero on every motion
  // that keeps |p| = 1 (the second time derivative of (p . p - 1)/2), gives
  // that direction the mass k: a regular mass matrix, without which
  // generalized-alpha lost an order (docs/model.md §9.1).
  const double k = kMassAlongP * body_->inertia().trace() / 3.0, c = p.dot(a) + v.dot(v);
  Eigen::Map<euler::Vec4>(r + 3) += rot.force + k * c * p;
  if (!J) return;
  Eigen::Map<Eigen::Matrix<double, 7, 7, Eigen::RowMajor>> Jm(J);
  const Kinematics &kin = ctx.kin;
  for (int i = 0; i < 3; ++i) Jm(i, i) += kin.cA * m;
  Jm.block<4, 4>(3, 3) += kin.cA * (rot.dA + k * p * p.transpose()) + kin.cV * (rot.dV + 2.0 * k * p * v.transpose()) +
                          kin.cQ * (rot.dP + k * (c * Eigen::Matrix4d::Identity() + p * a.transpose()));
}

void SpatialRigidInertia::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  const double m = body_->mass();
  const Eigen::Map<const Vec3> x(in.q), xd(in.v);
  e.kinetic += 0.5 * m * xd.squaredNorm() +
               euler::rotaryKineticEnergy(body_->inertia(), Eigen::Map<const euler::Vec4>(in.q + 3),
                                          Eigen::Map<const euler::Vec4>(in.v + 3));
  e.potential -= ctx.loadFactor * m * gravity_.dot(x);
}

void SpatialRigidInertia::scales(const ItemValues &, double &massDiag, double &, int &count) const
{
  massDiag += 3.0 * body_->mass();
  count += 3;
}

void EulerNormalization::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.resize(4);
  for (int k = 0; k < 4; ++k) dofs[k] = first_ + k;
}

void EulerNormalization::evaluate(double, const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  const Eigen::Map<const euler::Vec4> p(q);
  out.C.setConstant(1, p.squaredNorm() - 1.0);
  out.Cq = 2.0 * p.transpose();
  if (v) {
    const Eigen::Map<const euler::Vec4> pd(v);
    out.gamma.setConstant(1, 2.0 * pd.squaredNorm());
    out.Ct.setZero(1);
  }
  if (w) out.H = 2.0 * w[0] * Eigen::Matrix4d::Identity();
}

} // namespace boomdyn
