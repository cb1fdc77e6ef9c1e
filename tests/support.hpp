// Runs for verification and regression tests: a scene's static or dynamic
// analysis through the same Simulation object as the program
// (include/boomdyn/simulation.hpp), without output files; a recording
// monitor returns what the tests compare (sensor readings, energy,
// constraint violation per step).
#pragma once

#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/generalized_alpha.hpp"
#include "boomdyn/monitor.hpp"
#include "boomdyn/monitors.hpp"
#include "boomdyn/scene_reader.hpp"
#include "boomdyn/simulation.hpp"
#include "boomdyn/static_solver.hpp"
#include "boomdyn/time_stepper.hpp"

#include <slepcsys.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace boomdyn::testing {

// A failed PETSc call must end the test. ASSERT_* inside this helper would
// only return from the helper and let the caller go on with a half-built
// object (and check() is also called from functions that return values,
// where ASSERT_* cannot be used), so it throws instead: GoogleTest reports an
// exception that leaves a test body as a failure of that test and runs the
// next one. Not for use inside callbacks that PETSc calls (use PetscCall there).
struct PetscCallFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline void check(PetscErrorCode ierr)
{
  if (ierr != 0) throw PetscCallFailed("PETSc call failed with error code " + std::to_string(ierr));
}

struct StaticOutcome {
  std::vector<SensorReading> sensors; // on rank 0
  bool converged = false;
  double violation = 0;
};

// A simulation without output files, modal analysis, energy check or
// messages: what the tests observe comes from their own monitor.
inline SimulationOptions testOptions(double errorTolerance = 0)
{
  SimulationOptions o;
  o.energyTolerance = 0;
  o.adaptiveTolerance = errorTolerance;
  o.modal = false;
  o.quiet = true;
  o.warnings = false;
  return o;
}

// Sensors and constraint violation at the end of a static run.
class StaticRecorder : public Monitor {
public:
  StaticRecorder(Simulation &sim, StaticOutcome &out) : sim_(sim), out_(out) {}
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override
  {
    AssemblyContext ctx;
    PetscReal violation;
    PetscFunctionBeginUser;
    out_.converged = outcome.completed();
    PetscCall(sim_.sensors().read(s.q, s.v, out_.sensors));
    PetscCall(sim_.assembler().setOffsets(nullptr, nullptr, nullptr));
    PetscCall(sim_.assembler().diagnostics(ctx, s.q, nullptr, &violation));
    out_.violation = violation;
    PetscFunctionReturn(0);
  }

private:
  Simulation &sim_;
  StaticOutcome &out_;
};

inline StaticOutcome runStatic(const Scene &scene, MPI_Comm comm = PETSC_COMM_WORLD)
{
  StaticOutcome out;
  Simulation sim(scene, comm, testOptions());
  check(sim.setUp());
  sim.addMonitor(std::make_unique<StaticRecorder>(sim, out));
  check(sim.run());
  return out;
}

struct DynamicHistory {
  std::vector<double> time, violation, energy; // energy: kinetic + strain + potential
  std::vector<double> inputPower;              // of time-varying loads and drives, per step
  std::vector<EnergyParts> energyParts;
  std::vector<std::vector<SensorReading>> sensors;
  std::vector<std::vector<double>> multipliers; // unscaled, every row, per step (all ranks)
  std::vector<std::vector<double>> slacks;      // slack coordinate of every sliding joint, per step
  RunSummary summary;
  RunOutcome outcome;             // with the energy balance of the EnergyCheck
  std::vector<double> finalState; // q and v of the last step, gathered on every rank
  NewtonStatistics newton;        // of the time steps' solver
  int patternVersion = 0;         // pattern rebuilds (sliding joints changing elements)
  std::vector<std::vector<double>> outputs; // every output channel's value, per step (rank 0; empty elsewhere)
  std::vector<TypeEvent> events;            // of the types' event sources (rank 0)
};

// All entries of a distributed vector on every rank.
inline std::vector<double> gatherAll(Vec v)
{
  Vec all;
  VecScatter sc;
  const PetscScalar *a;
  PetscInt n;
  VecScatterCreateToAll(v, &sc, &all);
  VecScatterBegin(sc, v, all, INSERT_VALUES, SCATTER_FORWARD);
  VecScatterEnd(sc, v, all, INSERT_VALUES, SCATTER_FORWARD);
  VecGetSize(all, &n);
  VecGetArrayRead(all, &a);
  std::vector<double> out(a, a + n);
  VecRestoreArrayRead(all, &a);
  VecScatterDestroy(&sc);
  VecDestroy(&all);
  return out;
}

