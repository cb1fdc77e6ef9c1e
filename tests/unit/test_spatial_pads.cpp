// Pads at the spatial sliding joint (SpatialPadGap + PadContact, docs/model.md
// §9.5) against central finite differences: the lateral gaps g_k = -C_k
// (k = 2, 3) and their gradient and Hessian over the joint's coordinates
// (the beam's element, the slider's and the slack s), at random deformed
// and twisted states with s inside an element, on a node and just past it;
// the pad force f and its derivatives f_q, f_v in contact on either side of
// the clearance and inside it (f = 0); and the gap's continuity when the
// contact point moves to the next element.
#include "spatial_test_frames.hpp"
#include "boomdyn/pad_contact.hpp"
#include "boomdyn/spatial_rigid_body.hpp"
#include "boomdyn/spatial_sliding_joint.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <random>

using namespace boomdyn;
namespace sb = boomdyn::spatial_beam;

using spatial_test::axesOf;
using spatial_test::unitSection;

namespace {

// A 4-element beam of length 2 m along a general direction and a rigid
// sleeve (coordinates 35..41: position, then Euler parameters).
struct PadSetup {
  SpatialAncfBeam track{"track", 2.0, 4, unitSection(), Vec3(0.1, -0.2, 0.3), axesOf(Vec3(1, 0.4, -0.3), Vec3(0.2, 1, 0.5)),
                        0};
  SpatialRigidBody sleeve{"sleeve", 0.4, 3.0, Mat3::Identity(), Vec3(0.2, 0, 0), Vec3(0.5, 0, 0),
                          axesOf(Vec3(0.9, 0.5, -0.2), Vec3(0, 1, 0.3)), 35};
  std::vector<double> q0 = std::vector<double>(42);
  PadSetup()
  {
    track.initialCoordinates(q0.data());
    sleeve.initialCoordinates(q0.data() + 35);
  }
};

std::vector<double> randomGlobal(const std::vector<double> &q0, std::mt19937 &rng, double amp)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> q = q0;
  for (double &x : q) x += amp * u(rng);
  for (int node = 0; node < 5; ++node) q[7 * node + 6] = 0.8 * u(rng);
  return q;
}

std::vector<double> localOf(const PadGap &gap, const std::vector<double> &qg, double s)
{
  std::vector<PetscInt> dofs;
  gap.coordinates(dofs);
  std::vector<double> q(dofs.size());
  for (std::size_t i = 0; i + 1 < dofs.size(); ++i) q[i] = qg[dofs[i]];
  q.back() = s;
  return q;
}

// Moves the sleeve (its position coordinates, local 14..16) so that the gap
// is `target`: the gap is linear in them with gradient d_k.
void setGap(const PadGap &gap, std::vector<double> &q, double target)
{
  double d;
  Eigen::VectorXd dq;
  gap.normalGap(q.data(), d, dq);
  const Vec3 dk = dq.segment<3>(14);
  ASSERT_NEAR(dk.norm(), 1.0, 1e-12); // d_k is a unit vector
  for (int c = 0; c < 3; ++c) q[14 + c] += (target - d) * dk[c];
}

} // namespace

