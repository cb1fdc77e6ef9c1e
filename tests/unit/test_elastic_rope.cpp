// The elastic tension-only rope (elastic_rope.hpp) as a kernel: its residual
// derivatives against central finite differences at random taut states
// (cQ block: d residual/dq with the damping's dl'/dq term; cV block:
// d residual/dv), over two pulleys on ANCF beams and a rigid body
// (curvature terms); and no force and no Jacobian while slack.
#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/elastic_rope.hpp"
#include "boomdyn/rigid_body.hpp"
#include "boomdyn/rope.hpp"
#include "rope_test_bodies.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace boomdyn;

namespace {

struct Residual {
  std::vector<double> r, J;
};

Residual evaluate(const ElasticRope &rope, const std::vector<double> &q, const std::vector<double> &v, double cQ,
                  double cV, double t = 0.0)
{
  const std::size_t n = q.size();
  Residual out{std::vector<double>(n, 0.0), std::vector<double>(n * n, 0.0)};
  AssemblyContext ctx;
  ctx.t = t;
  ctx.kin.cQ = cQ, ctx.kin.cV = cV;
  const std::vector<double> a(n, 0.0);
  rope.evaluate(ctx, ItemValues{q.data(), v.data(), a.data(), nullptr}, out.r.data(), out.J.data());
  return out;
}

} // namespace

TEST(ElasticRope, JacobianMatchesFiniteDifferencesOverTwoPulleys)
{
  const rope_test::Bodies bodies;
  const auto &[b1, b2, b3, q0] = bodies;
  const RopePath path({{&b1, 0.3}, {&b2, 2.0}, {&b3, 0.0}, {&b1, 1.7}}); // a pulley inside an element, one on a node
  std::vector<PetscInt> dofs;
  path.coordinates(dofs);
  std::vector<double> qp;
  for (PetscInt d : dofs) qp.push_back(q0[d]);
  const double l0 = path.length(qp.data());
  const ElasticRope rope("rope", path, 1.2e7, 0.95 * l0, 3.0e4); // 5 % stretch: taut at every draw
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::size_t n = qp.size();
  double worstQ = 0, worstV = 0, scale = 0;
  for (int draw = 0; draw < 5; ++draw) {
    std::vector<double> q = qp, v(n);
    for (std::size_t i = 0; i < n; ++i) q[i] += 0.01 * u(rng), v[i] = 0.5 * u(rng);
    ASSERT_TRUE(rope.state(0.0, q.data(), v.data()).taut);
    const Residual atQ = evaluate(rope, q, v, 1.0, 0.0), atV = evaluate(rope, q, v, 0.0, 1.0);
    for (std::size_t j = 0; j < n; ++j) {
      const double hq = 1e-7, hv = 1e-4;
      std::vector<double> qa = q, qb = q, va = v, vb = v;
      qa[j] += hq, qb[j] -= hq, va[j] += hv, vb[j] -= hv;
      const Residual rqa = evaluate(rope, qa, v, 1, 0), rqb = evaluate(rope, qb, v, 1, 0);
      const Residual rva = evaluate(rope, q, va, 1, 0), rvb = evaluate(rope, q, vb, 1, 0);
      for (std::size_t i = 0; i < n; ++i) {
        worstQ = std::max(worstQ, std::abs((rqa.r[i] - rqb.r[i]) / (2 * hq) - atQ.J[i * n + j]));
        worstV = std::max(worstV, std::abs((rva.r[i] - rvb.r[i]) / (2 * hv) - atV.J[i * n + j]));
        scale = std::max(scale, std::abs(atQ.J[i * n + j]));
      }
    }
  }
  PetscPrintf(PETSC_COMM_WORLD, "  elastic rope FD: max |J - FD| / max |J|: cQ block %.2e, cV block %.2e (max |J| %.3e)\n",
              worstQ / scale, worstV / scale, scale);
  EXPECT_LT(worstQ / scale, 1e-6);
  EXPECT_LT(worstV / scale, 1e-9); // the damping force is linear in v: exact up to round-off

  // Slack (L0 longer than the path): no force, no Jacobian.
  const ElasticRope slack("slack", path, 1.2e7, 1.05 * l0, 3.0e4);
  std::vector<double> v(n, 0.0);
  const Residual none = evaluate(slack, qp, v, 1.0, 1.0);
  for (double x : none.r) EXPECT_EQ(x, 0.0);
  for (double x : none.J) EXPECT_EQ(x, 0.0);
}

