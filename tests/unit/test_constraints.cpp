// Constraint kernels: Jacobian, multiplier-weighted Hessian and the
// acceleration-level term against central finite differences, at random
// states, with the material point inside an element and on an element boundary.
#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/angle_drive.hpp"
#include "boomdyn/distance.hpp"
#include "boomdyn/pin.hpp"
#include "boomdyn/rigid_body.hpp"
#include "boomdyn/rope.hpp"
#include "constraint_derivative_check.hpp"
#include "rope_test_bodies.hpp"
#include "boomdyn/sliding_joint.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace boomdyn;

namespace {

const ancf::Section kSection{1e8, 1e5, 30};

// Random deformed states: q0 plus up to 5 cm (or rad) on every coordinate.
constexpr double kSpread = 0.05;

std::vector<double> randomState(const std::vector<PetscInt> &dofs, std::mt19937 &rng, const std::vector<double> &q0)
{
  return boomdyn::testing::randomNear(dofs, q0, rng, kSpread);
}

void checkConstraint(const Constraint &c, const std::vector<double> &q0, unsigned seed)
{
  boomdyn::testing::checkConstraintDerivatives(c, q0, seed, kSpread);
}

} // namespace

class ConstraintKernels : public ::testing::TestWithParam<double> {};

TEST_P(ConstraintKernels, PinToGround)
{
  AncfBeam beam("b", 2.0, 4, kSection, Vec2(0.1, 0.2), 0.4, 0);
  std::vector<double> q0(beam.numCoordinates());
  beam.initialCoordinates(q0.data());
  checkConstraint(Pin("pin", beam, GetParam(), Vec2(0.3, -0.1)), q0, 11);
}

TEST_P(ConstraintKernels, PinBetweenBodies)
{
  AncfBeam a("a", 2.0, 4, kSection, Vec2(0, 0), 0.0, 0);
  AncfBeam b("b", 1.5, 3, kSection, Vec2(0.5, 0.1), 0.2, a.numCoordinates());
  std::vector<double> q0(a.numCoordinates() + b.numCoordinates());
  a.initialCoordinates(q0.data());
  b.initialCoordinates(q0.data() + a.numCoordinates());
  checkConstraint(Pin("pin2", a, GetParam(), b, 0.5 * GetParam()), q0, 12);
}

TEST_P(ConstraintKernels, AngleDriveWithTimeDependentAngle)
{
  AncfBeam beam("b", 2.0, 4, kSection, Vec2(0.1, 0.2), 0.4, 0);
  std::vector<double> q0(beam.numCoordinates());
  beam.initialCoordinates(q0.data());
  checkConstraint(AngleDrive("drive", beam, GetParam(), TimeFunction::sine(0.3, 0.7, 0.2, 0.1)), q0, 13);
  checkConstraint(AngleDrive("drive2", beam, GetParam(), TimeFunction::smoothStep(0.0, 3.0, 0.0, 0.6)), q0, 14);
}

// Inside an element, exactly on an element boundary (0.5 with 4 elements of 0.5 m), and the ends.
INSTANTIATE_TEST_SUITE_P(MaterialPoints, ConstraintKernels, ::testing::Values(0.0, 0.3, 0.5, 1.0, 2.0 - 1e-12));

// Sliding joint: track beam a, slider point on beam b, slack coordinate last.
// Checked with s inside a track element, on an element boundary, and near the ends.
class SlidingJointKernel : public ::testing::TestWithParam<double> {};

TEST_P(SlidingJointKernel, DerivativesMatchFiniteDifferences)
{
  AncfBeam track("track", 2.0, 4, kSection, Vec2(0, 0), 0.1, 0);
  AncfBeam slider("slider", 1.5, 3, kSection, Vec2(0.5, 0.05), 0.1, track.numCoordinates());
  const PetscInt slack = track.numCoordinates() + slider.numCoordinates();
  std::vector<double> q0(slack + 1);
  track.initialCoordinates(q0.data());
  slider.initialCoordinates(q0.data() + track.numCoordinates());
  const double s = GetParam();
  q0[slack] = s;
  SlidingJoint joint("slide", track, slider, 0.3, slack, s);
  std::vector<PetscInt> dofs;
  joint.coordinates(dofs);
  ASSERT_EQ(dofs.size(), 17u);
  EXPECT_EQ(dofs.back(), slack);
  // The random state perturbs s by up to 0.05 m: it may leave the element
  // (the kernel then extrapolates the element's cubic), which is fine for a
  // derivative check.
  checkConstraint(joint, q0, 21);
  // With a pad only the tangential row is a constraint (C_d of the same joint).
  SlidingJoint padded("slide_pad", track, slider, 0.3, slack, s, false);
  ASSERT_EQ(padded.numRows(), 1);
  checkConstraint(padded, q0, 21);
}

