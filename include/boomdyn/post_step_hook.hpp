// Work a type does after every converged step, on values of the solution
// that every rank receives (e.g. a sliding joint moves its contact point to
// the track element that now holds it; a spatial beam rebases its node
// references). SliderTracker runs the hooks the types registered
// (Model::postStepHooks()).
#pragma once

#include <petscsys.h>

#include <functional>
#include <string>
#include <vector>

namespace boomdyn {

struct PostStepHook {
  std::string name;
  std::vector<PetscInt> watched; // global coordinates handed to afterStep, in this order
  // After a converged step at time t: *changed when the assembly pattern
  // must be rebuilt (the step is redone); *stop non-empty when the run
  // cannot go on (the message says why). Same decisions on every rank.
  std::function<PetscErrorCode(const double *values, double t, bool *changed, std::string *stop)> afterStep;
  // One number of state that checkpoints save and restore (optional).
  std::function<double()> location;
  std::function<void(double)> setLocation;
  // Or several (optional; a spatial beam's node references): the count
  // never changes during a run.
  std::function<std::vector<double>()> state;
  std::function<void(const double *)> setState;
  // A change of chart that keeps the state and the assembly pattern (a
  // spatial beam rebasing its node references): runs once a step is
  // accepted (a rejected step must restart from the old state in the old
  // chart) and after every converged load step of a static solve, instead
  // of after each Newton solve.
  bool changesChartOnly = false;
};

} // namespace boomdyn