// Every accepted step of a dynamic run (and the start), into a DynamicHistory.
class HistoryRecorder : public Monitor {
public:
  HistoryRecorder(Simulation &sim, DynamicHistory &h) : sim_(sim), h_(h) {}
  PetscErrorCode start(const RunState &s, bool) override { return record(s); }
  PetscErrorCode afterStep(const RunState &s, std::string *) override { return record(s); }

private:
  PetscErrorCode record(const RunState &s)
  {
    std::vector<SensorReading> r;
    PetscFunctionBeginUser;
    PetscCall(sim_.sensors().read(s.q, s.v, r));
    h_.time.push_back(s.t);
    h_.violation.push_back(s.violation);
    h_.energy.push_back(s.energy.kinetic + s.energy.strain + s.energy.potential);
    h_.inputPower.push_back(s.energy.inputPower);
    h_.energyParts.push_back(s.energy);
    h_.sensors.push_back(r);
    const Model &model = sim_.model();
    const std::vector<double> lam = gatherAll(s.lambda), q = gatherAll(s.q);
    h_.multipliers.emplace_back(lam.begin() + model.numCoordinates(), lam.end());
    std::vector<double> slack;
    for (const auto &j : model.slidingJoints()) slack.push_back(q[j->slackIndex()]);
    h_.slacks.push_back(slack);
    std::vector<double> multipliers, slacks, outputs;
    PetscCall(sim_.sensors().readJoints(s.q, s.lambda, slacks, multipliers));
    PetscCall(sim_.sensors().readOutputs(s.t, s.q, s.v, multipliers, outputs));
    h_.outputs.push_back(outputs);
    PetscFunctionReturn(0);
  }

  Simulation &sim_;
  DynamicHistory &h_;
};

// A dynamic run with the given options (testOptions() and changes to it).
inline DynamicHistory runDynamicWith(const Scene &scene, MPI_Comm comm, const SimulationOptions &options)
{
  DynamicHistory h;
  Simulation sim(scene, comm, options);
  check(sim.setUp());
  sim.addMonitor(std::make_unique<HistoryRecorder>(sim, h));
  const TypeEventsOutput *events = nullptr;
  if (!sim.model().eventSources().empty()) {
    auto monitor = std::make_unique<TypeEventsOutput>(sim, nullptr, true);
    events = monitor.get();
    sim.addMonitor(std::move(monitor));
  }
  check(sim.run());
  if (events) h.events = events->events();
  h.summary = sim.summary();
  h.outcome = sim.outcome();
  // Final q and v on every rank, for comparisons across rank counts.
  GeneralizedAlpha &integrator = *sim.integrator();
  for (Vec v : {integrator.positions(), integrator.velocities()}) {
    const std::vector<double> all = gatherAll(v);
    h.finalState.insert(h.finalState.end(), all.begin(), all.begin() + sim.model().numCoordinates());
  }
  h.newton = integrator.newton().statistics();
  h.patternVersion = sim.assembler().patternVersion();
  return h;
}

inline DynamicHistory runDynamic(const Scene &scene, MPI_Comm comm = PETSC_COMM_WORLD, double errorTolerance = 0,
                                 bool kinkRestart = true, bool accelerationPredictor = true)
{
  SimulationOptions options = testOptions(errorTolerance);
  options.kinkRestart = kinkRestart;                     // -boom_kink_restart
  options.accelerationPredictor = accelerationPredictor; // -boom_acceleration_predictor
  return runDynamicWith(scene, comm, options);
}

// runDynamic with one boomdyn option set (e.g. "-boom_schur_dd", "1") for
// this run only.
inline DynamicHistory runDynamicWithOption(const Scene &scene, MPI_Comm comm, const char *name, const char *value,
                                           bool kinkRestart = true, bool accelerationPredictor = true)
{
  PetscOptionsSetValue(nullptr, name, value);
  DynamicHistory h = runDynamic(scene, comm, 0, kinkRestart, accelerationPredictor);
  PetscOptionsClearValue(nullptr, name);
  return h;
}

