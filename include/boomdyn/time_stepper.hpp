// The time loop around GeneralizedAlpha: steps of the scene's dt up to
// t_end; a step whose Newton iteration fails is retried with half the step
// (down to dt_min, then the run stops with a message), and the step grows
// back after a run of successes. Never accepts a failed step.
#pragma once

#include "boomdyn/generalized_alpha.hpp"
#include "boomdyn/scene.hpp"

#include <functional>
#include <string>

namespace boomdyn {

// The step controller's state, carried across steps and through checkpoints.
struct StepperState {
  double h = 0;               // step to try next (0: the scene's dt)
  int successesSinceCut = 0;
  PetscInt steps = 0, rejected = 0, newtonIterations = 0;
};

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
  std::string failure;       // reason when not completed
  PetscInt steps = 0, rejected = 0, newtonIterations = 0;
};

// state: in/out (a fresh StepperState starts at the scene's dt; a restored
// one continues). stop, if given, is asked after every accepted step and must
// give the same answer on every rank.
PetscErrorCode integrate(GeneralizedAlpha &integrator, const DynamicSpec &spec,
                         const std::function<PetscErrorCode(const StepInfo &)> &onStep, RunSummary *summary,
                         StepperState *state = nullptr, const std::function<bool()> &stop = {});

// Checkpoints of the step controller (keys stepper.h, stepper.successes,
// stepper.steps, stepper.rejected, stepper.newton). restoreStepper throws
// std::runtime_error naming the file when a key is missing.
PetscErrorCode saveStepper(CheckpointWriter &out, const StepperState &state);
PetscErrorCode restoreStepper(const CheckpointReader &in, StepperState *state);

} // namespace boomdyn
