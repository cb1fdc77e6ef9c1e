// One run of a scene as a library object: the Simulation owns the model,
// the assembler, the solver of the scene's analysis (generalized-alpha for
// dynamic scenes, the load-stepping static solver for static and modal
// ones) and a list of monitors that write, check and report the run
// (monitor.hpp, monitors.hpp). The program (src/app) and the tests build
// the same object; only the monitors they attach differ.
//
//   Simulation sim(scene, PETSC_COMM_WORLD, options);
//   PetscCall(sim.setUp());
//   sim.addMonitor(std::make_unique<ResultsOutput>(sim, ...));
//   PetscCall(sim.run());
//   sim.outcome().status  // "completed", "interrupted" or "failed: ..."
//
// The data path of one run is described in docs/architecture.md.
#pragma once

#include "boomdyn/assembler.hpp"
#include "boomdyn/generalized_alpha.hpp"
#include "boomdyn/model.hpp"
#include "boomdyn/monitor.hpp"
#include "boomdyn/petsc_handle.hpp"
#include "boomdyn/sensors.hpp"
#include "boomdyn/static_solver.hpp"
#include "boomdyn/time_stepper.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace boomdyn {

class EnergyCheck;

struct SimulationOptions {
  double energyTolerance = 0.05;  // energy-balance check of dynamic runs (0: computed, never fails)
  double adaptiveTolerance = 0;   // local position error per step (0: fixed steps)
  bool kinkRestart = true;        // land on drives' velocity kinks and restart there (docs/model.md §4.8)
  bool accelerationPredictor = true; // Newton's start from q + h v + h^2/2 a when that predicted better (§4.2)
  bool filteredStart = true; // the first step's a without the modes it cannot resolve (§4.3)
  bool consistentMultipliers = false; // report multipliers from the acceleration-level equations (§4.8)
  std::string restartPath;        // continue a dynamic run from this checkpoint
  bool modal = true;              // run the scene's modal analysis (modal: block)
  bool quiet = false;             // no status lines (warnings and events are printed anyway)
  bool warnings = true;           // print the mesh conditioning warnings
  bool trackingFullSolve = false; // tracking: full eigen-solve at every analysis (no refinement)
};

class Simulation {
public:
  // The Simulation keeps its own copy of the scene (the Model's), so the
  // caller's Scene may be a temporary or change afterwards. Throws
  // ModelError for scenes that are no mechanism (Model's constructor).
  Simulation(const Scene &scene, MPI_Comm comm, const SimulationOptions &options = {});
  Simulation(const Simulation &) = delete;
  Simulation &operator=(const Simulation &) = delete;

  // Collective: distributes the model, creates the initial state and the solver.
  PetscErrorCode setUp();
  void addMonitor(std::unique_ptr<Monitor> monitor) { monitors_.push_back(std::move(monitor)); }
  // Collective: the whole analysis. stop, if given, is asked after every
  // time step, load increment and iteration of an eigen-solve, and must answer
  // alike on every rank (SIGINT/SIGTERM/SIGHUP/SIGPIPE). A run
  // that fails or is stopped returns 0 and says so in outcome().
  PetscErrorCode run(const std::function<bool()> &stop = {});
  // Collective: everything needed to continue this run bitwise (one rank):
  // integrator, step controller, every monitor's state.
  PetscErrorCode writeCheckpoint(const std::string &path) const;

  const Scene &scene() const { return model_.scene(); }
  const Model &model() const { return model_; }
  Assembler &assembler() { return assembler_; }
  SensorProbe &sensors() { return sensors_; }
  MPI_Comm comm() const { return comm_; }
  const SimulationOptions &options() const { return options_; }
  // The stop request of the run() in progress (empty outside run()), for
  // monitors whose work can be long (the tracking's eigen-solves).
  const std::function<bool()> &stopRequest() const { return stop_; }
  // The initial state (layout of x); a vector of that layout.
  Vec initialState() const { return x_; }
  // Dynamic scenes: the integrator (after setUp); nullptr otherwise.
  GeneralizedAlpha *integrator() { return integrator_.get(); }
  const RunOutcome &outcome() const { return outcome_; }
  const RunSummary &summary() const { return summary_; }
  const std::vector<std::string> &conditioningWarnings() const { return conditioning_; }

private:
  PetscErrorCode runDynamic(const std::function<bool()> &stop);
  PetscErrorCode runStatic(const std::function<bool()> &stop);
  PetscErrorCode restore(RunState *state);
  PetscErrorCode staticInitialState(); // dynamic.initial: static
  PetscErrorCode dynamicState(RunState *state);
  PetscErrorCode afterStep(const RunState &state, std::string *failure);
  PetscErrorCode finish(const RunState &state);
  // The scene's modes at (t, q, lambda); stop is asked during the eigen-solves
  // (*interrupted: they were stopped, no modes reported).
  PetscErrorCode modalAnalysis(double t, Vec q, Vec lambda, const std::function<bool()> &stop, bool *interrupted);
  PetscErrorCode failureDetails(const std::string &failure, std::string *status); // collective

  MPI_Comm comm_;
  SimulationOptions options_;
  Model model_;
  Assembler assembler_;
  SensorProbe sensors_;
  PetscHandle<Vec> x_, zero_, v0_; // v0_: the initial velocities (zero but for spatial bodies given one)
  std::unique_ptr<GeneralizedAlpha> integrator_;
  std::unique_ptr<StaticSolver> statics_;
  std::vector<std::unique_ptr<Monitor>> monitors_;
  const EnergyCheck *energy_ = nullptr; // the first monitor of dynamic runs
  Assembler::DampingForces dampingForces_; // at the state of the last dynamicState() (RunState::dampingForces)
  std::vector<std::string> conditioning_;
  StepperState stepper_;
  RunSummary summary_;
  RunOutcome outcome_;
  PetscLogDouble started_ = 0;
  std::function<bool()> stop_; // run()'s stop
};

} // namespace boomdyn
