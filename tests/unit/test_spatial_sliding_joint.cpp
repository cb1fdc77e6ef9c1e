// The spatial sliding joint (spatial_sliding_joint.hpp) against central
// finite differences: the section frame of the beam as a function of its
// coordinates and the arc length (slackFrame), and the joint's rows (C_q in
// both blocks, the beam's and the slider's coordinates and the slack s, the
// multiplier-weighted Hessian and gamma) at random deformed and twisted
// states, with s inside elements, on nodes and just past an element's end;
// and the rows' continuity when the contact point moves to the next element.
#include "spatial_test_frames.hpp"
#include "boomdyn/spatial_beam_slack_frame.hpp"
#include "boomdyn/slack_track.hpp"
#include "boomdyn/spatial_rigid_body.hpp"
#include "boomdyn/spatial_sliding_joint.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>

using namespace boomdyn;
namespace sb = boomdyn::spatial_beam;

using spatial_test::axesOf;
using spatial_test::unitSection;

namespace {

// A 4-element beam of length 2 m along a general direction, and a slider:
// a rigid sleeve (Euler parameters) or a second beam.
struct SlidingSetup {
  const Mat3 triad = axesOf(Vec3(1, 0.4, -0.3), Vec3(0.2, 1, 0.5));
  SpatialAncfBeam track{"track", 2.0, 4, unitSection(), Vec3(0.1, -0.2, 0.3), triad, 0};
  SpatialRigidBody sleeve{"sleeve", 0.4, 3.0, Mat3::Identity(), Vec3(0.2, 0, 0), Vec3(0.5, 0, 0),
                          axesOf(Vec3(0.9, 0.5, -0.2), Vec3(0, 1, 0.3)), 35};
  SpatialAncfBeam inner{"inner", 1.0, 2, unitSection(), Vec3(0.3, 0.1, 0.0), axesOf(Vec3(1, 0.3, -0.4), Vec3(0, 1, 0)),
                        42};
  std::vector<double> q0 = std::vector<double>(42 + 21);
  SlidingSetup()
  {
    track.initialCoordinates(q0.data());
    sleeve.initialCoordinates(q0.data() + 35);
    inner.initialCoordinates(q0.data() + 42);
  }
};

// A random deformed and twisted state near q0 (positions and slopes by
// up to amp, twists by up to 0.8 rad; Euler parameters off the unit sphere).
std::vector<double> randomGlobal(const std::vector<double> &q0, std::mt19937 &rng, double amp)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> q = q0;
  for (std::size_t k = 0; k < q.size(); ++k) q[k] += amp * u(rng);
  for (int node = 0; node < 5; ++node) q[7 * node + 6] = 0.8 * u(rng);
  for (int node = 0; node < 3; ++node) q[42 + 7 * node + 6] = 0.8 * u(rng);
  return q;
}

std::vector<double> localOf(const Constraint &c, const std::vector<double> &qg, double s)
{
  std::vector<PetscInt> dofs;
  c.coordinates(dofs);
  std::vector<double> q(dofs.size());
  for (std::size_t i = 0; i + 1 < dofs.size(); ++i) q[i] = qg[dofs[i]];
  q.back() = s;
  return q;
}

// C_q, H = sum w_i C_i,qq and gamma = d2C/dt2 - C_q a against central differences at q.
void checkRows(const Constraint &c, const std::vector<double> &q, std::mt19937 &rng, const std::string &what)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = static_cast<int>(q.size()), m = c.numRows();
  std::vector<double> v(n), a(n), w(m);
  for (auto *vec : {&v, &a, &w})
    for (double &x : *vec) x = u(rng);
  ConstraintEval ev;
  c.evaluate(0.0, q.data(), v.data(), w.data(), ev);
  ASSERT_EQ(ev.C.size(), m);
  ASSERT_EQ(ev.Cq.cols(), n);
  const double h = 1e-6;
  Eigen::MatrixXd fd(m, n), fdH(n, n);
  const Eigen::Map<const Eigen::VectorXd> wv(w.data(), m);
  for (int j = 0; j < n; ++j) {
    auto qp = q, qm = q;
    qp[j] += h, qm[j] -= h;
    ConstraintEval ep, em;
    c.evaluate(0.0, qp.data(), nullptr, nullptr, ep);
    c.evaluate(0.0, qm.data(), nullptr, nullptr, em);
    fd.col(j) = (ep.C - em.C) / (2 * h);
    fdH.col(j) = (ep.Cq.transpose() * wv - em.Cq.transpose() * wv) / (2 * h);
  }
  const double errQ = (ev.Cq - fd).norm() / (1.0 + fd.norm()), errH = (ev.H - fdH).norm() / (1.0 + fdH.norm());
  EXPECT_LT(errQ, 1e-8) << what << " C_q";
  EXPECT_LT(errH, 1e-7) << what << " H\n" << ev.H - fdH;
  // The s column alone (a column that no other joint has).
  EXPECT_LT((ev.Cq.col(n - 1) - fd.col(n - 1)).norm(), 1e-8 * (1.0 + fd.col(n - 1).norm())) << what << " C_s";
  const double ht = 1e-4;
  auto path = [&](double tau) {
    std::vector<double> qt(n);
    for (int j = 0; j < n; ++j) qt[j] = q[j] + tau * v[j] + 0.5 * tau * tau * a[j];
    ConstraintEval e;
    c.evaluate(0.0, qt.data(), nullptr, nullptr, e);
    return Eigen::VectorXd(e.C);
  };
  const Eigen::VectorXd d2 = (path(ht) - 2.0 * path(0.0) + path(-ht)) / (ht * ht);
  const Eigen::VectorXd predicted = ev.Cq * Eigen::Map<const Eigen::VectorXd>(a.data(), n) + ev.gamma;
  const double errG = (predicted - d2).norm() / (1.0 + d2.norm());
  EXPECT_LT(errG, 1e-5) << what << " gamma";
  std::printf("%-34s C_q %.1e  H %.1e  gamma %.1e\n", what.c_str(), errQ, errH, errG);
}

} // namespace

