// Sensors of spatial scenes (point_sensor and frame_sensor with dimension:
// 3, docs/output.md "/sensors" and "/frames") through the whole pipeline
// (scene -> model -> generalized-alpha TS -> SensorProbe), against closed
// forms derived here: a rigid arm turned at a constant rate about a tilted
// hinge (its triad is the exponential of the rotation, exactly, since the
// drive prescribes it), and a cantilever twisted by an end torque, damped to
// rest (twist T s / GJ along the beam, torsion T / GJ, no bending).
#include "support.hpp"

#include "boomdyn/spatial_embedding.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct SensorHistory {
  std::vector<double> t;
  std::vector<std::vector<SensorReading>> points;
  std::vector<std::vector<SectionReading>> sections;
  double violation = 0; // largest constraint violation of the run
  bool completed = false;
};

class SensorRecorder : public Monitor {
public:
  SensorRecorder(Simulation &sim, SensorHistory &out) : sim_(sim), out_(out) {}
  PetscErrorCode start(const RunState &s, bool) override { return record(s); }
  PetscErrorCode afterStep(const RunState &s, std::string *) override { return record(s); }

private:
  PetscErrorCode record(const RunState &s)
  {
    PetscFunctionBeginUser;
    out_.t.push_back(s.t);
    out_.points.emplace_back(), out_.sections.emplace_back();
    PetscCall(sim_.sensors().read(s.q, s.v, out_.points.back()));
    PetscCall(sim_.sensors().readSections(s.q, s.v, out_.sections.back()));
    out_.violation = std::max(out_.violation, s.violation);
    PetscFunctionReturn(0);
  }
  Simulation &sim_;
  SensorHistory &out_;
};

SensorHistory run(const std::string &text)
{
  const Scene scene = parseScene(text, "spatial-sensors.yaml");
  SensorHistory out;
  Simulation sim(scene, PETSC_COMM_SELF, testOptions());
  check(sim.setUp());
  sim.addMonitor(std::make_unique<SensorRecorder>(sim, out));
  check(sim.run());
  out.completed = sim.summary().completed;
  return out;
}