// g_q and g_qq against central differences of g and g_q; g = -C_k of the
// rigid joint's row k.
TEST(SpatialPads, GapsMatchFiniteDifferences)
{
  std::mt19937 rng(3601);
  const PadSetup st;
  const Vec3 v2 = Vec3(0.3, 0.9, -0.2).normalized(), v3 = Vec3(-0.1, 0.2, 1.0).normalized();
  for (double s : {0.73, 1.0, 1.0004, 1.61}) {
    const double s0 = s > 1.0 && s < 1.001 ? 0.99 : s; // past a node: the element before it
    auto padded = std::make_shared<SpatialSlidingJoint>("j", st.track, st.sleeve, 0.2, 42, s0, true, true, v2, v3,
                                                        std::array<bool, 2>{false, false});
    const SpatialSlidingJoint rigid("j", st.track, st.sleeve, 0.2, 42, s0, true, true, v2, v3);
    EXPECT_EQ(padded->numRows(), 4);
    EXPECT_EQ(padded->firstRotationRow(), 1);
    for (int k = 2; k <= 3; ++k) {
      const SpatialPadGap gap(padded, k);
      const std::vector<double> q = localOf(gap, randomGlobal(st.q0, rng, 0.08), s);
      const int n = static_cast<int>(q.size());
      double d;
      Eigen::VectorXd dq, dq2;
      Eigen::MatrixXd dqq;
      gap.normalGap(q.data(), d, dq, dqq);
      double d2;
      gap.normalGap(q.data(), d2, dq2);
      EXPECT_EQ(d, d2);
      EXPECT_EQ((dq - dq2).norm(), 0.0);
      ConstraintEval ev;
      rigid.evaluate(0.0, q.data(), nullptr, nullptr, ev);
      EXPECT_NEAR(d, -ev.C[k - 1], 1e-15);
      EXPECT_LT((dq + ev.Cq.row(k - 1).transpose()).norm(), 1e-14);
      const double h = 1e-6;
      Eigen::VectorXd fd(n);
      Eigen::MatrixXd fdH(n, n);
      for (int j = 0; j < n; ++j) {
        auto qp = q, qm = q;
        qp[j] += h, qm[j] -= h;
        double dp, dm;
        Eigen::VectorXd gp, gm;
        gap.normalGap(qp.data(), dp, gp);
        gap.normalGap(qm.data(), dm, gm);
        fd[j] = (dp - dm) / (2 * h);
        fdH.col(j) = (gp - gm) / (2 * h);
      }
      const double errQ = (dq - fd).norm() / (1 + fd.norm()), errH = (dqq - fdH).norm() / (1 + fdH.norm());
      EXPECT_LT(errQ, 1e-8) << "s " << s << " k " << k;
      EXPECT_LT(errH, 1e-7) << "s " << s << " k " << k;
      EXPECT_LT(std::abs(dq[n - 1] - fd[n - 1]), 1e-8 * (1 + std::abs(fd[n - 1]))) << "g_s";
      std::printf("s %-7g k %d  g_q %.1e  g_qq %.1e\n", s, k, errQ, errH);
    }
  }
}

