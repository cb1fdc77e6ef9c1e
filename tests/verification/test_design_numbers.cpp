// Design numbers of a run (docs/output.md "Design numbers";
// src/simulation/design_numbers.cpp), fed by the same sensor reads as the
// results file, against closed forms:
//  - a 1 t payload on an elastic rope (EA = 1e5 N, 1 m, pretensioned to the
//    static tension, so k = EA / L0 = EA + T_s) from a rigid, clamped ceiling, started static under its weight and an extra downward
//    force F = 0.5 m g that is removed within one step: static tension
//    T_s = 1.5 m g (t = 0, exact to the static solve), peak = T_s at t = 0
//    (dynamic factor 1), then an oscillation about m g with amplitude
//    0.5 m g: minimum 0.5 m g (factor 1/3) half a period omega = sqrt(k/m)
//    later (rho_inf = 1: no numerical damping; sampled at h = 1e-3 s the
//    minimum is within (omega h)^2 / 2 = 5e-5 of the continuous one);
//  - a cantilever (2 m, rhoA 54.5 kg/m) carrying the payload on a rope from
//    its clamped root over a pulley at its tip, static start: root moment
//    at t = 0 (the clamp's reaction moment) m g Lb + rhoA g Lb^2 / 2 (the
//    rope's horizontal part pulls root and tip together: no moment).
#include "support.hpp"

#include "boomdyn/design_numbers.hpp"

#include <cmath>
#include <map>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double g = 9.81, m = 1000.0;

class DesignRecorder : public Monitor {
public:
  explicit DesignRecorder(Simulation &sim) : sim_(sim), design(sim.model()) {}
  PetscErrorCode start(const RunState &s, bool) override { return record(s); }
  PetscErrorCode afterStep(const RunState &s, std::string *) override { return record(s); }
  DesignNumbers design;

private:
  PetscErrorCode record(const RunState &s)
  {
    std::vector<double> slacks, multipliers, outputs;
    PetscFunctionBeginUser;
    PetscCall(sim_.sensors().readJoints(s.q, s.lambda, slacks, multipliers));
    PetscCall(sim_.sensors().readOutputs(s.t, s.q, s.v, multipliers, outputs));
    design.update(s.t, outputs, multipliers);
    PetscFunctionReturn(0);
  }
  Simulation &sim_;
};

std::map<std::string, double> designNumbers(const std::string &text, std::string *report)
{
  const Scene scene = parseScene(text, "design.yaml");
  Simulation sim(scene, PETSC_COMM_WORLD, testOptions(0));
  check(sim.setUp());
  auto recorder = std::make_unique<DesignRecorder>(sim);
  DesignRecorder *r = recorder.get();
  sim.addMonitor(std::move(recorder));
  check(sim.run());
  EXPECT_TRUE(sim.summary().completed) << sim.summary().failure;
  std::map<std::string, double> out;
  for (const auto &[name, value] : r->design.attributes()) out[name] = value;
  *report = r->design.report();
  return out;
}

} // namespace

