// Spatial ANCF beams (type ancf_beam, dimension: 3) through the whole
// pipeline (scene -> model -> assembly -> generalized-alpha TS), against
// closed forms derived here: roll-up of a cantilever under an end moment
// (damped to rest: the dynamic path to the static solution; statics of
// spatial scenes: test_spatial_statics.cpp), the
// first bending frequency in both planes and the first torsional frequency
// from free vibration, energy conservation at rho_inf = 1, and a planar
// beam scene run as a spatial model in its plane (-boom_spatial).
#include "spatial_trajectory.hpp"

#include "boomdyn/spatial_embedding.hpp"

#include <algorithm>
#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

Trajectory run(const std::string &text) { return runTrajectory(text, "spatial-beam.yaml"); }

// A cantilever of length 1 m along x with unit section constants, clamped
// at its start, with the given section, loads and run.
std::string cantilever(int elements, const std::string &section, const std::string &loads, const std::string &dynamic)
{
  return "name: spatial-cantilever\ndimension: 3\nanalysis: dynamic\ngravity: [0, 0, 0]\nbodies:\n"
         "  - {name: beam, type: ancf_beam, length: 1.0, elements: " +
         std::to_string(elements) + ", section: {" + section + "}}\nconstraints:\n  - {type: clamp, body: beam, at: start}\n" +
         loads + "dynamic: {" + dynamic + "}\n";
}

} // namespace

// Roll-up: a cantilever (EI = 1 N m^2, L = 1 m) under an end moment M about
// the global z axis bends into a circular arc of radius EI/M (Euler's
// elastica with an end couple; inextensible in the limit EA -> inf), so the
// tip is at x = (EI/M) sin(ML/EI), y = (EI/M)(1 - cos(ML/EI)). M = pi/2 EI/L
// turns the tip by a quarter turn: x = y = 2L/pi. The moment rises smoothly
// over 2 s; Kelvin-Voigt damping (eta 0.5 s, the first mode about critically
// damped) brings the beam to rest by t = 12 s. EA = 1e6 EI/L^2 leaves an
// axial strain of at most ~1e-6. Also with the moment about the axis
// (0, 1, 1)/sqrt 2 between the two principal axes of a section with
// EI_y = EI_z: the arc lies in the plane normal to that axis.
TEST(SpatialBeamScenes, RollUpUnderEndMomentIsACircularArc)
{
  const double M = kPi / 2, R = 1.0 / M;
  const std::string section = "EA: 1.0e6, EI_y: 1, EI_z: 1, GJ: 1, rhoA: 1, rho_Ip: 0.01, eta_bending: 0.5, "
                              "eta_axial: 0.5, eta_torsion: 0.5";
  for (int axisCase = 0; axisCase < 2; ++axisCase) {
    const double c = std::sqrt(0.5);
    const Eigen::Vector3d n = axisCase == 0 ? Eigen::Vector3d(0, 0, 1) : Eigen::Vector3d(0, c, c);
    const std::string loads = "loads:\n  - {type: point_moment, body: beam, at: end, moment: [0, " +
                              number(M * n[1]) + ", " + number(M * n[2]) +
                              "], scale: {type: smooth_step, t0: 0, t1: 2, from: 0, to: 1}}\n";
    const Trajectory tr = run(cantilever(16, section, loads, "t_end: 12, dt: 0.01, rho_inf: 0.8"));
    ASSERT_TRUE(tr.completed);
    const std::vector<double> &q = tr.q.back();
    const int tip = 7 * 16;
    const Eigen::Vector3d r(q[tip], q[tip + 1], q[tip + 2]);
    // In the plane normal to n: along x by R sin(phi), across by R (1 - cos phi) in the direction n x e_x.
    const Eigen::Vector3d across = n.cross(Eigen::Vector3d::UnitX());
    const Eigen::Vector3d exact = R * std::sin(M * 1.0) * Eigen::Vector3d::UnitX() + R * (1 - std::cos(M)) * across;
    const double error = (r - exact).norm();
    std::printf("roll-up, moment axis %d: tip (%.8f, %.8f, %.8f), exact (%.8f, %.8f, %.8f), error %.3e L\n", axisCase,
                r[0], r[1], r[2], exact[0], exact[1], exact[2], error);
    EXPECT_LT(error, 1e-4);
  }
}