// f, f_q and f_v of the pad law on the spatial gap: in contact on the +
// side and the - side of the clearance (f = -k (g -+ c) - c_pad gdot) and
// free inside it (f = 0, no derivatives).
TEST(SpatialPads, PadForceMatchesFiniteDifferencesAcrossTheClearance)
{
  std::mt19937 rng(3602);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const PadSetup st;
  const Vec3 v2 = Vec3(0.3, 0.9, -0.2).normalized(), v3 = Vec3(-0.1, 0.2, 1.0).normalized();
  const PadSpec spec{2.0e3, 0.01, 7.0};
  for (double s : {0.73, 1.0004}) {
    const double s0 = s > 1.0 && s < 1.001 ? 0.99 : s;
    auto joint = std::make_shared<SpatialSlidingJoint>("j", st.track, st.sleeve, 0.2, 42, s0, true, true, v2, v3,
                                                       std::array<bool, 2>{false, false});
    for (int k = 2; k <= 3; ++k) {
      const auto gap = std::make_shared<SpatialPadGap>(joint, k);
      const PadContact pad(gap, spec);
      EXPECT_EQ(pad.name(), "j.pad_" + std::to_string(k));
      for (double target : {0.013, -0.017, 0.004, -0.006}) {
        std::vector<double> q = localOf(*gap, randomGlobal(st.q0, rng, 0.05), s);
        setGap(*gap, q, target);
        const int n = static_cast<int>(q.size());
        std::vector<double> v(n);
        for (double &x : v) x = u(rng);
        double f;
        Eigen::VectorXd fq, fv, dq;
        pad.force(q.data(), v.data(), f, fq, fv);
        double d;
        gap->normalGap(q.data(), d, dq);
        ASSERT_NEAR(d, target, 1e-12);
        const int side = PadContact::sideOf(d, spec.clearance);
        EXPECT_EQ(side, std::abs(target) > spec.clearance ? (target > 0 ? 1 : -1) : 0);
        const double gdot = dq.dot(Eigen::Map<const Eigen::VectorXd>(v.data(), n));
        const double expected = side == 0 ? 0.0 : -spec.stiffness * (d - side * spec.clearance) - spec.damping * gdot;
        EXPECT_NEAR(f, expected, 1e-12 * (1 + std::abs(expected)));
        EXPECT_EQ(pad.state(q.data(), v.data()).force, f);
        const double h = 1e-7;
        Eigen::VectorXd fdq(n), fdv(n);
        for (int j = 0; j < n; ++j) {
          auto qp = q, qm = q, vp = v, vm = v;
          qp[j] += h, qm[j] -= h, vp[j] += h, vm[j] -= h;
          double a, b;
          Eigen::VectorXd x1, x2;
          pad.force(qp.data(), v.data(), a, x1, x2);
          pad.force(qm.data(), v.data(), b, x1, x2);
          fdq[j] = (a - b) / (2 * h);
          pad.force(q.data(), vp.data(), a, x1, x2);
          pad.force(q.data(), vm.data(), b, x1, x2);
          fdv[j] = (a - b) / (2 * h);
        }
        const double scale = spec.stiffness + spec.damping;
        EXPECT_LT((fq - fdq).norm(), 1e-6 * scale) << "s " << s << " k " << k << " gap " << target;
        EXPECT_LT((fv - fdv).norm(), 1e-6 * scale) << "s " << s << " k " << k << " gap " << target;
        if (side == 0) EXPECT_EQ(fq.norm() + fv.norm(), 0.0);
        else EXPECT_GT(fq.norm(), 0.5 * spec.stiffness); // |g_q| >= 1 through the sleeve's position
        std::printf("s %-7g k %d gap %+.3f side %+d  f %+.4e  |f_q - fd| %.1e  |f_v - fd| %.1e\n", s, k, target, side,
                    f, (fq - fdq).norm(), (fv - fdv).norm());
      }
    }
  }
}

// At a node both elements give the same gap and the same derivatives in
// the node's and the sleeve's coordinates.
TEST(SpatialPads, GapsAreContinuousAcrossElementBoundaries)
{
  std::mt19937 rng(3603);
  const PadSetup st;
  const Vec3 v2 = Vec3(0.3, 0.9, -0.2).normalized(), v3 = Vec3(-0.1, 0.2, 1.0).normalized();
  const std::array<bool, 2> pads{false, false};
  auto before = std::make_shared<SpatialSlidingJoint>("j", st.track, st.sleeve, 0.1, 42, 0.9, true, true, v2, v3, pads);
  auto after = std::make_shared<SpatialSlidingJoint>("j", st.track, st.sleeve, 0.1, 42, 1.1, true, true, v2, v3, pads);
  ASSERT_EQ(before->trackLocation().element, 1);
  ASSERT_EQ(after->trackLocation().element, 2);
  for (int k = 2; k <= 3; ++k) {
    const SpatialPadGap gb(before, k), ga(after, k);
    for (int trial = 0; trial < 3; ++trial) {
      const std::vector<double> qg = randomGlobal(st.q0, rng, 0.1);
      double db, da;
      Eigen::VectorXd qb, qa;
      gb.normalGap(localOf(gb, qg, 1.0).data(), db, qb);
      ga.normalGap(localOf(ga, qg, 1.0).data(), da, qa);
      EXPECT_NEAR(db, da, 1e-13);
      EXPECT_LT((qb.segment(7, 7) - qa.head(7)).norm(), 1e-12 * (1 + qb.norm()));
      EXPECT_LT((qb.segment(14, 7) - qa.segment(14, 7)).norm(), 1e-12 * (1 + qb.norm()));
      EXPECT_LT(qb.head(7).norm(), 1e-12 * (1 + qb.norm()));
    }
  }
}
