// Spatial rigid bodies through the whole pipeline (scene -> model ->
// assembly -> generalized-alpha TS), against closed forms derived here:
// the compound pendulum's small-swing frequency in two planes (two
// different moments of inertia), the precession rate of a gyroscope (a
// heavy symmetric top with its axis horizontal), energy conservation at
// rho_inf = 1 with its second-order rate, a slewing drive on a hinge, and
// planar scenes run as spatial models in their plane (-boom_spatial).
#include "spatial_trajectory.hpp"

#include "boomdyn/euler_parameters.hpp"
#include "boomdyn/spatial_embedding.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

Trajectory run(const std::string &text) { return runTrajectory(text, "spatial.yaml"); }

// A rod of 1 m and 2 kg hanging from a spherical joint at its start, tilted
// by theta0 in the x-z plane; `up` chooses which body axis is the swing axis.
std::string pendulum(double theta0, const std::string &up, double dt, double tEnd, double rho = 1.0)
{
  return "name: compound-pendulum\ndimension: 3\nanalysis: dynamic\ngravity: [0, 0, -9.81]\nbodies:\n"
         "  - {name: rod, type: rigid, length: 1.0, mass: 2.0, inertia: [0.05, 0.2, 0.23], axis: [" +
         number(std::sin(theta0)) + ", 0, " + number(-std::cos(theta0)) + "], up: " + up +
         "}\nconstraints:\n  - {type: spherical_joint, body: rod, at: start}\ndynamic: {t_end: " + number(tEnd) +
         ", dt: " + number(dt) + ", rho_inf: " + number(rho) + "}\n";
}

} // namespace

// Small swings of a compound pendulum: omega^2 = m g l / (J + m l^2) with l
// the distance of the centre of mass from the joint (0.5 m) and J the
// moment of inertia about the swing axis through the centre of mass. With
// up = y the swing axis is the body y axis (J = 0.2), with up = x the body z
// axis (J = 0.23). theta0 = 0.01 rad: the amplitude correction theta0^2/16 =
// 6e-6; the time-step error of the trapezoidal rule (rho_inf = 1) is
// (omega h)^2 / 12 = 1.2e-6 at h = 1 ms; bound 1e-4.
TEST(SpatialRigid, CompoundPendulumSwingsAtTheClosedFormFrequency)
{
  const double m = 2.0, g = 9.81, l = 0.5;
  for (const auto &[up, J] : {std::pair<std::string, double>{"[0, 1, 0]", 0.2}, {"[1, 0, 0]", 0.23}}) {
    const double omega = std::sqrt(m * g * l / (J + m * l * l));
    const Trajectory tr = run(pendulum(0.01, up, 1e-3, 3.5 * 2 * kPi / omega));
    ASSERT_TRUE(tr.completed);
    std::vector<double> x, y;
    for (const auto &q : tr.q) x.push_back(q[0]), y.push_back(q[1]);
    const double measured = crossingFrequency(tr.t, x);
    PetscPrintf(PETSC_COMM_WORLD, "  up %s: omega %.10f rad/s, closed form %.10f, relative error %.2e\n", up.c_str(),
                measured, omega, measured / omega - 1);
    EXPECT_NEAR(measured / omega, 1.0, 1e-4);
    // The swing stays in its plane: y of the centre of mass is round-off.
    double outOfPlane = 0;
    for (double v : y) outOfPlane = std::max(outOfPlane, std::abs(v));
    EXPECT_LT(outOfPlane, 1e-11);
  }
}

