// Compliant pad with clearance (PadContact) and LuGre friction driven by the
// pad force: residual Jacobians against central finite differences at random
// states in contact on either side and inside the clearance, in the dynamic
// iteration mode (cQ, cV, cA, cZ all nonzero) and the static mode; the pad
// residual against the gradient of its strain energy.
#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/lugre_friction.hpp"
#include "boomdyn/pad_contact.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace boomdyn;

namespace {

const ancf::Section kSection{1e8, 1e5, 30};
constexpr double kClearance = 0.01;

struct PadRig {
  AncfBeam track{"track", 2.0, 4, kSection, Vec2(0, 0), 0.1, 0};
  AncfBeam slider{"slider", 1.5, 3, kSection, Vec2(0.5, 0.05), 0.1, 36};
  std::shared_ptr<SlidingJoint> joint;
  PadContact pad;
  PadRig(double s, const PadSpec &spec)
    : joint(std::make_shared<SlidingJoint>("slide", track, slider, 0.3, 36 + 32, s, false)), pad(joint, spec)
  {
  }
};

// A random deformed state of the joint's coordinates with the slider point
// moved along the track normal so that the signed gap is `gap`.
std::vector<double> stateWithGap(const PadRig &su, double s, double gap, std::mt19937 &rng)
{
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  std::vector<double> q0(69);
  su.track.initialCoordinates(q0.data());
  su.slider.initialCoordinates(q0.data() + 36);
  q0[68] = s;
  std::vector<PetscInt> dofs;
  su.joint->coordinates(dofs);
  std::vector<double> q(dofs.size());
  for (std::size_t i = 0; i < dofs.size(); ++i) q[i] = q0[dofs[i]] + u(rng);
  double d;
  Eigen::VectorXd dq;
  Eigen::MatrixXd dqq;
  su.joint->normalGap(q.data(), d, dq, dqq);
  // Shift both slider nodes' positions by (gap - d) n: the slider point moves
  // by the same vector, d by (gap - d) (n is the track's unit normal at s).
  const Eigen::Vector2d n(dq[8], dq[9]); // d_q of the slider's first node position = n
  for (int node = 0; node < 2; ++node)
    for (int c = 0; c < 2; ++c) q[8 + 4 * node + c] += (gap - d) * n[c] / n.norm();
  su.joint->normalGap(q.data(), d, dq, dqq);
  EXPECT_NEAR(d, gap, 1e-9);
  return q;
}

// d(residual)/dx of a work item against central differences, x entering as
// q = q0 + cQ x, v = v0 + cV x, a = a0 + cA x (first-order states: v = v0 + cZ x).
void checkItem(const WorkItem &item, const Kinematics &kin, std::vector<double> q, std::vector<double> v,
               std::vector<double> a, int firstOrder, const char *what)
{
  std::vector<PetscInt> dofs, rows;
  item.coordinates(dofs);
  item.multiplierRows(rows);
  const int n = static_cast<int>(dofs.size());
  ASSERT_TRUE(rows.empty());
  AssemblyContext ctx;
  ctx.kin = kin;
  ctx.sigma = 3.0;
  auto residual = [&](const std::vector<double> &qq, const std::vector<double> &vv, const std::vector<double> &aa,
                      double *J) {
    std::vector<double> r(n, 0.0);
    ItemValues in{qq.data(), vv.data(), aa.data(), nullptr};
    item.evaluate(ctx, in, r.data(), J);
    return Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(r.data(), n));
  };
  std::vector<double> J(n * n, 0.0);
  residual(q, v, a, J.data());
  const Eigen::MatrixXd Ja = Eigen::Map<Eigen::Matrix<double, -1, -1, Eigen::RowMajor>>(J.data(), n, n);
  Eigen::MatrixXd fd(n, n);
  const double h = 1e-7;
  for (int j = 0; j < n; ++j) {
    auto qp = q, qm = q, vp = v, vm = v, ap = a, am = a;
    const double cv = j == firstOrder ? kin.cZ : kin.cV;
    qp[j] += kin.cQ * h, qm[j] -= kin.cQ * h, vp[j] += cv * h, vm[j] -= cv * h, ap[j] += kin.cA * h,
        am[j] -= kin.cA * h;
    fd.col(j) = (residual(qp, vp, ap, nullptr) - residual(qm, vm, am, nullptr)) / (2 * h);
  }
  EXPECT_LT((Ja - fd).norm(), 1e-6 * (1.0 + fd.norm())) << what << ": |J - J_fd| = " << (Ja - fd).norm()
                                                         << ", |J_fd| = " << fd.norm();
}

