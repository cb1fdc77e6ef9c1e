// Spatial cylindrical and prismatic joints (and the slide drive) through the
// whole pipeline, against closed forms derived here: a block sliding down
// an inclined prismatic joint under gravity (x = g sin(alpha) t^2 / 2, the
// joint force m g cos(alpha) normal to the incline and the moment of the
// offset centre of mass), the same block driven along the incline, and a
// body spinning and sliding freely on a cylindrical joint (constant rates,
// the centripetal force and the gyroscopic moment of a tilted principal
// axis). The joint's force and moment are read from its multipliers,
// -C_q^T lambda on the body's coordinates (docs/model.md §0.4, §9.2).
#include "spatial_trajectory.hpp"

#include "boomdyn/euler_parameters.hpp"

#include <Eigen/Geometry>

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Force F and moment M (about the centre of mass, global axes) the joint
// `name` applies to the rigid body whose 7 coordinates come first in the
// joint, at the last step of h.
struct Wrench {
  Vec3 force, moment;
};

Wrench jointWrench(const Scene &scene, const DynamicHistory &h, const std::string &name)
{
  const Model model(scene);
  const ConstraintItem *item = nullptr;
  for (const ConstraintItem *c : model.constraints())
    if (c->name() == name) item = c;
  EXPECT_NE(item, nullptr) << name;
  const Constraint &c = item->constraint();
  std::vector<PetscInt> dofs;
  c.coordinates(dofs);
  std::vector<double> q(dofs.size());
  for (std::size_t k = 0; k < dofs.size(); ++k) q[k] = h.finalState[dofs[k]];
  ConstraintEval ev;
  c.evaluate(h.time.back(), q.data(), nullptr, nullptr, ev);
  const int first = static_cast<int>(item->firstRow() - model.numCoordinates());
  const Eigen::Map<const Eigen::VectorXd> lambda(h.multipliers.back().data() + first, c.numRows());
  const Eigen::VectorXd Q = -ev.Cq.leftCols(7).transpose() * lambda;
  // A moment M does the work M . omega = M . 2 E(p) pdot: Q_p = 2 E^T M, so
  // M = E Q_p / 2 (E E^T = I at |p| = 1).
  const euler::Vec4 p(q[3], q[4], q[5], q[6]);
  return {Q.head<3>(), 0.5 * euler::globalRateMatrix(p) * Q.tail<4>()};
}

Vec3 unit(const Vec3 &v) { return v.normalized(); }

std::string vec(const Vec3 &v) { return "[" + number(v[0]) + ", " + number(v[1]) + ", " + number(v[2]) + "]"; }

// A block of 2 kg on an incline at alpha = 30 deg, its body x axis down the
// slope e = (cos a, 0, -sin a), y horizontal, z = n = (sin a, 0, cos a) the
// incline's normal; the centre of mass at c' = (0.3, 0.1, 0.2) from the
// joint point s = 0.
const double kAlpha = 30.0 * kPi / 180.0, kMass = 2.0, kG = 9.81;
const Vec3 kCenter(0.3, 0.1, 0.2);

std::string incline(const std::string &slide, double tEnd)
{
  const Vec3 e(std::cos(kAlpha), 0, -std::sin(kAlpha));
  return "name: incline\ndimension: 3\nanalysis: dynamic\ngravity: [0, 0, -9.81]\nbodies:\n"
         "  - {name: block, type: rigid, length: 1.0, mass: 2.0, inertia: [0.2, 0.25, 0.3], products: [0.01, 0, 0.02], "
         "center_of_mass: " + vec(kCenter) + ", axis: " + vec(e) + ", up: [0, 1, 0]}\n"
         "constraints:\n  - {type: prismatic_joint, name: slider, body: block, at: start, axis: " + vec(e) + slide +
         "}\ndynamic: {t_end: " + number(tEnd) + ", dt: 1.0e-3, rho_inf: 0.8}\n";
}

// The joint point's position at each step: r_P = x - R(p) c'.
Vec3 jointPoint(const std::vector<double> &q)
{
  const euler::Vec4 p(q[3], q[4], q[5], q[6]);
  return Vec3(q[0], q[1], q[2]) - euler::rotation(p) * kCenter;
}