// The paper extraction scene (inputs/paper_extraction_single_calibration.yaml) shortened to
// `seconds` of smooth extraction at 1 m/s from t = 0, so that the contact
// points cross elements within a short run.
inline Scene shortenedExtraction(double seconds)
{
  Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/paper_extraction_single_calibration.yaml");
  for (auto &c : scene.constraints)
    if (c.type == "extraction_drive")
      c.set("displacement", TimeFunction::smoothStep(0.0, seconds, 0.0, seconds));
  scene.dynamic.t_end = seconds;
  return scene;
}

// max |a - b| / max |a| over two states of the same layout. States of
// different sizes, empty states and states with a NaN cannot be compared:
// that is a failure of the test (recorded here), and the result is +inf, so
// that the caller's EXPECT_LT(d, tol) fails as well.
inline double maxRelativeDifference(const std::vector<double> &a, const std::vector<double> &b)
{
  const double never = std::numeric_limits<double>::infinity();
  if (a.size() != b.size()) {
    ADD_FAILURE() << "maxRelativeDifference: states of different sizes (" << a.size() << " and " << b.size() << ")";
    return never;
  }
  if (a.empty()) {
    ADD_FAILURE() << "maxRelativeDifference: empty states (nothing was recorded)";
    return never;
  }
  double diff = 0, norm = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i]) || std::isnan(b[i])) {
      ADD_FAILURE() << "maxRelativeDifference: NaN at index " << i;
      return never;
    }
    diff = std::max(diff, std::abs(a[i] - b[i]));
    norm = std::max(norm, std::abs(a[i]));
  }
  return norm > 0 ? diff / norm : diff;
}

// A scene's model integrated by hand (GeneralizedAlpha and integrate(), not
// Simulation), at its initial state with consistent accelerations and SLEPc
// initialized: for tests that analyze the states a run passes through
// (frequency tracking) or run two analyses side by side on them.
struct HandIntegration {
  Model model;
  Assembler assembler;
  PetscHandle<Vec> x, zero;
  std::unique_ptr<GeneralizedAlpha> integrator;

  explicit HandIntegration(const Scene &scene, MPI_Comm comm = PETSC_COMM_WORLD) : model(scene), assembler(model)
  {
    check(assembler.setUp(comm));
    check(assembler.createVector(x.address()));
    check(assembler.createVector(zero.address()));
    check(assembler.initialState(x));
    integrator = std::make_unique<GeneralizedAlpha>(assembler, scene.dynamic.rho_inf);
    check(integrator->setUp(scene.dynamic.max_newton));
    check(integrator->initialize(0.0, x, zero));
    check(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  }
};

// A scene's model at its static equilibrium under its loads at t = 0 (the
// `initial: static` start, `analysis: modal`) on `comm`; expects the
// statics to converge.
struct StaticEquilibrium {
  Scene scene;
  Model model;
  Assembler assembler;
  PetscHandle<Vec> x;
  std::unique_ptr<StaticSolver> statics;
  explicit StaticEquilibrium(Scene s, MPI_Comm comm = PETSC_COMM_WORLD)
    : scene(std::move(s)), model(scene), assembler(model)
  {
    check(assembler.setUp(comm));
    check(assembler.createVector(x.address()));
    check(assembler.initialState(x));
    statics = std::make_unique<StaticSolver>(assembler);
    check(statics->setUp());
    PetscBool converged;
    check(statics->solve(0.0, scene.statics.load_steps, x, nullptr, &converged));
    EXPECT_TRUE(converged);
    check(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  }
  Vec multipliers() const { return statics->multipliers(); }
};

// The modes of a scene at its static equilibrium (StaticEquilibrium).
// With `state`, the equilibrium too (gathered on rank 0).
inline ModalResult modesAtStaticEquilibrium(const Scene &scene, int count, MPI_Comm comm = PETSC_COMM_WORLD,
                                            std::vector<double> *state = nullptr)
{
  StaticEquilibrium equilibrium(scene, comm);
  ModalResult modes;
  check(solveModes(equilibrium.assembler, 0.0, equilibrium.x, equilibrium.multipliers(), count, &modes));
  if (state) check(gatherShape(equilibrium.assembler, equilibrium.x, state));
  return modes;
}

} // namespace boomdyn::testing