// A rope on a winch (L0(t) = L0 + dL0(t), hoisting at 0.4 m/s from t = 0.5 s
// on a ramp): at t = 1 s (inside the ramp) the Jacobian against central
// differences as above, and the energy statement of the winch power: along
// the motion q(t) = q + v (t - 1) the strain energy U(t, q(t)) changes at the
// rate d/dt U = T dl/dt + P - D (the rope's work on the bodies is -T dl/dt),
// with P the winch power and D the dissipation the item reports (central
// differences in t).
TEST(ElasticRope, WinchJacobianAndPowerMatchFiniteDifferences)
{
  const rope_test::Bodies bodies;
  const auto &[b1, b2, b3, q0] = bodies;
  const RopePath path({{&b1, 0.3}, {&b2, 2.0}, {&b3, 0.0}, {&b1, 1.7}});
  std::vector<PetscInt> dofs;
  path.coordinates(dofs);
  std::vector<double> qp;
  for (PetscInt d : dofs) qp.push_back(q0[d]);
  const double l0 = path.length(qp.data()), t = 1.0;
  const ElasticRope rope("rope", path, 1.2e7, 0.97 * l0, 3.0e4, TimeFunction::ramp(0.5, 2.0, 0.0, -0.6));
  ASSERT_TRUE(rope.hasWinch());
  EXPECT_DOUBLE_EQ(rope.restLength(t), 0.97 * l0 - 0.2);
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::size_t n = qp.size();
  double worstQ = 0, worstV = 0, scale = 0, worstPower = 0, powerScale = 0;
  for (int draw = 0; draw < 5; ++draw) {
    std::vector<double> q = qp, v(n), a(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) q[i] += 0.01 * u(rng), v[i] = 0.5 * u(rng);
    const ElasticRope::State st = rope.state(t, q.data(), v.data());
    ASSERT_TRUE(st.taut);
    EXPECT_DOUBLE_EQ(st.payoutRate, -0.4);
    const Residual atQ = evaluate(rope, q, v, 1.0, 0.0, t), atV = evaluate(rope, q, v, 0.0, 1.0, t);
    for (std::size_t j = 0; j < n; ++j) {
      const double hq = 1e-7, hv = 1e-4;
      std::vector<double> qa = q, qb = q, va = v, vb = v;
      qa[j] += hq, qb[j] -= hq, va[j] += hv, vb[j] -= hv;
      const Residual rqa = evaluate(rope, qa, v, 1, 0, t), rqb = evaluate(rope, qb, v, 1, 0, t);
      const Residual rva = evaluate(rope, q, va, 1, 0, t), rvb = evaluate(rope, q, vb, 1, 0, t);
      for (std::size_t i = 0; i < n; ++i) {
        worstQ = std::max(worstQ, std::abs((rqa.r[i] - rqb.r[i]) / (2 * hq) - atQ.J[i * n + j]));
        worstV = std::max(worstV, std::abs((rva.r[i] - rvb.r[i]) / (2 * hv) - atV.J[i * n + j]));
        scale = std::max(scale, std::abs(atQ.J[i * n + j]));
      }
    }
    // Energy: U(t, q(t)) by central differences along the motion.
    auto strainAt = [&](double dt) {
      std::vector<double> qs = q;
      for (std::size_t i = 0; i < n; ++i) qs[i] += v[i] * dt;
      AssemblyContext ctx;
      ctx.t = t + dt;
      EnergyParts e;
      rope.energy(ctx, ItemValues{qs.data(), v.data(), a.data(), nullptr}, e);
      return e.strain;
    };
    const double dt = 1e-6, dUdt = (strainAt(dt) - strainAt(-dt)) / (2 * dt);
    AssemblyContext ctx;
    ctx.t = t;
    EnergyParts e;
    rope.energy(ctx, ItemValues{q.data(), v.data(), a.data(), nullptr}, e);
    EXPECT_DOUBLE_EQ(e.inputPower, st.winchPower);
    EXPECT_GT(st.winchPower, 0); // hoisting a taut rope
    worstPower = std::max(worstPower, std::abs((dUdt - st.tension * st.rate) - (e.inputPower - e.dissipation)));
    powerScale = std::max(powerScale, std::abs(st.winchPower));
  }
  PetscPrintf(PETSC_COMM_WORLD,
              "  winch rope FD: max |J - FD| / max |J|: cQ %.2e, cV %.2e; energy rate vs P - D: %.2e relative\n",
              worstQ / scale, worstV / scale, worstPower / powerScale);
  EXPECT_LT(worstQ / scale, 1e-6);
  EXPECT_LT(worstV / scale, 1e-9);
  EXPECT_LT(worstPower / powerScale, 1e-6);
  std::vector<double> breaks;
  rope.breakpoints(breaks);
  ASSERT_EQ(breaks.size(), 2u); // the ramp's start and end: the winch speed jumps
  EXPECT_DOUBLE_EQ(breaks[0], 0.5);
  EXPECT_DOUBLE_EQ(breaks[1], 2.0);
}