// Hand statics of the block in its accelerating frame: it translates with
// acceleration a (no rotation), so the joint force is F = m (a - g) and the
// joint's moment about the centre of mass is zero; about the joint point P
// it is M_P = c x F with c = R c' the arm of the centre of mass.
void expectBlockWrench(const Wrench &w, const Vec3 &a, const Mat3 &R, double &forceError, double &momentError)
{
  const Vec3 F = kMass * (a - Vec3(0, 0, -kG));
  const Vec3 arm = R * kCenter;
  const Vec3 MP = w.moment + arm.cross(w.force); // moment about P from the joint's wrench
  forceError = (w.force - F).norm() / F.norm();
  momentError = (MP - arm.cross(F)).norm() / arm.cross(F).norm();
}

} // namespace

// Free slide: x(t) = g sin(alpha) t^2 / 2 along the slope (generalized-alpha
// integrates a constant acceleration exactly: round-off), no motion across
// it and no rotation; the joint pushes with m g cos(alpha) along the normal
// n, and its moment about the joint point is c x (m g cos(alpha) n) =
// m g cos(alpha) (c'_y e - c'_x y): a roll moment about the slope axis from
// the sideways offset c'_y and a pitch moment from the offset c'_x along it.
TEST(SpatialAxisJoints, BlockSlidesDownAnInclinedPrismaticJoint)
{
  const std::string text = incline("", 1.0);
  const Trajectory tr = runTrajectory(text, "incline.yaml");
  ASSERT_TRUE(tr.completed);
  const Vec3 e(std::cos(kAlpha), 0, -std::sin(kAlpha)), n(std::sin(kAlpha), 0, std::cos(kAlpha));
  const Vec3 r0 = jointPoint(tr.q[0]);
  const euler::Vec4 p0(tr.q[0][3], tr.q[0][4], tr.q[0][5], tr.q[0][6]);
  double along = 0, across = 0, turn = 0;
  for (std::size_t k = 0; k < tr.q.size(); ++k) {
    const Vec3 d = jointPoint(tr.q[k]) - r0;
    const double x = 0.5 * kG * std::sin(kAlpha) * tr.t[k] * tr.t[k];
    along = std::max(along, std::abs(d.dot(e) - x));
    across = std::max(across, (d - d.dot(e) * e).norm());
    const euler::Vec4 p(tr.q[k][3], tr.q[k][4], tr.q[k][5], tr.q[k][6]);
    turn = std::max(turn, (p - p0).norm());
  }
  SimulationOptions options = testOptions();
  options.consistentMultipliers = true;
  const Scene scene = parseScene(text, "incline.yaml");
  const DynamicHistory h = runDynamicWith(scene, PETSC_COMM_WORLD, options);
  ASSERT_TRUE(h.summary.completed) << h.summary.failure;
  const Wrench w = jointWrench(scene, h, "slider");
  double forceError, momentError;
  const Mat3 R = euler::rotation(p0);
  expectBlockWrench(w, kG * std::sin(kAlpha) * e, R, forceError, momentError);
  const Vec3 arm = R * kCenter, MP = w.moment + arm.cross(w.force);
  PetscPrintf(PETSC_COMM_WORLD,
              "  slide error %.2e m (x = %.6f m at 1 s), across %.2e m, rotation %.2e; joint force %.6f N along n "
              "(m g cos a = %.6f), force error %.2e, moment about P [%.6f, %.6f, %.6f] N m, error %.2e\n",
              along, 0.5 * kG * std::sin(kAlpha), across, turn, w.force.dot(n), kMass * kG * std::cos(kAlpha),
              forceError, MP[0], MP[1], MP[2], momentError);
  EXPECT_LT(along, 1e-10);
  EXPECT_LT(across, 1e-12);
  EXPECT_LT(turn, 1e-12);
  EXPECT_NEAR(w.force.dot(n), kMass * kG * std::cos(kAlpha), 1e-9);
  EXPECT_LT(forceError, 1e-9);
  EXPECT_LT(momentError, 1e-9);
  // The hand formula of the moment about P in the block's axes (e, y, n).
  const double f = kMass * kG * std::cos(kAlpha);
  EXPECT_NEAR(MP.dot(e), f * kCenter[1], 1e-9);
  EXPECT_NEAR(MP.dot(Vec3(0, 1, 0)), -f * kCenter[0], 1e-9);
  EXPECT_NEAR(MP.dot(n), 0.0, 1e-9);
}