const Kinematics kDynamic{1.0, 2e3, 4e6, 1e3}, kStatic{1.0, 0.0, 0.0, 0.0};

} // namespace

// Gaps: in contact on the + side, on the - side, inside the clearance.
class PadContactKernel : public ::testing::TestWithParam<double> {};

TEST_P(PadContactKernel, JacobianMatchesFiniteDifferencesOnEitherSideAndInTheClearance)
{
  const double gap = GetParam();
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double s : {0.37, 1.0, 1.61}) {
    PadRig su(s, PadSpec{2e6, kClearance, 150.0});
    const std::vector<double> q = stateWithGap(su, s, gap, rng);
    std::vector<double> v(q.size()), a(q.size());
    for (auto &x : v) x = u(rng);
    for (auto &x : a) x = u(rng);
    const PadState st = su.pad.state(q.data(), v.data());
    EXPECT_EQ(st.side, PadContact::sideOf(gap, kClearance));
    EXPECT_NEAR(st.penetration, std::abs(gap) - kClearance, 1e-9);
    checkItem(su.pad, kDynamic, q, v, a, -1, "pad, dynamic");
    if (st.side != 0) checkItem(su.pad, kStatic, q, v, a, -1, "pad, static");
    // Without damping the residual is the gradient of the strain energy k (|d| - g)^2 / 2.
    PadRig elastic(s, PadSpec{2e6, kClearance, 0.0});
    std::vector<double> r(q.size(), 0.0);
    AssemblyContext ctx;
    elastic.pad.evaluate(ctx, ItemValues{q.data(), v.data(), a.data(), nullptr}, r.data(), nullptr);
    auto strain = [&](const std::vector<double> &qq) {
      EnergyParts e;
      elastic.pad.energy(ctx, ItemValues{qq.data(), nullptr, nullptr, nullptr}, e);
      return e.strain;
    };
    double err = 0, scale = 0;
    for (std::size_t j = 0; j < q.size(); ++j) {
      auto qp = q, qm = q;
      qp[j] += 1e-7, qm[j] -= 1e-7;
      const double g = (strain(qp) - strain(qm)) / 2e-7;
      err = std::max(err, std::abs(g - r[j]));
      scale = std::max(scale, std::abs(g));
    }
    EXPECT_LT(err, 1e-6 * (1.0 + scale)) << "residual = dV/dq";
    if (st.side != 0) EXPECT_GT(scale, 1.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Gaps, PadContactKernel, ::testing::Values(kClearance + 0.004, -kClearance - 0.003, 0.4 * kClearance),
                         [](const auto &info) { return std::string(info.index == 0 ? "PlusSide" : info.index == 1 ? "MinusSide" : "Clearance"); });

TEST(PadContactSides, ZeroClearanceIsBilateral)
{
  EXPECT_EQ(PadContact::sideOf(0.0, 0.0), 1);
  EXPECT_EQ(PadContact::sideOf(-1e-300, 0.0), -1);
  EXPECT_EQ(PadContact::sideOf(0.0, 1e-3), 0);
}

// LuGre friction whose normal force is the pad's |f|: the Jacobian includes
// the derivatives of |f| in q and v (and no multiplier column).
TEST_P(PadContactKernel, LuGreFrictionWithPadForceMatchesFiniteDifferences)
{
  const double gap = GetParam();
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1, 1);
  FrictionSpec fr;
  fr.mu_s = 0.3, fr.mu_c = 0.2, fr.v_s = 0.05, fr.sigma0 = 1e4, fr.sigma1 = 30, fr.sigma2 = 2;
  for (double s : {0.37, 1.61}) {
    PadRig su(s, PadSpec{2e6, kClearance, 150.0});
    std::vector<double> q = stateWithGap(su, s, gap, rng);
    const int iz = static_cast<int>(q.size());
    LuGreFriction friction(su.joint, 69, &su.pad, fr);
    std::vector<PetscInt> dofs;
    friction.coordinates(dofs);
    ASSERT_EQ(static_cast<int>(dofs.size()), iz + 1);
    q.push_back(2e-5 * u(rng)); // z
    std::vector<double> v(q.size()), a(q.size());
    for (auto &x : v) x = 0.3 * u(rng);
    for (auto &x : a) x = u(rng);
    checkItem(friction, kDynamic, q, v, a, iz, "friction with pad, dynamic");
  }
}
