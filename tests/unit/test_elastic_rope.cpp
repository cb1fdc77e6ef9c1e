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

#include <random>

using namespace boomdyn;

namespace {

struct Residual {
  std::vector<double> r, J;
};

Residual evaluate(const ElasticRope &rope, const std::vector<double> &q, const std::vector<double> &v, double cQ,
                  double cV)
{
  const std::size_t n = q.size();
  Residual out{std::vector<double>(n, 0.0), std::vector<double>(n * n, 0.0)};
  AssemblyContext ctx;
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
    ASSERT_TRUE(rope.state(q.data(), v.data()).taut);
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
