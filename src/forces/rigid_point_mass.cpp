// A point mass on a rigid body's axis (point_load.hpp): the payload of a
// hoist as a rigid body plus masses, each of which may be released.
#include "boomdyn/point_load.hpp"

#include <cmath>

namespace boomdyn {

RigidPointMass::RigidPointMass(std::string name, const Body &body, double s, double mass, Vec2 gravity,
                               Release release)
  : name_(std::move(name)), first_(body.firstCoordinate()), d_(s - 0.5 * body.length()), mass_(mass),
    gravity_(gravity), release_(release)
{
}

void RigidPointMass::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.resize(3);
  for (int k = 0; k < 3; ++k) dofs[k] = first_ + k;
}

void RigidPointMass::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *r, double *J) const
{
  if (release_.gone(ctx)) return;
  const double c = std::cos(in.q[2]), s = std::sin(in.q[2]), w = in.v[2], al = in.a[2], d = d_, m = mass_;
  // f = m (r'' - g), r'' = (a_x - d s al - d c w^2, a_y + d c al - d s w^2).
  const Vec2 g = ctx.loadFactor * gravity_;
  const double fx = m * (in.a[0] - d * s * al - d * c * w * w - g.x());
  const double fy = m * (in.a[1] + d * c * al - d * s * w * w - g.y());
  // r_q^T f with r_q = [1 0 -d s; 0 1 d c].
  r[0] += fx, r[1] += fy, r[2] += d * (-s * fx + c * fy);
  if (!J) return;
  const double rq[2][3] = {{1, 0, -d * s}, {0, 1, d * c}};
  // df/da = m r_q; df/dtheta' = m d w (-2c, -2s); df/dtheta = m d (-c al + s w^2, -s al - c w^2).
  const double dfdw[2] = {-2 * m * d * c * w, -2 * m * d * s * w};
  const double dfdth[2] = {m * d * (-c * al + s * w * w), m * d * (-s * al - c * w * w)};
  const Kinematics &k = ctx.kin;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double mass = 0;
      for (int a = 0; a < 2; ++a) mass += rq[a][i] * m * rq[a][j];
      J[3 * i + j] += k.cA * mass;
    }
    J[3 * i + 2] += k.cV * (rq[0][i] * dfdw[0] + rq[1][i] * dfdw[1]) + k.cQ * (rq[0][i] * dfdth[0] + rq[1][i] * dfdth[1]);
  }
  // d(r_q^T)/dtheta f: only the third row, d (-c fx - s fy).
  J[3 * 2 + 2] += k.cQ * d * (-c * fx - s * fy);
}

void RigidPointMass::energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const
{
  if (release_.gone(ctx)) return;
  const double c = std::cos(in.q[2]), s = std::sin(in.q[2]);
  const Vec2 r(in.q[0] + d_ * c, in.q[1] + d_ * s), vel(in.v[0] - d_ * s * in.v[2], in.v[1] + d_ * c * in.v[2]);
  e.kinetic += 0.5 * mass_ * vel.squaredNorm();
  e.potential -= ctx.loadFactor * mass_ * gravity_.dot(r);
}

void RigidPointMass::scales(const ItemValues &, double &massDiag, double &, int &count) const
{
  massDiag += 2.0 * mass_;
  count += 2;
}

} // namespace boomdyn
