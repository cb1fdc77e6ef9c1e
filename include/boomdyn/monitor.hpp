// What watches a run: the Simulation calls every monitor at the start, after
// every accepted time step (or converged load increment) and at the end, in
// the order they were added. A monitor writes results, checks the run or
// reports progress; it keeps its own state and saves and restores exactly
// that state in checkpoints, so a restarted run continues every monitor
// where it was.
#pragma once

#include "boomdyn/checkpoint.hpp"
#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/time_stepper.hpp"
#include "boomdyn/work_item.hpp"

#include <petscvec.h>

#include <string>

namespace boomdyn {

// The state a monitor sees. Vectors have the layout of x (coordinates, then
// unscaled multipliers in lambda's last entries); they belong to the solver
// and are valid only during the call.
struct RunState {
  bool dynamic = true;
  double t = 0;            // time; for a static load increment the load factor
  double h = 0;            // step that reached t (0 at the start and in statics)
  PetscInt step = 0;       // accepted steps (load increments) so far
  PetscInt iterations = 0; // Newton iterations of this step
  PetscInt rejected = 0;   // rejected attempts so far (whole run)
  bool last = false;       // this step reaches the end time
  Vec q = nullptr, v = nullptr, lambda = nullptr;
  EnergyParts energy;      // at this state
  double violation = 0;    // largest constraint violation at this state
  // Damped models in dynamic runs: the damping forces at this state, from
  // the pass that computed the energy (null: not computed, EnergyCheck
  // evaluates them itself).
  const Assembler::DampingForces *dampingForces = nullptr;
  const StepperState *stepper = nullptr; // step controller after this step (dynamic runs)
};

// How a run ended.
struct RunOutcome {
  std::string status = "completed"; // or "interrupted", or "failed: <reason>"
  bool dynamic = true;
  PetscInt steps = 0, rejected = 0, newtonIterations = 0;
  double maxViolation = 0, wallTime = 0;
  double endTime = 0; // time (statics: the scene's statics.time) of the final state
  // Energy balance of a dynamic run (EnergyCheck): W_in, excess (E - E0 - W_in + W_diss), involved [J].
  bool hasEnergyBalance = false;
  double inputWork = 0, energyExcess = 0, energyInvolved = 0;
  double dissipatedWork = 0; // W_diss of the damping forces [J]
  // A run that -ts_max_steps ended before t_end did what was asked: it
  // counts as completed (exit 0), and /summary/status says why it stopped.
  static constexpr const char *kStepLimit = "completed: stopped by -ts_max_steps before t_end";
  bool completed() const { return status == "completed" || status == kStepLimit; }
  bool interrupted() const { return status == "interrupted"; }
};

class Monitor {
public:
  virtual ~Monitor() = default;
  // Once, before restore() and start(): open files, create solvers.
  virtual PetscErrorCode setUp() { return 0; }
  // The initial (or, restarted, the restored) state.
  virtual PetscErrorCode start(const RunState &, bool /*restarted*/) { return 0; }
  // After every accepted step. Setting *failure ends the run as failed with
  // that reason (the other monitors still see this step).
  virtual PetscErrorCode afterStep(const RunState &, std::string * /*failure*/) { return 0; }
  // An eigen-analysis of the run (the scene's modal block).
  virtual PetscErrorCode modes(double /*t*/, const ModalResult &) { return 0; }
  // The end: state holds the final state (the last accepted one when the run failed).
  virtual PetscErrorCode finish(const RunState &, const RunOutcome &) { return 0; }
  // Checkpoints: this monitor's own state, under keys of its own.
  virtual PetscErrorCode save(CheckpointWriter &) const { return 0; }
  virtual PetscErrorCode restore(const CheckpointReader &) { return 0; }
};

} // namespace boomdyn