std::string number(double x)
{
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

std::string vec(const Eigen::Vector3d &v)
{
  char text[160];
  std::snprintf(text, sizeof text, "[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
  return text;
}

} // namespace

// A rigid arm (L = 2 m, s = 0 on a hinge at p) turned from rest about the
// tilted axis n = (1, 2, 2)/3 by the angle theta(t) of a smooth_step drive
// (0 to 2 rad over 1 s: theta = 2 (10 u^3 - 15 u^4 + 6 u^5), u = t / 1 s).
// Its axis starts along a = (2, -1, 0)/sqrt 5, normal to n, its y axis along
// n. The drive prescribes the rotation, so at every step
//   triad(t) = exp(theta(t) [n]x) R0,  R0 = [a, n, a x n],
//   tip r = p + L triad(t) e_x,  velocity theta' n x (r - p),
//   angular velocity theta' n,
// and the twist is 0: the axis turns about n, normal to it, so the smallest
// rotation from the initial axis is the whole rotation. Gravity loads the
// hinge but changes none of this. Triad and tip position within 1e-10 (the
// drive and hinge rows hold to Newton's tolerance); the velocities come from
// the integrator's velocity update, which the index-3 rows do not make
// consistent: its O(h^2) error (measured 5.3e-4 of the peak rate at h = 0.01
// s) against 1e-3 of the peak rate.
TEST(SpatialSensors, RigidArmTurningAboutATiltedAxisReadsTheExponentialTriad)
{
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, 2) / 3.0, a = Eigen::Vector3d(2, -1, 0).normalized(),
                        p(0.5, -0.3, 0.2);
  const double turn = 2.0, L = 2.0;
  const std::string scene =
      "name: tilted-turn\ndimension: 3\nanalysis: dynamic\ngravity: [0, 0, -9.81]\nbodies:\n"
      "  - {name: arm, type: rigid, length: 2.0, mass: 3.0, inertia: [0.1, 1.0, 1.1], origin: " + vec(p) +
      ", axis: " + vec(a) + ", up: " + vec(n) + "}\n"
      "constraints:\n"
      "  - {type: revolute_joint, body: arm, at: start, axis: " + vec(n) + "}\n"
      "  - {type: angle_drive, body: arm, at: start, axis: " + vec(n) +
      ", angle: {type: smooth_step, t0: 0, t1: 1, from: 0, to: " + number(turn * 180.0 / kPi) + "}}\n"
      "output:\n  sensors:\n    - {name: tip, body: arm, at: end}\n"
      "  frames:\n    - {name: tip, body: arm, at: end}\n    - {name: middle, body: arm, at: 1.0}\n"
      "dynamic: {t_end: 1.0, dt: 0.01, rho_inf: 0.8}\n";
  const SensorHistory h = run(scene);
  ASSERT_TRUE(h.completed);
  ASSERT_EQ(h.points.back().size(), 1u);
  ASSERT_EQ(h.sections.back().size(), 2u);
  Eigen::Matrix3d R0;
  R0 << a, n, a.cross(n);
  double triad = 0, tip = 0, velocity = 0, omega = 0, twist = 0;
  for (std::size_t k = 0; k < h.t.size(); ++k) {
    const double u = h.t[k], angle = turn * u * u * u * (10 - 15 * u + 6 * u * u),
                 rate = turn * 30 * u * u * (1 - 2 * u + u * u);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, n).toRotationMatrix() * R0;
    const Eigen::Vector3d r = p + L * R.col(0);
    for (const SectionReading &s : h.sections[k]) {
      triad = std::max(triad, (s.triad - R).cwiseAbs().maxCoeff());
      omega = std::max(omega, (s.angularVelocity - rate * n).norm() / (1.875 * turn));
      twist = std::max(twist, std::abs(s.twist));
    }
    EXPECT_LT((h.sections[k][1].position - (p + 1.0 * R.col(0))).norm(), 1e-10);
    const SensorReading &s = h.points[k][0];
    tip = std::max(tip, (s.position3 - r).norm() / L);
    velocity = std::max(velocity, (s.velocity3 - rate * n.cross(r - p)).norm() / (1.875 * turn * L));
    EXPECT_EQ(s.position, s.position3.head<2>());
    EXPECT_LT((h.sections[k][0].position - s.position3).norm(), 1e-14);
  }
  std::printf("rigid arm about a tilted axis, %zu states: triad error %.2e, tip %.2e L, velocity %.2e of the peak rate L, "
              "angular velocity %.2e of the peak rate, twist %.2e rad, constraint violation %.2e\n",
              h.t.size(), triad, tip, velocity, omega, twist, h.violation);
  EXPECT_LT(triad, 1e-10);
  EXPECT_LT(tip, 1e-10);
  EXPECT_LT(twist, 1e-10);
  EXPECT_LT(velocity, 1e-3);
  EXPECT_LT(omega, 1e-3);
}

// A cantilever (L = 1 m along x, 4 elements, GJ = 1 N m^2) under an end
// torque T = 1 N m about its axis, fixed in space, raised over 2 s and
// damped to rest (eta_torsion 0.1 s: the first torsional mode, 15.7 rad/s,
// near critically damped). The beam stays straight and twists uniformly:
// twist(s) = T s / GJ (1 rad at the tip, a large rotation), torsion T / GJ
// everywhere, no bending, and the section triad is the rotation by the twist
// about x. The element interpolates the twist linearly, so this holds at
// every s, not only at the nodes.
TEST(SpatialSensors, CantileverUnderEndTorqueTwistsByTorqueTimesLengthOverGJ)
{
  const double T = 1.0, GJ = 1.0;
  const std::string scene =
      "name: twisted-cantilever\ndimension: 3\nanalysis: dynamic\ngravity: [0, 0, 0]\nbodies:\n"
      "  - {name: beam, type: ancf_beam, length: 1.0, elements: 4, section: {EA: 1.0e6, EI_y: 2, EI_z: 1, GJ: 1, "
      "rhoA: 1, rho_Ip: 0.01, eta_axial: 0.1, eta_bending: 0.1, eta_torsion: 0.1}}\n"
      "constraints:\n  - {type: clamp, body: beam, at: start}\n"
      "loads:\n  - {type: point_moment, body: beam, at: end, moment: [1, 0, 0], "
      "scale: {type: smooth_step, t0: 0, t1: 2, from: 0, to: 1}}\n"
      "output:\n  sensors:\n    - {name: tip, body: beam, at: end}\n"
      "  frames:\n    - {name: tip, body: beam, at: end}\n    - {name: middle, body: beam, at: 0.5}\n"
      "    - {name: inside, body: beam, at: 0.3}\n"
      "dynamic: {t_end: 6, dt: 0.01, rho_inf: 0.8}\n";
  const SensorHistory h = run(scene);
  ASSERT_TRUE(h.completed);
  const std::vector<double> at = {1.0, 0.5, 0.3};
  const std::vector<SectionReading> &last = h.sections.back();
  ASSERT_EQ(last.size(), at.size());
  double twist = 0, torsion = 0, bending = 0, triad = 0, axis = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    const double exact = T * at[i] / GJ;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(exact, Eigen::Vector3d::UnitX()).toRotationMatrix();
    twist = std::max(twist, std::abs(last[i].twist - exact) / exact);
    torsion = std::max(torsion, std::abs(last[i].strains.torsion - T / GJ) / (T / GJ));
    bending = std::max({bending, std::abs(last[i].strains.curvature2), std::abs(last[i].strains.curvature3)});
    triad = std::max(triad, (last[i].triad - R).cwiseAbs().maxCoeff());
    axis = std::max(axis, (last[i].position - Eigen::Vector3d(at[i], 0, 0)).norm());
    std::printf("s = %.2f: twist %.12f rad (exact %.12f), torsion %.12f 1/m, curvatures %.1e %.1e\n", at[i],
                last[i].twist, exact, last[i].strains.torsion, last[i].strains.curvature2,
                last[i].strains.curvature3);
  }
  std::printf("twisted cantilever at t = %g s: twist error %.2e, torsion %.2e (relative), curvature %.2e 1/m, "
              "triad %.2e, axis points off x %.2e m, tip sensor speed %.2e m/s\n",
              h.t.back(), twist, torsion, bending, triad, axis, h.points.back()[0].velocity3.norm());
  EXPECT_LT(twist, 1e-8);
  EXPECT_LT(torsion, 1e-8);
  EXPECT_LT(bending, 1e-8);
  EXPECT_LT(triad, 1e-8);
  EXPECT_LT(axis, 1e-8);
  EXPECT_LT((h.points.back()[0].position3 - Eigen::Vector3d(1, 0, 0)).norm(), 1e-8);
}

