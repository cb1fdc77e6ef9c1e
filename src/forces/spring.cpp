#include "boomdyn/spring.hpp"

#include <unsupported/Eigen/AutoDiff>

#include <array>

namespace boomdyn {

namespace {
using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;
}

Spring::Spring(std::string name, End a, End b, double stiffness, double restLength, double damping)
  : name_(std::move(name)), ends_{a, b}, k_(stiffness), L0_(restLength), c_(damping)
{
  for (int e = 0; e < 2; ++e)
    if (ends_[e].body) loc_[e] = ends_[e].body->locate(ends_[e].s);
}

void Spring::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.clear();
  for (int e = 0; e < 2; ++e)
    if (ends_[e].body) dofs.insert(dofs.end(), loc_[e].dofs.begin(), loc_[e].dofs.begin() + loc_[e].count);
}

void Spring::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  const Kinematics &k = ctx.kin;
  int n = 0, offset[2] = {0, 0};
  for (int e = 0; e < 2; ++e) offset[e] = n, n += ends_[e].body ? loc_[e].count : 0;
  auto constant = [&](double v) { return AD(v, Eigen::VectorXd::Zero(n)); };
  // Position and velocity of each end and the Jacobian entries r_q(c, m), as AD numbers.
  AD r[2][2], v[2][2];
  std::vector<std::array<std::vector<AD>, 2>> rq(2);
  for (int e = 0; e < 2; ++e) {
    for (int c = 0; c < 2; ++c) r[e][c] = constant(ends_[e].ground[c]), v[e][c] = constant(0.0);
    if (!ends_[e].body) continue;
    const int m0 = offset[e], cnt = loc_[e].count;
    CenterlineSample p;
    ends_[e].body->sample(loc_[e], ends_[e].s, in.q + m0, p);
    Eigen::Matrix<double, 8, 8> H[2];
    for (int c = 0; c < 2; ++c) {
      H[c].setZero();
      if (!p.linear) ends_[e].body->curvatureTerm(loc_[e], ends_[e].s, in.q + m0, 0, Vec2::Unit(c), H[c]);
      rq[e][c].resize(cnt);
      r[e][c] = constant(p.r[0][c]);
      for (int m = 0; m < cnt; ++m) {
        r[e][c].derivatives()[m0 + m] += k.cQ * p.r_q[0](c, m);
        AD entry = constant(p.r_q[0](c, m));
        for (int q = 0; q < cnt; ++q) entry.derivatives()[m0 + q] += k.cQ * H[c](m, q);
        rq[e][c][m] = entry;
        AD vm(in.v[m0 + m], n, m0 + m);
        vm.derivatives() *= k.cV;
        v[e][c] += entry * vm;
      }
    }
  }
  const AD dx = r[0][0] - r[1][0], dy = r[0][1] - r[1][1];
  AD fx, fy; // force pulling a towards b (and b towards a), times -1
  if (L0_ == 0) {
    // Zero rest length: the vector spring k d + c d', defined at d = 0 too.
    fx = k_ * dx + c_ * (v[0][0] - v[1][0]);
    fy = k_ * dy + c_ * (v[0][1] - v[1][1]);
  } else {
    const AD l = sqrt(dx * dx + dy * dy);
    const AD ux = dx / l, uy = dy / l;
    const AD ldot = ux * (v[0][0] - v[1][0]) + uy * (v[0][1] - v[1][1]);
    const AD tension = k_ * (l - L0_) + c_ * ldot;
    fx = tension * ux, fy = tension * uy;
  }
  for (int e = 0; e < 2; ++e) {
    if (!ends_[e].body) continue;
    const double sign = e == 0 ? 1.0 : -1.0; // residual = -Q: +T u on a, -T u on b
    for (int m = 0; m < loc_[e].count; ++m) {
      const AD rm = sign * (rq[e][0][m] * fx + rq[e][1][m] * fy);
      const int row = offset[e] + m;
      residual[row] += rm.value();
      if (J)
        for (int col = 0; col < n; ++col) J[row * n + col] += rm.derivatives()[col];
    }
  }
}

void Spring::energy(const AssemblyContext &, const ItemValues &in, EnergyParts &e) const
{
  Vec2 r[2];
  int offset = 0;
  for (int k = 0; k < 2; ++k) {
    r[k] = ends_[k].ground;
    if (!ends_[k].body) continue;
    CenterlineSample p;
    ends_[k].body->sample(loc_[k], ends_[k].s, in.q + offset, p);
    r[k] = p.r[0];
    offset += loc_[k].count;
  }
  const double stretch = (r[0] - r[1]).norm() - L0_;
  e.strain += 0.5 * k_ * stretch * stretch;
}

} // namespace boomdyn
