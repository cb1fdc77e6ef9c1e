// Rope tensions of a step, for /joints/rope_tension: minus the multipliers
// of the rope rows (the rope's constraint is C = L - l1 - l2). A negative
// tension means the rope would have to push: it is slack there; such steps
// are counted for /summary/slack_rope_steps and the first one is reported.
// Kept apart so that the rope is found in one place (to be replaced by the
// Model's list of output channels).
#pragma once

#include "boomdyn/model.hpp"

#include <petscsys.h>

#include <string>
#include <utility>
#include <vector>

namespace boomdyn {

class RopeTensions {
public:
  explicit RopeTensions(const Model &model);
  // Collective. multipliers: every unscaled multiplier (rank 0 data; empty
  // elsewhere). Fills tensions (one per rope, rank 0).
  PetscErrorCode update(MPI_Comm comm, double t, const std::vector<double> &multipliers, std::vector<double> &tensions);
  PetscInt slackSteps() const { return slackSteps_; }
  void setSlackSteps(PetscInt n) { slackSteps_ = n; }

private:
  std::vector<std::pair<std::string, PetscInt>> rows_; // rope name, its multiplier row counted from 0
  PetscInt slackSteps_ = 0;
};

} // namespace boomdyn