namespace {

// A gyroscope: a symmetric top (I3 = 0.01 about its axis, 0.006 across,
// 1 kg, centre of mass 0.1 m from the pivot) with its axis horizontal along
// x, spinning at w3 about it and precessing at Omega about the vertical.
// Its angular momentum about the pivot is I3 w3 e + I1 Omega e_z, whose rate
// I3 w3 Omega (e_z x e) equals the weight's moment m g l (e_z x e) exactly
// when Omega = m g l / (I3 w3) (the cos(theta) term of the general steady
// precession vanishes at theta = 90 deg): started on it, the top precesses
// steadily at that rate. rho_inf = 0.9 here; rho_inf = 1 below.
std::string gyroscope(double w3, double dt, double tEnd, double rho = 0.9)
{
  const double Omega = 1.0 * 9.81 * 0.1 / (0.01 * w3);
  return "name: gyroscope\ndimension: 3\nanalysis: dynamic\ngravity: [0, 0, -9.81]\nbodies:\n"
         "  - {name: top, type: rigid, length: 0.2, mass: 1.0, inertia: [0.01, 0.006, 0.006], center_of_mass: [0.1, 0, "
         "0], axis: [1, 0, 0], up: [0, 1, 0], angular_velocity: [" +
         number(w3) + ", 0, " + number(Omega) +
         "]}\nconstraints:\n  - {type: spherical_joint, body: top, at: start}\ndynamic: {t_end: " + number(tEnd) +
         ", dt: " + number(dt) + ", rho_inf: " + number(rho) + "}\n";
}

// The precession rate from the azimuth of the centre of mass at the end.
double precessionRate(const Trajectory &tr)
{
  double phi = 0, previous = 0;
  for (const auto &q : tr.q) { // unwrapped azimuth
    const double a = std::atan2(q[1], q[0]);
    double d = a - previous;
    d -= 2 * kPi * std::round(d / (2 * kPi));
    phi += d, previous = a;
  }
  return phi / tr.t.back();
}

} // namespace

TEST(SpatialRigid, GyroscopePrecessesAtTheGyroscopicRate)
{
  const double w3 = 100.0, Omega = 1.0 * 9.81 * 0.1 / (0.01 * w3);
  std::vector<double> errors;
  for (const double h : {1e-3, 5e-4, 2.5e-4}) {
    const Trajectory tr = run(gyroscope(w3, h, 1.0));
    ASSERT_TRUE(tr.completed);
    const double rate = precessionRate(tr);
    double height = 0;
    for (const auto &q : tr.q) height = std::max(height, std::abs(q[2]));
    errors.push_back(std::abs(rate / Omega - 1));
    PetscPrintf(PETSC_COMM_WORLD, "  h = %g: precession %.10f rad/s, m g l/(I3 w3) = %.10f, relative error %.2e, "
                "largest height of the centre of mass %.2e m\n", h, rate, Omega, errors.back(), height);
  }
  EXPECT_LT(errors.back(), 1e-4);
  // Second order in h: halving the step quarters the error.
  EXPECT_GT(errors[0] / errors[1], 3.0);
  EXPECT_GT(errors[1] / errors[2], 3.0);
}

// The same fast top at rho_inf = 1 (no numerical damping): it precesses at
// m g l/(I3 w3) to the time-step error (second order, within 1e-4 at
// h = 0.25 ms) and keeps its energy: the largest drift over 1 s falls with
// the step faster than h^2 and stays below 1e-9 of the kinetic energy at
// h = 0.25 ms. Without the consistent accelerations after every step that
// spatial runs at rho_inf = 1 take (generalized_alpha.cpp, docs/model.md
// §9.1), the alternating part of the index-3 accelerations grew and the top
// fell at 0.27 s at every step size.
TEST(SpatialRigid, FastTopAtRhoInfOneConservesEnergyAndPrecesses)
{
  const double w3 = 100.0, Omega = 1.0 * 9.81 * 0.1 / (0.01 * w3);
  std::vector<double> errors, drift;
  for (const double h : {1e-3, 5e-4, 2.5e-4}) {
    const Trajectory tr = run(gyroscope(w3, h, 1.0, 1.0));
    ASSERT_TRUE(tr.completed);
    errors.push_back(std::abs(precessionRate(tr) / Omega - 1));
    double d = 0;
    for (double e : tr.energy) d = std::max(d, std::abs(e - tr.energy[0]));
    drift.push_back(d / tr.energy[0]);
    PetscPrintf(PETSC_COMM_WORLD, "  rho_inf = 1, h = %g: precession relative error %.2e, largest energy drift %.2e "
                "of %.2f J\n", h, errors.back(), drift.back(), tr.energy[0]);
  }
  EXPECT_LT(errors.back(), 1e-4);
  EXPECT_GT(errors[0] / errors[1], 3.0);
  EXPECT_GT(errors[1] / errors[2], 3.0);
  EXPECT_LT(drift.back(), 1e-9);
  EXPECT_GT(drift[0] / drift[1], 3.0);
  EXPECT_GT(drift[1] / drift[2], 3.0);
}