// The jets of slackFrame against central differences of sectionFrame (the
// element's section at fixed xi) in the element coordinates, and against
// differences in x of itself for the slack column.
TEST(SpatialSlackFrame, DerivativesInCoordinatesAndArcLength)
{
  std::mt19937 rng(361);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const SlidingSetup st;
  const sb::Geometry geo = st.track.geometry(0); // the element whose coordinates follow the slider's 7
  for (int trial = 0; trial < 6; ++trial) {
    const std::vector<double> qg = randomGlobal(st.q0, rng, 0.1);
    const sb::Vec14 e = Eigen::Map<const sb::Vec14>(qg.data() + 7);
    const double xi = trial == 0 ? 0.0 : trial == 1 ? 1.0 : trial == 2 ? 1.0005 : 0.5 + 0.5 * u(rng);
    const sb::SlackFrame F = sb::slackFrame(geo, e, xi);
    // Values: the element's own section frame.
    const sb::SectionFrame S = sb::sectionFrame(geo, e, xi);
    EXPECT_LT((F.position() - S.r).norm(), 1e-14);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT((F.director(k) - S.d.col(k)).norm(), 1e-14);
      EXPECT_NEAR(F.rd[k].value, S.d.col(k).dot(S.r), 1e-14);
    }
    // Every scalar's gradient and Hessian in all 15 variables.
    auto scalars = [&](const sb::SlackFrame &f) {
      std::vector<const sb::SlackScalar *> out;
      for (int c = 0; c < 3; ++c) out.push_back(&f.r[c]), out.push_back(&f.rd[c]);
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) out.push_back(&f.d[k][c]);
      return out;
    };
    const double h = 1e-6, l = geo.l;
    std::vector<sb::SlackFrame> plus, minus;
    for (int j = 0; j < sb::kSlackVariables; ++j) {
      sb::Vec14 ep = e, em = e;
      double xp = xi, xm = xi;
      if (j < sb::kCoordinates) ep[j] += h, em[j] -= h;
      else xp += h / l, xm -= h / l;
      plus.push_back(sb::slackFrame(geo, ep, xp));
      minus.push_back(sb::slackFrame(geo, em, xm));
    }
    const auto f0 = scalars(F);
    double worstG = 0, worstH = 0;
    for (std::size_t i = 0; i < f0.size(); ++i) {
      sb::Vec15 g;
      sb::Mat15 H;
      for (int j = 0; j < sb::kSlackVariables; ++j) {
        g[j] = (scalars(plus[j])[i]->value - scalars(minus[j])[i]->value) / (2 * h);
        H.col(j) = (scalars(plus[j])[i]->grad - scalars(minus[j])[i]->grad) / (2 * h);
      }
      worstG = std::max(worstG, (f0[i]->grad - g).norm() / (1.0 + g.norm()));
      worstH = std::max(worstH, (f0[i]->hess - H).norm() / (1.0 + H.norm()));
      EXPECT_LT((f0[i]->hess - f0[i]->hess.transpose()).norm(), 1e-12);
    }
    EXPECT_LT(worstG, 1e-8) << "xi " << xi;
    EXPECT_LT(worstH, 1e-7) << "xi " << xi;
  }
}