// Slide drive: the same block moved along the slope by an acceleration-
// limited profile s(t). The block follows s(t) exactly and the joint force is
// m (s'' e - g): along the slope m (s'' - g sin(alpha)) (the drive force),
// across it m g cos(alpha). Checked at 0.3 s, inside the acceleration phase
// (s'' = 4 m/s^2), so that the drive's gamma and C_t are exercised.
TEST(SpatialAxisJoints, SlideDriveMovesTheBlockAlongItsProfile)
{
  const std::string profile = ", slide: {type: accel_limited, t0: 0.1, from: 0, to: 0.5, speed: 1, accel: 4}";
  const std::string text = incline(profile, 0.3);
  const Scene scene = parseScene(text, "incline-drive.yaml");
  const TimeFunction s = scene.constraints[0].function("slide");
  const Trajectory tr = runTrajectory(text, "incline-drive.yaml");
  ASSERT_TRUE(tr.completed);
  const Vec3 e(std::cos(kAlpha), 0, -std::sin(kAlpha));
  const Vec3 r0 = jointPoint(tr.q[0]);
  double error = 0;
  for (std::size_t k = 0; k < tr.q.size(); ++k)
    error = std::max(error, (jointPoint(tr.q[k]) - r0 - s.value(tr.t[k]) * e).norm());
  SimulationOptions options = testOptions();
  options.consistentMultipliers = true;
  const DynamicHistory h = runDynamicWith(scene, PETSC_COMM_WORLD, options);
  ASSERT_TRUE(h.summary.completed) << h.summary.failure;
  const Wrench w = jointWrench(scene, h, "slider");
  const euler::Vec4 p0(tr.q[0][3], tr.q[0][4], tr.q[0][5], tr.q[0][6]);
  double forceError, momentError;
  const double acc = s.accel(h.time.back());
  expectBlockWrench(w, acc * e, euler::rotation(p0), forceError, momentError);
  PetscPrintf(PETSC_COMM_WORLD,
              "  drive: position error %.2e m, s = %.6f m, s'' = %.3f m/s^2, drive force %.6f N (m (s'' - g sin a) = "
              "%.6f), force error %.2e, moment error %.2e\n",
              error, s.value(h.time.back()), acc, w.force.dot(e), kMass * (acc - kG * std::sin(kAlpha)), forceError,
              momentError);
  EXPECT_NEAR(acc, 4.0, 1e-12);
  EXPECT_LT(error, 1e-10);
  EXPECT_LT(forceError, 1e-9);
  EXPECT_LT(momentError, 1e-9);
}

namespace {

// A body spinning at w about a cylindrical joint's axis e and sliding along
// it at v, without gravity: both rates stay constant (the joint's forces do
// no work along the free directions). The centre of mass c' = (0.4, 0.15, 0)
// sits 0.15 m off the axis (body x), and the products of inertia tilt the
// principal axes away from it.
const Vec3 kSpinCenter(0.4, 0.15, 0.0);

std::string spinner(double w, double v, double dt, double tEnd)
{
  const Vec3 e = unit(Vec3(1, 2, 2));
  return "name: spinner\ndimension: 3\nanalysis: dynamic\ngravity: [0, 0, 0]\nbodies:\n"
         "  - {name: rotor, type: rigid, length: 1.0, mass: 3.0, inertia: [0.2, 0.5, 0.6], products: [0.03, 0.01, "
         "-0.02], center_of_mass: " + vec(kSpinCenter) + ", origin: [0.1, -0.2, 0.3], axis: " + vec(e) +
         ", up: [0, 0, 1], velocity: " + vec(v * e) + ", angular_velocity: " + vec(w * e) +
         "}\nconstraints:\n  - {type: cylindrical_joint, name: shaft, body: rotor, at: start, axis: " + vec(e) +
         "}\ndynamic: {t_end: " + number(tEnd) + ", dt: " + number(dt) + ", rho_inf: 0.8}\n";
}

} // namespace