// A swirling spherical pendulum (tilted 0.8 rad, turning about the vertical
// at 2 rad/s: a fully spatial motion) at rho_inf = 1 conserves its energy to
// the time-step error: the largest drift over 2 s falls like h^2.
TEST(SpatialRigid, EnergyIsConservedToTheTimeStepErrorAtRhoInfOne)
{
  std::vector<double> drift;
  for (const double h : {4e-3, 2e-3, 1e-3}) {
    std::string text = pendulum(0.8, "[0, 1, 0]", h, 2.0);
    text.insert(text.find("}\nconstraints"), ", angular_velocity: [0, 0, 2]");
    const Trajectory tr = run(text);
    ASSERT_TRUE(tr.completed);
    double d = 0, scale = 0;
    for (double e : tr.energy) d = std::max(d, std::abs(e - tr.energy[0]));
    scale = 2.0 * 9.81 * 0.5; // m g l
    drift.push_back(d / scale);
    PetscPrintf(PETSC_COMM_WORLD, "  h = %g: largest energy drift %.3e of m g l\n", h, drift.back());
  }
  EXPECT_LT(drift.back(), 1e-4);
  EXPECT_GT(drift[0] / drift[1], 3.0);
  EXPECT_GT(drift[1] / drift[2], 3.0);
}

// A slewing boom: a horizontal rigid boom on a vertical hinge, turned by an
// angle_drive with an acceleration-limited profile. The boom's azimuth
// follows theta(t), and the drive's multiplier is the torque about the
// axis, (J_zz + m l^2) theta'' (the weight's moment is carried by the hinge).
TEST(SpatialRigid, SlewingDriveFollowsItsProfileWithTheInertialTorque)
{
  const char *text = R"(
name: slewing
dimension: 3
analysis: dynamic
gravity: [0, 0, -9.81]
bodies:
  - {name: boom, type: rigid, length: 4.0, mass: 100, inertia: [5, 130, 133], axis: [1, 0, 0], up: [0, 1, 0]}
constraints:
  - {type: revolute_joint, body: boom, at: start, axis: [0, 0, 1]}
  - type: angle_drive
    body: boom
    at: start
    axis: [0, 0, 1]
    angle: {type: accel_limited, t0: 0.1, from: 0, to: 30, speed: 20, accel: 40}
dynamic: {t_end: 1.2, dt: 1.0e-3, rho_inf: 0.8}
)";
  const Scene scene = parseScene(text, "slewing.yaml");
  SimulationOptions options = testOptions();
  options.consistentMultipliers = true; // the acceleration-level multipliers: exact for a prescribed rigid motion
  const DynamicHistory h = runDynamicWith(scene, PETSC_COMM_WORLD, options);
  ASSERT_TRUE(h.summary.completed) << h.summary.failure;
  const TimeFunction theta = scene.constraints[1].function("angle");
  const double I = 133 + 100 * 2.0 * 2.0; // J_zz about the centre of mass + m l^2
  // Rows: boom.euler (0), revolute (1..5), drive (6).
  double torqueError = 0, torqueScale = 0, angleError = 0;
  const Trajectory tr = run(text);
  for (std::size_t k = 0; k < tr.q.size(); ++k) {
    const double azimuth = std::atan2(tr.q[k][1], tr.q[k][0]);
    angleError = std::max(angleError, std::abs(azimuth - theta.value(tr.t[k])));
  }
  for (std::size_t k = 1; k < h.time.size(); ++k) {
    const double expected = I * theta.accel(h.time[k]);
    torqueError = std::max(torqueError, std::abs(std::abs(h.multipliers[k][6]) - std::abs(expected)));
    torqueScale = std::max(torqueScale, std::abs(expected));
  }
  PetscPrintf(PETSC_COMM_WORLD, "  azimuth error %.2e rad, drive torque error %.2e of %.1f N m\n", angleError, torqueError,
              torqueScale);
  EXPECT_LT(angleError, 1e-9);
  EXPECT_LT(torqueError, 1e-6 * torqueScale);
}

namespace {

// Rigid bars: a luffed bar clamped with a moving angle carrying a point
// mass, a second one pinned to its end with a load, a third pinned to the
// ground and turned by an angle drive: every kind -boom_spatial takes. The
// two runs discretize different rotation coordinates (an angle against
// Euler parameters), so they agree to their time-step errors, which are
// second order: h = 0.1 ms (PendulumOrder in test_point_mass_order.cpp
// measures the order of both with a point mass on a pendulum).
const char *kPlanar = R"(
name: planar-in-space
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: lower, type: rigid, length: 2.0, angle: 10, section: {rhoA: 30}}
  - {name: upper, type: rigid, length: 1.5, origin: [1.969615506024416, 0.3472963553338607], angle: -30, section: {rhoA: 20}}
  - {name: arm, type: rigid, length: 1.0, origin: [3, 0], angle: 90, section: {rhoA: 10}}