INSTANTIATE_TEST_SUITE_P(SlackPositions, SlidingJointKernel, ::testing::Values(0.05, 0.8, 1.0, 1.37, 1.95));

// Rigid bodies: centerlines nonlinear in the rotation, so the curvature
// terms of the Hessian and of gamma are exercised.
TEST(RigidBodyConstraints, PinAngleDriveAndSlidingJointOnRigidBodies)
{
  RigidBody ramp("ramp", 4.0, 40.0, Vec2(0.1, -0.2), 0.5, 0);
  RigidBody block("block", 0.5, 5.0, Vec2(1.0, 0.4), 0.45, 3);
  AncfBeam beam("beam", 2.0, 4, kSection, Vec2(0.3, 0.6), 0.5, 6);
  std::vector<double> q0(6 + beam.numCoordinates() + 1);
  ramp.initialCoordinates(q0.data());
  block.initialCoordinates(q0.data() + 3);
  beam.initialCoordinates(q0.data() + 6);
  const PetscInt slack = static_cast<PetscInt>(q0.size()) - 1;
  q0[slack] = 1.3;
  checkConstraint(Pin("pin-rigid-ground", ramp, 0.7, Vec2(0.2, 0.1)), q0, 31);
  checkConstraint(Pin("pin-rigid-rigid", ramp, 3.1, block, 0.2), q0, 32);
  checkConstraint(AngleDrive("drive-rigid", block, 0.3, TimeFunction::sine(0.2, 1.0, 0.0, 0.4)), q0, 33);
  checkConstraint(SlidingJoint("slide-rigid-on-rigid", ramp, block, 0.25, slack, 1.3), q0, 34);
  checkConstraint(SlidingJoint("slide-beam-on-rigid", ramp, beam, 0.6, slack, 1.3), q0, 35);
  checkConstraint(SlidingJoint("slide-rigid-on-beam", beam, block, 0.1, slack, 1.3), q0, 36);
}

TEST(RopeConstraint, DerivativesMatchFiniteDifferencesOnBeamsAndRigidBodies)
{
  const rope_test::Bodies bodies;
  const auto &[b1, b2, b3, q0] = bodies;
  // P near boom 1's front, pulley Q at boom 2's front, R at boom 3's rear.
  Rope rope("rope", {&b1, 1.9}, {&b2, 2.0}, {&b3, 0.0}, 3.0);
  checkConstraint(rope, q0, 41);
  std::vector<PetscInt> dofs;
  rope.coordinates(dofs);
  EXPECT_EQ(dofs.size(), 19u);
}

// Distance: to a ground point and between bodies, on beams (material point
// inside an element and on a node) and on rigid bodies (curvature terms).
TEST(DistanceConstraint, DerivativesMatchFiniteDifferencesOnBeamsAndRigidBodies)
{
  AncfBeam beam("beam", 2.0, 4, kSection, Vec2(0.1, 0.2), 0.4, 0);
  RigidBody bar("bar", 1.5, 10.0, Vec2(-0.5, 1.0), 0.3, 20);
  std::vector<double> q0(23);
  beam.initialCoordinates(q0.data());
  bar.initialCoordinates(q0.data() + 20);
  for (const double s : {0.3, 1.0, 2.0}) {
    checkConstraint(Distance("to-ground", beam, s, Vec2(1.5, -0.7), 1.2), q0, 51);
    checkConstraint(Distance("beam-bar", beam, s, bar, 1.1, 0.9), q0, 52);
    checkConstraint(Distance("bar-beam", bar, 0.2, beam, s, 0.9), q0, 53);
  }
  checkConstraint(Distance("bar-to-ground", bar, 1.4, Vec2(0.3, 0.2), 1.0), q0, 54);
  // C = |d| - L at the initial state, and one row over both bodies' points.
  const Distance link("link", beam, 2.0, Vec2(0.1, 0.2), 1.0);
  std::vector<PetscInt> dofs;
  link.coordinates(dofs);
  std::vector<double> vals;
  for (PetscInt d : dofs) vals.push_back(q0[d]);
  EXPECT_NEAR(link.distance(vals.data()), 2.0, 1e-14); // the beam's end is 2 m from its start
  ConstraintEval ev;
  link.evaluate(0.0, vals.data(), nullptr, nullptr, ev);
  EXPECT_NEAR(ev.C[0], 1.0, 1e-14);
}