// Free vibration of a cantilever after a step load (L = 1 m). A tip force P
// switched on at t = 0 makes the tip oscillate about the static deflection
// P L^3/(3 EI) (exact for the cubic element in linear statics) at the
// bending frequencies omega_n = (beta_n L)^2 sqrt(EI/(rhoA L^4)), beta_1 L
// = 1.8751040687; the first dominates the tip (the second's amplitude is
// (omega_1/omega_2)^2 = 2.5 % of it). A tip torque T switched on at t = 0
// twists the tip about T L/GJ at omega_n = (2n - 1) pi/(2L) sqrt(GJ/rhoIp);
// all torsional modes' tip responses cross zero together (odd multiples of
// the first), so the crossings give omega_1. Small loads (linear response),
// EI_y = 2, EI_z = 1 (different frequencies in the two planes), rho_inf = 1
// (no numerical damping) and 80 steps per first period.
TEST(SpatialBeamScenes, FirstBendingFrequenciesInBothPlanesAndFirstTorsionalFrequency)
{
  const double EIy = 2.0, EIz = 1.0, GJ = 0.5, rhoA = 1.0, rhoIp = 0.02, P = 1e-4, T = 1e-4;
  const double b1 = 1.8751040687119611;
  const std::string section = "EA: 1.0e4, EI_y: 2, EI_z: 1, GJ: 0.5, rhoA: 1, rho_Ip: 0.02";
  const int n = 16, tip = 7 * n;
  struct Case {
    const char *what;
    std::string load;
    int coordinate;
    double offset, omega;
  };
  const double wz = b1 * b1 * std::sqrt(EIz / rhoA), wy = b1 * b1 * std::sqrt(EIy / rhoA),
               wt = kPi / 2 * std::sqrt(GJ / rhoIp);
  const Case cases[] = {
      {"in-plane bending (y, EI_z)", "{type: point_force, body: beam, at: end, force: [0, " + number(P) + ", 0]}",
       tip + 1, P / (3 * EIz), wz},
      {"out-of-plane bending (z, EI_y)", "{type: point_force, body: beam, at: end, force: [0, 0, " + number(P) + "]}",
       tip + 2, P / (3 * EIy), wy},
      {"torsion", "{type: point_moment, body: beam, at: end, moment: [" + number(T) + ", 0, 0]}", tip + 6, T / GJ, wt},
  };
  for (const Case &c : cases) {
    const double period = 2 * kPi / c.omega, dt = period / 80;
    const Trajectory tr =
        run(cantilever(n, section, "loads:\n  - " + c.load + "\n",
                       "t_end: " + number(10.25 * period) + ", dt: " + number(dt) + ", rho_inf: 1"));
    ASSERT_TRUE(tr.completed) << c.what;
    std::vector<double> x;
    for (const auto &q : tr.q) x.push_back(q[c.coordinate] - c.offset);
    const double w = crossingFrequency(tr.t, x), rel = w / c.omega - 1;
    std::printf("%s: omega %.8f rad/s, closed form %.8f, relative %.3e\n", c.what, w, c.omega, rel);
    // Generalized-alpha at rho_inf = 1 lengthens the period by (omega h)^2/12
    // = 5.1e-4 at 80 steps per period (the trapezoidal rule; measured -5.20e-4
    // in both bending planes), the second mode could move the bending
    // crossings by up to 2.5 %/(pi N) ~ 8e-4 over N = 10 periods, and the
    // linear twist interpolation with consistent rotary inertia raises the
    // torsional omega_1 by about (pi/2n)^2/24 = 4e-4 (measured +2.6e-4 in all).
    EXPECT_LT(std::abs(rel), 2e-3) << c.what;
  }
}

