#include "boomdyn/rigid_body.hpp"

#include <cmath>

namespace boomdyn {

RigidBody::RigidBody(std::string name, double length, double mass, Vec2 origin, double angle, PetscInt first)
  : Body(std::move(name), length, first), mass_(mass), origin_(origin), angle_(angle)
{
}

void RigidBody::initialCoordinates(double *q) const
{
  const Vec2 c = origin_ + 0.5 * length_ * Vec2(std::cos(angle_), std::sin(angle_));
  q[0] = c.x(), q[1] = c.y(), q[2] = angle_;
}

CenterlineLocation RigidBody::locate(double s) const
{
  CenterlineLocation loc;
  loc.count = 3;
  loc.s = s;
  loc.end = length_;
  for (int k = 0; k < 3; ++k) loc.dofs[k] = first_ + k;
  return loc;
}

void RigidBody::sample(const CenterlineLocation &, double s, const double *q, CenterlineSample &out) const
{
  const double a = s - 0.5 * length_, c = std::cos(q[2]), sn = std::sin(q[2]);
  const Vec2 dir(c, sn), perp(-sn, c);
  for (auto &m : out.r_q) m.setZero();
  out.r[0] = Vec2(q[0], q[1]) + a * dir;
  out.r[1] = dir;
  out.r[2] = out.r[3] = Vec2::Zero();
  out.r_q[0](0, 0) = 1.0;
  out.r_q[0](1, 1) = 1.0;
  out.r_q[0].col(2) = a * perp;
  out.r_q[1].col(2) = perp;
  out.linear = false;
}

void RigidBody::curvatureTerm(const CenterlineLocation &, double s, const double *q, int k, const Vec2 &w,
                              Eigen::Matrix<double, 8, 8> &H) const
{
  // d2/dtheta2 of (cos, sin) is -(cos, sin); r'' and r''' vanish.
  H.setZero();
  const Vec2 dir(std::cos(q[2]), std::sin(q[2]));
  if (k == 0) H(2, 2) = -(s - 0.5 * length_) * w.dot(dir);
  else if (k == 1) H(2, 2) = -w.dot(dir);
}

void RigidBodyItem::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.resize(3);
  for (int k = 0; k < 3; ++k) dofs[k] = body_->firstCoordinate() + k;
}

void RigidBodyItem::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *r, double *J) const
{
  const double m = body_->mass(), I = body_->inertia();
  r[0] += m * (in.a[0] - ctx.loadFactor * gravity_.x());
  r[1] += m * (in.a[1] - ctx.loadFactor * gravity_.y());
  r[2] += I * in.a[2];
  if (J) {
    J[0] += ctx.kin.cA * m;
    J[4] += ctx.kin.cA * m;
    J[8] += ctx.kin.cA * I;
  }
}

void RigidBodyItem::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  const double m = body_->mass();
  e.kinetic += 0.5 * (m * (in.v[0] * in.v[0] + in.v[1] * in.v[1]) + body_->inertia() * in.v[2] * in.v[2]);
  e.potential -= ctx.loadFactor * m * (gravity_.x() * in.q[0] + gravity_.y() * in.q[1]);
}

void RigidBodyItem::scales(const ItemValues &, double &massDiag, double &, int &count) const
{
  massDiag += 2.0 * body_->mass();
  count += 2;
}

} // namespace boomdyn