// A contact point keeps its track element until it is more than
// relocationHysteresis element lengths past the element's ends, and the
// constraint it evaluates there (the element's cubic continued) agrees with
// the neighbouring element's to second order in that distance.
TEST(SlidingJointRelocation, HysteresisBandAtNodesAndContinuity)
{
  AncfBeam track("track", 2.0, 4, kSection, Vec2(0, 0), 0.2, 0); // elements of 0.5 m
  AncfBeam slider("slider", 1.0, 2, kSection, Vec2(0.3, 0.1), 0.2, 20);
  std::vector<double> q0(20 + slider.numCoordinates() + 1);
  track.initialCoordinates(q0.data());
  slider.initialCoordinates(q0.data() + 20);
  // A smooth bend of the track, so that neighbouring cubics differ beyond C1 only slightly.
  for (int node = 0; node <= 4; ++node) {
    const double s = 0.5 * node;
    q0[4 * node + 1] += 0.01 * s * s, q0[4 * node + 3] += 0.02 * s;
  }
  const PetscInt slack = static_cast<PetscInt>(q0.size()) - 1;
  SlidingJoint joint("slide", track, slider, 0.4, slack, 1.0); // on the node between elements 1 and 2
  const double band = SlidingJoint::relocationHysteresis * 0.5;
  ASSERT_EQ(joint.trackLocation().element, 2);
  EXPECT_FALSE(joint.relocate(1.0 - 1e-9));
  EXPECT_FALSE(joint.relocate(1.0 - 0.8 * band));
  EXPECT_EQ(joint.trackLocation().element, 2);

  auto constraintAt = [&](double s) {
    std::vector<PetscInt> dofs;
    joint.coordinates(dofs);
    std::vector<double> q(dofs.size());
    for (std::size_t i = 0; i < dofs.size(); ++i) q[i] = q0[dofs[i]];
    q.back() = s;
    ConstraintEval ev;
    joint.evaluate(0.0, q.data(), nullptr, nullptr, ev);
    return Eigen::VectorXd(ev.C);
  };
  const double s = 1.0 - 0.8 * band;
  const Eigen::VectorXd continued = constraintAt(s); // element 2, continued past its start
  EXPECT_TRUE(joint.relocate(1.0 - 1.2 * band));
  EXPECT_EQ(joint.trackLocation().element, 1);
  const Eigen::VectorXd inside = constraintAt(s);     // element 1, inside
  EXPECT_LT((continued - inside).norm(), 1e-8) << continued.transpose() << " vs " << inside.transpose();
  // And back: within the band past element 1's end it stays, beyond it moves.
  EXPECT_FALSE(joint.relocate(1.0 + 0.8 * band));
  EXPECT_TRUE(joint.relocate(1.0 + 1.2 * band));
  EXPECT_EQ(joint.trackLocation().element, 2);
  // setTrackLocation (restarts) puts the point where the material coordinate says.
  joint.setTrackLocation(0.2);
  EXPECT_EQ(joint.trackLocation().element, 0);
}

// Constraints that say they do not depend on time (the energy balance skips
// their power) give the same C at any t; the drives do depend on it.
TEST(ConstraintTimeDependence, DeclaredIndependentMeansSameC)
{
  AncfBeam b1("b1", 2.0, 4, kSection, Vec2(0, 0), 0.1, 0);
  AncfBeam b2("b2", 2.0, 4, kSection, Vec2(0.5, 0.05), 0.1, 20);
  RigidBody b3("b3", 2.0, 10.0, Vec2(1.0, 0.1), 0.1, 40);
  std::vector<double> q0(44);
  b1.initialCoordinates(q0.data());
  b2.initialCoordinates(q0.data() + 20);
  b3.initialCoordinates(q0.data() + 40);
  q0[43] = 0.7;
  const Pin pin("pin", b1, 0.3, Vec2(0.2, 0.1));
  const Rope rope("rope", {&b1, 1.9}, {&b2, 2.0}, {&b3, 0.0}, 3.0);
  const SlidingJoint slide("slide", b1, b2, 0.4, 43, 0.7);
  const AngleDrive drive("drive", b1, 0.3, TimeFunction::sine(0.2, 1.0, 0.0, 0.4));
  std::mt19937 rng(7);
  for (const Constraint *c : std::initializer_list<const Constraint *>{&pin, &rope, &slide, &drive}) {
    std::vector<PetscInt> dofs;
    c->coordinates(dofs);
    const std::vector<double> q = randomState(dofs, rng, q0);
    ConstraintEval at0, at1;
    c->evaluate(0.3, q.data(), nullptr, nullptr, at0);
    c->evaluate(1.7, q.data(), nullptr, nullptr, at1);
    if (c->dependsOnTime()) EXPECT_GT((at1.C - at0.C).norm(), 1e-6) << c->name();
    else EXPECT_EQ((at1.C - at0.C).norm(), 0.0) << c->name();
  }
  EXPECT_FALSE(pin.dependsOnTime());
  EXPECT_TRUE(drive.dependsOnTime());
}