// Energy at rho_inf = 1: a cantilever under its own weight released from
// the straight, unloaded shape oscillates with constant total energy
// (kinetic + strain + potential of gravity); the drift falls with the
// square of the step (trapezoidal-rule energy error of a nonlinear system).
TEST(SpatialBeamScenes, EnergyIsConservedAtRhoInfOne)
{
  const std::string section = "EA: 1.0e4, EI_y: 2, EI_z: 1, GJ: 0.5, rhoA: 1, rho_Ip: 0.02";
  double drift[2];
  for (int k = 0; k < 2; ++k) {
    std::string text = cantilever(8, section, "", "t_end: 2, dt: " + number(k == 0 ? 0.01 : 0.005) + ", rho_inf: 1");
    text.replace(text.find("gravity: [0, 0, 0]"), 18, "gravity: [0, -6, -8]");
    const Trajectory tr = run(text);
    ASSERT_TRUE(tr.completed);
    // Scale: the work of gravity over the static deflection, ~ rhoA g^2 L^5 / EI.
    const double scale = 100.0 / 1.0;
    drift[k] = 0;
    for (double e : tr.energy) drift[k] = std::max(drift[k], std::abs(e - tr.energy.front()) / scale);
    std::printf("energy drift at dt %.3f: %.3e of rhoA g^2 L^5/EI\n", k == 0 ? 0.01 : 0.005, drift[k]);
  }
  EXPECT_LT(drift[1], 1e-4);
  EXPECT_GT(drift[0] / drift[1], 3.0); // second order: 4
}

// A planar cantilever (the 2 m steel box of inputs/cantilever_dynamic.yaml,
// a 10 kN step tip load, gravity) run as a spatial model in its plane
// (spatialEmbedding, what -boom_spatial does): every node's position and
// slope equal the planar run's at the end to 1e-8 relative, and the
// out-of-plane coordinates (z, z', twist) stay exactly zero (nothing loads
// them and the in-plane state produces no out-of-plane force).
TEST(SpatialBeamScenes, PlanarBeamSceneRunAsSpatialModelInItsPlane)
{
  const char *text = R"(
name: planar-cantilever
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: boom, length: 2.0, elements: 16, section: {E: 2.1e11, rho: 7850, A: 4.056e-3, I: 2.3586272e-5}}
constraints:
  - {type: clamp, name: base, body: boom, at: start}
loads:
  - {type: point_force, name: tip, body: boom, at: end, force: [0, -10000], scale: 1}
dynamic: {t_end: 0.05, dt: 1.0e-3, rho_inf: 0.8}
)";
  const Scene planar = parseScene(text, "planar.yaml");
  const Scene spatial = spatialEmbedding(planar);
  SimulationOptions options = testOptions();
  DynamicHistory a, b;
  runPlanarAndSpatial(planar, spatial, options, a, b);
  ASSERT_TRUE(a.summary.completed) << a.summary.failure;
  ASSERT_TRUE(b.summary.completed) << b.summary.failure;
  ASSERT_EQ(a.time.size(), b.time.size());
  double position = 0, size = 0, outOfPlane = 0;
  for (int n = 0; n <= 16; ++n) {
    const double *p = a.finalState.data() + 4 * n, *s = b.finalState.data() + 7 * n;
    for (int c = 0; c < 2; ++c) {
      position = std::max({position, std::abs(s[c] - p[c]), std::abs(s[3 + c] - p[2 + c])});
      size = std::max({size, std::abs(p[c]), std::abs(p[2 + c])});
    }
    outOfPlane = std::max({outOfPlane, std::abs(s[2]), std::abs(s[5]), std::abs(s[6])});
  }
  std::printf("planar beam in its plane: positions and slopes %.3e relative, out of plane %.3e\n", position / size,
              outOfPlane);
  EXPECT_LT(position / size, 1e-8);
  EXPECT_EQ(outOfPlane, 0.0);
}
