// Work a type does after every converged step, on values of the solution
// that every rank receives (e.g. a sliding joint moves its contact point to
// the track element that now holds it). SliderTracker runs the hooks the
// types registered (Model::postStepHooks()).
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
  // One number of state that checkpoints save and restore.
  std::function<double()> location;
  std::function<void(double)> setLocation;
};

} // namespace boomdyn