// A planar cantilever with point sensors run as a spatial model in its plane
// (spatialEmbedding, what -boom_spatial does: the sensors carry over): at
// every step the spatial sensors read the planar positions and velocities to
// 1e-8 of their size, and z stays exactly 0.
TEST(SpatialSensors, PlanarSensorsRunAsSpatialModelReadThePlanarMotion)
{
  const char *text = R"(
name: planar-cantilever-sensors
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: boom, length: 2.0, elements: 8, section: {E: 2.1e11, rho: 7850, A: 4.056e-3, I: 2.3586272e-5}}
constraints:
  - {type: clamp, name: base, body: boom, at: start}
loads:
  - {type: point_force, name: tip, body: boom, at: end, force: [0, -10000], scale: 1}
output:
  sensors:
    - {name: tip, body: boom, at: end}
    - {name: inside, body: boom, at: 0.7}
dynamic: {t_end: 0.03, dt: 1.0e-3, rho_inf: 0.8}
)";
  const Scene planar = parseScene(text, "planar.yaml");
  const Scene spatial = spatialEmbedding(planar);
  check(PetscOptionsSetValue(nullptr, "-boom_jacobian_reuse", "0"));
  const DynamicHistory a = runDynamicWith(planar, PETSC_COMM_SELF, testOptions());
  const DynamicHistory b = runDynamicWith(spatial, PETSC_COMM_SELF, testOptions());
  check(PetscOptionsClearValue(nullptr, "-boom_jacobian_reuse"));
  ASSERT_TRUE(a.summary.completed && b.summary.completed);
  ASSERT_EQ(a.sensors.size(), b.sensors.size());
  double position = 0, velocity = 0, size = 0, speed = 0, z = 0;
  for (std::size_t k = 0; k < a.sensors.size(); ++k) {
    ASSERT_EQ(b.sensors[k].size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
      const SensorReading &p = a.sensors[k][i], &s = b.sensors[k][i];
      position = std::max(position, (s.position3.head<2>() - p.position).cwiseAbs().maxCoeff());
      velocity = std::max(velocity, (s.velocity3.head<2>() - p.velocity).cwiseAbs().maxCoeff());
      size = std::max(size, p.position.cwiseAbs().maxCoeff()), speed = std::max(speed, p.velocity.norm());
      z = std::max({z, std::abs(s.position3.z()), std::abs(s.velocity3.z())});
    }
  }
  std::printf("planar sensors in the spatial model, %zu steps: positions %.2e, velocities %.2e relative, z %.1e\n",
              a.sensors.size(), position / size, velocity / speed, z);
  EXPECT_LT(position / size, 1e-8);
  EXPECT_LT(velocity / speed, 1e-8);
  EXPECT_EQ(z, 0.0);
}