TEST(DesignNumbers, SuddenUnloadingOfAHangingPayload)
{
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "300 steps of a 6-coordinate model: 10 s on 2 ranks for nothing; the design numbers on 2 "
                                 "ranks are DesignNumbers.RootMomentOfACantileverCarryingAPayload";
  const double F = 0.5 * m * g, k = 1.0e5 + 1.5 * m * g, w = std::sqrt(k / m);
  char text[2048];
  std::snprintf(text, sizeof text, R"(
name: unloading
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: ceiling, type: rigid, length: 0.2, origin: [-0.1, 0], section: {rhoA: 1}}
  - {name: payload, type: rigid, length: 0.2, origin: [-0.1, -1.0], section: {rhoA: 5000}}
constraints:
  - {type: clamp, name: top, body: ceiling, at: start}
  - {type: angle_drive, body: payload, at: 0.1, angle: 0}
  - {type: elastic_rope, name: hoist, from: ceiling, from_at: 0.1, to: payload, to_at: 0.1, EA: 1.0e5, pretension: %.17g}
loads:
  - {type: point_force, body: payload, at: 0.1, force: [0, %.17g], scale: {type: ramp, t0: 0, t1: 1.0e-3, from: 1, to: 0}}
dynamic: {t_end: %.17g, dt: 1.0e-3, rho_inf: 1.0, initial: static}
)",
                1.5 * m * g, -F, 0.75 * 2 * M_PI / w);
  std::string report;
  const auto d = designNumbers(text, &report);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  PetscPrintf(PETSC_COMM_SELF, "%s", report.c_str());
  const std::string p = "design.elastic_rope.hoist.";
  ASSERT_TRUE(d.count(p + "dynamic_factor"));
  const double tMin = M_PI / w + 0.5e-3; // half a period after the force is gone (removed over one step)
  PetscPrintf(PETSC_COMM_SELF,
              "  static %.9g N (exact %.9g), minimum %.9g N (exact %.9g, rel. %.1e) at t = %.4f s (exact %.4f)\n",
              d.at(p + "static_tension_N"), 1.5 * m * g, d.at(p + "min_tension_N"), 0.5 * m * g,
              std::abs(d.at(p + "min_tension_N") / (0.5 * m * g) - 1), d.at(p + "min_tension_time_s"), tMin);
  EXPECT_NEAR(d.at(p + "static_tension_N"), 1.5 * m * g, 1e-9 * m * g);
  EXPECT_NEAR(d.at(p + "peak_tension_N"), 1.5 * m * g, 1e-9 * m * g);
  EXPECT_EQ(d.at(p + "peak_tension_time_s"), 0.0);
  EXPECT_NEAR(d.at(p + "dynamic_factor"), 1.0, 1e-12);
  EXPECT_NEAR(d.at(p + "min_tension_N"), 0.5 * m * g, 1e-3 * 0.5 * m * g);
  EXPECT_NEAR(d.at(p + "min_factor"), 1.0 / 3.0, 1e-3 / 3.0);
  EXPECT_NEAR(d.at(p + "min_tension_time_s"), tMin, 2e-3);
  // The ceiling's clamp: its reaction moment is that of the rope force at
  // 0.1 m (at t = 0, 1.5 m g x 0.1 m) - the ceiling's own weight at 0.1 m.
  EXPECT_NEAR(d.at("design.clamp.top.static_root_moment_Nm"), 1.5 * m * g * 0.1 + 0.2 * g * 0.1, 1e-6);
}

TEST(DesignNumbers, RootMomentOfACantileverCarryingAPayload)
{
  const double Lb = 2.0, rhoA = 7850 * 6.944e-3;
  const std::string text = R"(
name: boom-payload
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: boom, length: 2.0, elements: 8, section: {E: 2.1e11, A: 6.944e-3, I: 6.395214e-5, rho: 7850}}
  - {name: payload, type: rigid, length: 0.2, origin: [1.9, -1.0], section: {rhoA: 5000}}
constraints:
  - {type: clamp, name: root, body: boom, at: start}
  - {type: angle_drive, body: payload, at: 0.1, angle: 0}
  - {type: elastic_rope, name: hoist, from: boom, from_at: 0.0, pulley: boom, pulley_at: end, to: payload, to_at: 0.1, EA: 2.0e7, pretension: 9810}
dynamic: {t_end: 0.01, dt: 1.0e-3, initial: static}
)";
  std::string report;
  const auto d = designNumbers(text, &report);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  PetscPrintf(PETSC_COMM_SELF, "%s", report.c_str());
  const double exact = m * g * Lb + rhoA * g * Lb * Lb / 2;
  const double M0 = d.at("design.clamp.root.static_root_moment_Nm");
  PetscPrintf(PETSC_COMM_SELF, "  root moment at t = 0: %.9g N m (exact %.9g, rel. %.1e)\n", M0, exact,
              std::abs(M0 / exact - 1));
  // Exact up to the deflection (the tip moves in by ~u'^2 L / 3 ~ 1e-6 m) and |r'| - 1 (~1e-6).
  EXPECT_NEAR(M0, exact, 1e-5 * exact);
  EXPECT_NEAR(d.at("design.elastic_rope.hoist.static_tension_N"), m * g, 1e-6 * m * g);
}
