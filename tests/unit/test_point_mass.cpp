// Point masses (point_load.hpp): the rigid-body kernel's residual
// derivatives against central finite differences at random states (cQ,
// cV and cA blocks: the centripetal term depends on theta and theta'), its
// residual against r_q^T m (r'' - g) with r'' from differences of r(q(t));
// and the quick release: present in the step that lands on release_at,
// gone at its restart (right limit) and after.
#include "boomdyn/point_load.hpp"
#include "boomdyn/rigid_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace boomdyn;

namespace {

std::vector<double> residualOf(const WorkItem &item, const AssemblyContext &ctx, const std::vector<double> &q,
                               const std::vector<double> &v, const std::vector<double> &a, std::vector<double> *J)
{
  std::vector<double> r(3, 0.0);
  if (J) J->assign(9, 0.0);
  item.evaluate(ctx, ItemValues{q.data(), v.data(), a.data(), nullptr}, r.data(), J ? J->data() : nullptr);
  return r;
}

} // namespace

TEST(RigidPointMass, JacobianAndAccelerationMatchFiniteDifferences)
{
  const RigidBody body("payload", 2.0, 100.0, Vec2(0, 0), 0.3, 0);
  const RigidPointMass mass("hook", body, 1.6, 250.0, Vec2(0, -9.81)); // 0.6 m from the centre
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst[3] = {0, 0, 0}, scale = 0, worstResidual = 0;
  for (int draw = 0; draw < 5; ++draw) {
    std::vector<double> q{u(rng), u(rng), 3 * u(rng)}, v{u(rng), u(rng), 2 * u(rng)}, a{u(rng), u(rng), 5 * u(rng)};
    for (int block = 0; block < 3; ++block) { // cQ, cV, cA
      AssemblyContext ctx;
      ctx.kin = {block == 0 ? 1.0 : 0.0, block == 1 ? 1.0 : 0.0, block == 2 ? 1.0 : 0.0};
      std::vector<double> J;
      residualOf(mass, ctx, q, v, a, &J);
      for (int j = 0; j < 3; ++j) {
        const double h = 1e-6;
        std::vector<double> p[2] = {block == 0 ? q : block == 1 ? v : a, block == 0 ? q : block == 1 ? v : a};
        p[0][j] += h, p[1][j] -= h;
        auto at = [&](const std::vector<double> &x) {
          return residualOf(mass, ctx, block == 0 ? x : q, block == 1 ? x : v, block == 2 ? x : a, nullptr);
        };
        const std::vector<double> ra = at(p[0]), rb = at(p[1]);
        for (int i = 0; i < 3; ++i) {
          worst[block] = std::max(worst[block], std::abs((ra[i] - rb[i]) / (2 * h) - J[3 * i + j]));
          scale = std::max(scale, std::abs(J[3 * i + j]));
        }
      }
    }
    // r'' along q(t) = q + v t + a t^2/2 by central differences of the sampled position.
    const CenterlineLocation loc = body.locate(1.6);
    auto position = [&](double t) {
      std::vector<double> qt(3);
      for (int i = 0; i < 3; ++i) qt[i] = q[i] + v[i] * t + 0.5 * a[i] * t * t;
      CenterlineSample s;
      body.sample(loc, 1.6, qt.data(), s);
      return std::make_pair(s.r[0], s.r_q[0]);
    };
    const double dt = 1e-4;
    const Vec2 acc = (position(dt).first - 2 * position(0).first + position(-dt).first) / (dt * dt);
    const Eigen::Matrix<double, 2, 3> rq = position(0).second.leftCols(3);
    const Eigen::Vector3d expected = rq.transpose() * (250.0 * (acc - Vec2(0, -9.81)));
    const std::vector<double> r = residualOf(mass, AssemblyContext{}, q, v, a, nullptr);
    for (int i = 0; i < 3; ++i) worstResidual = std::max(worstResidual, std::abs(r[i] - expected[i]) / expected.norm());
  }
  std::printf("  rigid point mass FD: cQ %.2e, cV %.2e, cA %.2e of max |J| %.3e; residual vs r_q^T m (r'' - g) %.2e\n",
              worst[0] / scale, worst[1] / scale, worst[2] / scale, scale, worstResidual);
  for (double w : worst) EXPECT_LT(w / scale, 1e-7);
  EXPECT_LT(worstResidual, 1e-6);
}

TEST(RigidPointMass, ReleaseRemovesInertiaAndWeightAfterTheBreakpoint)
{
  const RigidBody body("payload", 2.0, 100.0, Vec2(0, 0), 0.0, 0);
  Release release;
  release.at = 0.5;
  const RigidPointMass mass("part", body, 1.0, 250.0, Vec2(0, -9.81), release);
  std::vector<double> bps;
  mass.breakpoints(bps);
  ASSERT_EQ(bps.size(), 1u);
  EXPECT_EQ(bps[0], 0.5);
  const std::vector<double> q{0, 0, 0}, v{0, 0, 0}, a{0, 0, 0};
  AssemblyContext ctx;
  ctx.t = 0.5; // the step that lands on the release still carries the mass
  EXPECT_NEAR(residualOf(mass, ctx, q, v, a, nullptr)[1], 250.0 * 9.81, 1e-9);
  ctx.rightLimit = true; // its restart does not
  EXPECT_EQ(residualOf(mass, ctx, q, v, a, nullptr)[1], 0.0);
  ctx.rightLimit = false, ctx.t = 0.5000001;
  EXPECT_EQ(residualOf(mass, ctx, q, v, a, nullptr)[1], 0.0);
  EnergyParts e;
  mass.energy(ctx, ItemValues{q.data(), v.data(), a.data(), nullptr}, e);
  EXPECT_EQ(e.potential, 0.0);
}