// All rows (position, alignment, roll) with a rigid sleeve and with a
// point of a second beam as the slider, s inside elements, on nodes and
// past an element's end within the relocation band.
TEST(SpatialSlidingJoint, RowsMatchFiniteDifferences)
{
  std::mt19937 rng(362);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const SlidingSetup st;
  const Vec3 v2 = Vec3(0.3, 0.9, -0.2).normalized(), v3 = Vec3(-0.1, 0.2, 1.0).normalized();
  struct Case {
    const SpatialBody *slider;
    double at, s;
    bool align, roll;
    const char *what;
  };
  const Case cases[] = {
      {&st.sleeve, 0.2, 0.73, false, false, "sleeve, position rows"},
      {&st.sleeve, 0.2, 0.73, true, false, "sleeve, aligned"},
      {&st.sleeve, 0.2, 1.27, true, true, "sleeve, locked"},
      {&st.sleeve, 0.0, 1.0, true, true, "sleeve, locked, on a node"},
      {&st.sleeve, 0.4, 1.0004, true, true, "sleeve, locked, past a node"},
      {&st.inner, 0.35, 0.61, true, true, "beam point, locked"},
      {&st.inner, 0.5, 1.5, true, true, "beam point on its node, locked"},
  };
  int k = 0;
  for (const Case &c : cases) {
    // Past a node: the element before it (as the hysteresis keeps it).
    const double s0 = c.s > 1.0 && c.s < 1.001 ? 0.99 : c.s;
    SpatialSlidingJoint joint("joint", st.track, *c.slider, c.at, 63, s0, c.align, c.roll, v2, v3);
    EXPECT_EQ(joint.numRows(), 3 + (c.align ? 2 : 0) + (c.roll ? 1 : 0));
    for (int trial = 0; trial < 2; ++trial) {
      const std::vector<double> qg = randomGlobal(st.q0, rng, 0.08);
      checkRows(joint, localOf(joint, qg, c.s), rng, std::string(c.what) + " #" + std::to_string(k++));
    }
  }
}

// At a node both elements give the same rows and the same derivatives in
// the node's and the sleeve's coordinates (the axis point, the tangent and
// the section triad at a node depend on that node's coordinates only; the
// derivative in s jumps there, with the axis' curvature and the twist rate,
// which are continuous inside an element only); relocate() moves the joint
// when s passes the hysteresis band only.
TEST(SpatialSlidingJoint, RowsAreContinuousAcrossElementBoundaries)
{
  std::mt19937 rng(363);
  const SlidingSetup st;
  const Vec3 v2 = Vec3(0.3, 0.9, -0.2).normalized(), v3 = Vec3(-0.1, 0.2, 1.0).normalized();
  SpatialSlidingJoint before("joint", st.track, st.sleeve, 0.1, 63, 0.9, true, true, v2, v3);
  SpatialSlidingJoint after("joint", st.track, st.sleeve, 0.1, 63, 1.1, true, true, v2, v3);
  ASSERT_EQ(before.trackLocation().element, 1);
  ASSERT_EQ(after.trackLocation().element, 2);
  for (int trial = 0; trial < 3; ++trial) {
    const std::vector<double> qg = randomGlobal(st.q0, rng, 0.1);
    ConstraintEval eb, ea;
    before.evaluate(0, localOf(before, qg, 1.0).data(), nullptr, nullptr, eb);
    after.evaluate(0, localOf(after, qg, 1.0).data(), nullptr, nullptr, ea);
    EXPECT_LT((eb.C - ea.C).norm(), 1e-13);
    // Node 2 is node 1 of element 1 (local 7..13) and node 0 of element 2 (local 0..6).
    EXPECT_LT((eb.Cq.middleCols(7, 7) - ea.Cq.leftCols(7)).norm(), 1e-12 * (1 + eb.Cq.norm()));
    EXPECT_LT((eb.Cq.middleCols(14, 7) - ea.Cq.middleCols(14, 7)).norm(), 1e-12 * (1 + eb.Cq.norm())); // sleeve
    // The other node does not act at the node.
    EXPECT_LT(eb.Cq.leftCols(7).norm(), 1e-12 * (1 + eb.Cq.norm()));
  }
  EXPECT_FALSE(before.relocate(1.0 + 0.5 * kSlackRelocationHysteresis * 0.5));
  EXPECT_EQ(before.trackLocation().element, 1);
  EXPECT_TRUE(before.relocate(1.0 + 2.0 * kSlackRelocationHysteresis * 0.5));
  EXPECT_EQ(before.trackLocation().element, 2);
  EXPECT_TRUE(before.onTrack(2.0));
  EXPECT_FALSE(before.onTrack(2.0 + 1e-9));
}