// The shared path geometry gives the inextensible rope the same length and
// gradient as before (C = L - l, C_q = -l_q).
TEST(ElasticRope, PathAgreesWithTheRigidRope)
{
  const rope_test::Bodies bodies;
  const auto &[b1, b2, b3, q0] = bodies;
  const Rope rope("rope", {&b1, 1.9}, {&b2, 2.0}, {&b3, 0.0}, 3.0);
  const RopePath path({{&b1, 1.9}, {&b2, 2.0}, {&b3, 0.0}});
  std::vector<PetscInt> dofs;
  path.coordinates(dofs);
  std::vector<double> q;
  for (PetscInt d : dofs) q.push_back(q0[d]);
  ConstraintEval e;
  rope.evaluate(0, q.data(), nullptr, nullptr, e);
  Eigen::RowVectorXd lq;
  const double l = path.evaluate(q.data(), lq);
  EXPECT_DOUBLE_EQ(e.C[0], 3.0 - l);
  EXPECT_LT((e.Cq + lq).norm(), 1e-15 * lq.norm());
}

// A segment of zero length (a pulley on the rope's end point, here reached
// at run time) has no direction: the force is NaN. It must not be taken for
// slack (no force): the residual is NaN, so no step is accepted, the rope
// names itself in fault() for the run's message, and its tension output is
// NaN, not 0. Its path reports the segment (RopePath::shortSegment), which
// the rope types refuse at t = 0.
TEST(ElasticRope, NaNForceIsAnErrorNamingTheRopeNotSlack)
{
  const rope_test::Bodies bodies;
  const auto &[b1, b2, b3, q0] = bodies;
  const RopePath path({{&b1, 2.0}, {&b1, 2.0}, {&b3, 0.0}}); // the pulley on the first end's point
  std::vector<PetscInt> dofs;
  path.coordinates(dofs);
  std::vector<double> q;
  for (PetscInt d : dofs) q.push_back(q0[d]);
  EXPECT_EQ(path.shortSegment(q.data()), 0);
  EXPECT_EQ(path.segmentLengths(q.data())[0], 0.0);
  const ElasticRope rope("hoist", path, 1.2e7, 0.9 * path.length(q.data()), 0.0);
  EXPECT_TRUE(rope.fault().empty());
  const std::vector<double> v(q.size(), 0.0);
  const Residual r = evaluate(rope, q, v, 1.0, 0.0);
  bool allNaN = true;
  for (double x : r.r) allNaN = allNaN && std::isnan(x);
  EXPECT_TRUE(allNaN) << "a NaN force is not slack: the residual says so";
  EXPECT_NE(rope.fault().find("elastic_rope 'hoist'"), std::string::npos) << rope.fault();
  EXPECT_NE(rope.fault().find("not finite"), std::string::npos) << rope.fault();
  EXPECT_TRUE(std::isnan(rope.state(0.0, q.data(), v.data()).tension));
  // A path whose segments all have length keeps shortSegment at -1.
  const RopePath good({{&b1, 0.3}, {&b2, 2.0}, {&b3, 0.0}});
  good.coordinates(dofs);
  std::vector<double> qg;
  for (PetscInt d : dofs) qg.push_back(q0[d]);
  EXPECT_EQ(good.shortSegment(qg.data()), -1);
}
