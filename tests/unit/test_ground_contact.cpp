// The ground contact (ground_contact.hpp) as a kernel: residual derivatives
// against central finite differences at random states in contact (cQ and
// cV blocks) on an ANCF beam and on a rigid body (curvature of its height);
// no force and no Jacobian above the ground line; the force is k (y_g - y) - c y'.
#include "boomdyn/ground_contact.hpp"
#include "rope_test_bodies.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace boomdyn;

namespace {

std::vector<double> residualOf(const GroundContact &c, const std::vector<double> &q, const std::vector<double> &v,
                               double cQ, double cV, std::vector<double> *J)
{
  const std::size_t n = q.size();
  std::vector<double> r(n, 0.0), a(n, 0.0);
  if (J) J->assign(n * n, 0.0);
  AssemblyContext ctx;
  ctx.kin.cQ = cQ, ctx.kin.cV = cV;
  c.evaluate(ctx, ItemValues{q.data(), v.data(), a.data(), nullptr}, r.data(), J ? J->data() : nullptr);
  return r;
}

} // namespace

TEST(GroundContact, JacobianMatchesFiniteDifferencesOnBeamAndRigidBody)
{
  const rope_test::Bodies bodies;
  const auto &[b1, b2, b3, q0] = bodies;
  const std::pair<const Body *, double> points[] = {{&b1, 1.3}, {&b3, 1.7}};
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto &[body, s] : points) {
    const CenterlineLocation loc = body->locate(s);
    std::vector<double> qp;
    for (int i = 0; i < loc.count; ++i) qp.push_back(q0[loc.dofs[i]]);
    CenterlineSample p;
    body->sample(loc, s, qp.data(), p);
    const GroundContact contact("foot", *body, s, p.r[0].y() + 0.05, 1e7, 2e3); // 5 cm deep: in contact at every draw
    const std::size_t n = qp.size();
    double worstQ = 0, worstV = 0, scale = 0;
    for (int draw = 0; draw < 5; ++draw) {
      std::vector<double> q = qp, v(n);
      for (std::size_t i = 0; i < n; ++i) q[i] += 0.005 * u(rng), v[i] = 0.5 * u(rng);
      const GroundContact::State st = contact.state(q.data(), v.data());
      ASSERT_TRUE(st.contact);
      EXPECT_NEAR(st.force, -1e7 * st.gap - 2e3 * st.rate, 1e-9 * st.force);
      std::vector<double> JQ, JV;
      residualOf(contact, q, v, 1, 0, &JQ);
      residualOf(contact, q, v, 0, 1, &JV);
      for (std::size_t j = 0; j < n; ++j) {
        const double hq = 1e-7, hv = 1e-4;
        std::vector<double> qa = q, qb = q, va = v, vb = v;
        qa[j] += hq, qb[j] -= hq, va[j] += hv, vb[j] -= hv;
        const auto rqa = residualOf(contact, qa, v, 1, 0, nullptr), rqb = residualOf(contact, qb, v, 1, 0, nullptr);
        const auto rva = residualOf(contact, q, va, 1, 0, nullptr), rvb = residualOf(contact, q, vb, 1, 0, nullptr);
        for (std::size_t i = 0; i < n; ++i) {
          worstQ = std::max(worstQ, std::abs((rqa[i] - rqb[i]) / (2 * hq) - JQ[i * n + j]));
          worstV = std::max(worstV, std::abs((rva[i] - rvb[i]) / (2 * hv) - JV[i * n + j]));
          scale = std::max(scale, std::abs(JQ[i * n + j]));
        }
      }
    }
    std::printf("  ground contact FD on %s: cQ %.2e, cV %.2e of max |J| %.3e\n", body->name().c_str(), worstQ / scale,
                worstV / scale, scale);
    EXPECT_LT(worstQ / scale, 1e-6);
    EXPECT_LT(worstV / scale, 1e-9);
    // Above the ground line: nothing.
    const GroundContact above("foot", *body, s, p.r[0].y() - 0.05, 1e7, 2e3);
    std::vector<double> J, v(n, 0.0);
    for (double x : residualOf(above, qp, v, 1, 1, &J)) EXPECT_EQ(x, 0.0);
    for (double x : J) EXPECT_EQ(x, 0.0);
  }
}