constraints:
  - type: clamp
    body: lower
    at: start
    angle: {type: smooth_step, t0: 0.0, t1: 0.3, from: 10, to: 25}
  - {type: pin, body: lower, at: end, other: upper, other_at: 0.0}
  - {type: pin, body: arm, at: start}
  - type: angle_drive
    body: arm
    at: 0.5
    angle: {type: smooth_step, t0: 0.0, t1: 0.3, from: 90, to: 105}
loads:
  - {type: point_force, body: upper, at: 0.7, force: [300, -150]}
masses:
  - {body: lower, at: 1.5, mass: 40}
dynamic: {t_end: 0.3, dt: 1.0e-4, rho_inf: 0.8}
)";

} // namespace

// The planar scene and its spatial embedding give the same positions and
// multipliers to 1e-8 relative; the out-of-plane coordinates (z, e1, e2 of
// every body) stay at round-off.
TEST(SpatialRigid, PlanarSceneRunAsSpatialModelInItsPlane)
{
  const Scene planar = parseScene(kPlanar, "planar.yaml");
  const Scene spatial = spatialEmbedding(planar);
  SimulationOptions options = testOptions();
  options.consistentMultipliers = true; // the multipliers of each step's state, not the step's own (O(h))
  DynamicHistory a, b;
  runPlanarAndSpatial(planar, spatial, options, a, b);
  ASSERT_TRUE(a.summary.completed) << a.summary.failure;
  ASSERT_TRUE(b.summary.completed) << b.summary.failure;
  ASSERT_EQ(a.time.size(), b.time.size());
  const Model pm(planar), sm(spatial);
  // Positions: (x_c, y_c, theta) against (x, y, 2 atan2(e3, e0)); out of plane z, e1, e2.
  double position = 0, outOfPlane = 0;
  const std::size_t nb = planar.bodies.size();
  for (std::size_t i = 0; i < nb; ++i) {
    const double *p = a.finalState.data() + 3 * i, *s = b.finalState.data() + 7 * i;
    double angle = 2 * std::atan2(s[6], s[3]) - p[2];
    angle -= 2 * kPi * std::round(angle / (2 * kPi));
    position = std::max({position, std::abs(s[0] - p[0]), std::abs(s[1] - p[1]), std::abs(angle)});
    outOfPlane = std::max({outOfPlane, std::abs(s[2]), std::abs(s[4]), std::abs(s[5])});
  }
  // Multipliers by constraint name: planar row -> spatial row.
  auto rowOf = [](const Model &m, const std::string &name) {
    for (const ConstraintItem *c : m.constraints())
      if (c->name() == name) return static_cast<int>(c->firstRow() - m.numCoordinates());
    ADD_FAILURE() << "no constraint " << name;
    return 0;
  };
  // The pins' two rows are the revolute joints' first two; the clamp with
  // a moving angle is a revolute joint plus a drive of the same names.
  const std::vector<std::pair<std::string, int>> rows = {{"clamp0.pin", 0}, {"clamp0.pin", 1}, {"clamp0.angle", 0},
                                                         {"pin1", 0},       {"pin1", 1},       {"pin2", 0},
                                                         {"pin2", 1},       {"angle_drive3", 0}};
  double multiplier = 0;
  for (const auto &[name, row] : rows) {
    const int pr = rowOf(pm, name) + row, sr = rowOf(sm, name) + row;
    double diff = 0, scale = 0;
    for (std::size_t k = 1; k < a.time.size(); ++k)
      diff = std::max(diff, std::abs(a.multipliers[k][pr] - b.multipliers[k][sr])),
      scale = std::max(scale, std::abs(a.multipliers[k][pr]));
    multiplier = std::max(multiplier, diff / scale);
  }
  PetscPrintf(PETSC_COMM_WORLD, "  planar vs spatial: positions %.2e (m, rad), multipliers %.2e relative, out of "
              "plane %.2e\n", position, multiplier, outOfPlane);
  EXPECT_LT(position, 1e-8);
  EXPECT_LT(multiplier, 1e-8);
  EXPECT_LT(outOfPlane, 1e-12);
  EXPECT_EQ(a.summary.steps, b.summary.steps);
}