// Free spin and slide: the joint point moves at v along e (exactly: no joint
// row has a component along e), the body turns at w about e: R(t) =
// Rot(e, w t) R0, to the time-step error (second order, checked at two
// steps, within the phase error (w h)^2/12 w t). Hand statics at the end:
// the joint force is the centripetal force -m w^2 c_perp (c_perp the arm of the centre of mass across the axis) and
// its moment about the centre of mass is the gyroscopic moment
// w x (J w) = w^2 e x (J e), J = R J' R^T.
TEST(SpatialAxisJoints, CylindricalJointSpinsAndSlidesAtConstantRates)
{
  const double w = 3.0, v = 0.5, tEnd = 2.0;
  const Vec3 e = unit(Vec3(1, 2, 2));
  std::vector<double> spinErrors;
  for (const double dt : {2e-3, 1e-3}) {
    const std::string text = spinner(w, v, dt, tEnd);
    const Trajectory tr = runTrajectory(text, "spinner.yaml");
    ASSERT_TRUE(tr.completed);
    const euler::Vec4 p0(tr.q[0][3], tr.q[0][4], tr.q[0][5], tr.q[0][6]);
    const Mat3 R0 = euler::rotation(p0);
    auto point = [&](const std::vector<double> &q) {
      const euler::Vec4 p(q[3], q[4], q[5], q[6]);
      return Vec3(Vec3(q[0], q[1], q[2]) - euler::rotation(p) * kSpinCenter);
    };
    const Vec3 r0 = point(tr.q[0]);
    double slide = 0, spin = 0, energy = 0;
    for (std::size_t k = 0; k < tr.q.size(); ++k) {
      slide = std::max(slide, (point(tr.q[k]) - r0 - v * tr.t[k] * e).norm());
      const euler::Vec4 p(tr.q[k][3], tr.q[k][4], tr.q[k][5], tr.q[k][6]);
      const Mat3 expected = Eigen::AngleAxisd(w * tr.t[k], e).toRotationMatrix() * R0;
      spin = std::max(spin, (euler::rotation(p) - expected).norm());
      energy = std::max(energy, std::abs(tr.energy[k] / tr.energy[0] - 1));
    }
    spinErrors.push_back(spin);
    PetscPrintf(PETSC_COMM_WORLD, "  h = %g: slide error %.2e m, rotation error %.2e (after %.0f rad), energy %.2e\n",
                dt, slide, spin, w * tEnd, energy);
    EXPECT_LT(slide, 1e-10);
    // The trapezoidal rule's phase error of a rotation, (w h)^2/12 per radian.
    EXPECT_LT(spin, std::pow(w * dt, 2) / 12 * w * tEnd);
    EXPECT_LT(energy, 1e-6);
  }
  EXPECT_GT(spinErrors[0] / spinErrors[1], 3.0); // second order
  // Reactions at the end of the finer run against hand statics.
  const Scene scene = parseScene(spinner(w, v, 1e-3, tEnd), "spinner.yaml");
  SimulationOptions options = testOptions();
  options.consistentMultipliers = true;
  const DynamicHistory h = runDynamicWith(scene, PETSC_COMM_WORLD, options);
  ASSERT_TRUE(h.summary.completed) << h.summary.failure;
  const Wrench wr = jointWrench(scene, h, "shaft");
  const euler::Vec4 p(h.finalState[3], h.finalState[4], h.finalState[5], h.finalState[6]);
  const Mat3 R = euler::rotation(p);
  Mat3 Jb;
  Jb << 0.2, 0.03, -0.02, 0.03, 0.5, 0.01, -0.02, 0.01, 0.6;
  const Vec3 arm = R * kSpinCenter, perp = arm - arm.dot(e) * e;
  const Vec3 F = -3.0 * w * w * perp, M = w * w * e.cross(R * Jb * R.transpose() * e);
  PetscPrintf(PETSC_COMM_WORLD,
              "  joint force %.6f N (m w^2 r = %.6f), error %.2e; moment about the centre of mass %.6f N m "
              "(w^2 |e x J e| = %.6f), error %.2e\n",
              wr.force.norm(), F.norm(), (wr.force - F).norm() / F.norm(), wr.moment.norm(), M.norm(),
              (wr.moment - M).norm() / M.norm());
  EXPECT_LT((wr.force - F).norm(), 1e-5 * F.norm());
  EXPECT_LT((wr.moment - M).norm(), 1e-5 * M.norm());
}
