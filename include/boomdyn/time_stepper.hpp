// The time loop around GeneralizedAlpha, run by PETSc's TSSolve with the TS
// type boomalpha (ts_boomalpha.hpp): steps of the scene's dt up to t_end; a
// step whose Newton iteration fails is retried with half the step (down to
// dt_min, then the run stops with a message), and the step grows back after
// a run of successes. Never accepts a failed step. The usual -ts_ options
// apply (no prefix): -ts_monitor, -ts_view, -ts_max_steps,
// -ts_exact_final_time, -ts_adapt_type, -ts_max_snes_failures,
// -ts_max_reject, ...; those that cannot apply are rejected with a message.
#pragma once

#include "boomdyn/generalized_alpha.hpp"
#include "boomdyn/scene.hpp"
#include "boomdyn/ts_boomalpha.hpp"

#include <functional>
#include <string>

namespace boomdyn {

struct StepInfo {
  PetscInt step = 0;         // accepted steps so far
  double t = 0, h = 0;       // time reached and the step that reached it
  PetscInt iterations = 0;   // Newton iterations of this step
  PetscInt rejected = 0;     // rejected attempts so far (whole run)
  const StepperState *stepper = nullptr; // the controller after this step (for checkpoints)
  // Set by the step callback to end the run as failed, with this reason
  // (a check on the accepted step failed, e.g. the energy balance).
  mutable std::string failure;
};

struct RunSummary {
  bool completed = false;
  bool interrupted = false;  // stopped on request (stop() returned true)
  bool stepLimit = false;    // completed = true, but stopped by -ts_max_steps before t_end
  std::string failure;       // reason when not completed
  PetscInt steps = 0, rejected = 0, newtonIterations = 0;
};

// state: in/out (a fresh StepperState starts at the scene's dt; a restored
// one continues). stop, if given, is asked after every accepted step and
// before every retry of a rejected one, and must give the same answer on
// every rank.
PetscErrorCode integrate(GeneralizedAlpha &integrator, const DynamicSpec &spec,
                         const std::function<PetscErrorCode(const StepInfo &)> &onStep, RunSummary *summary,
                         StepperState *state = nullptr, const std::function<bool()> &stop = {});

// Checkpoints of the step controller, next to the integrator's own state
// (GeneralizedAlpha::save): keys stepper.h, stepper.successes, stepper.steps,
// stepper.rejected, stepper.newton. Pass a CheckpointWriter/-Reader (io).
PetscErrorCode saveStepper(StateWriter &out, const StepperState &state);
PetscErrorCode restoreStepper(const StateReader &in, StepperState *state);

} // namespace boomdyn
