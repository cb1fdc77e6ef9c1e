// Rope tensions of a step, for /joints/rope_tension: the output channels of
// group "rope" (minus the multipliers of the rope rows, since the rope's
// constraint is C = L - l1 - l2; rope_type.cpp). The inextensible rope
// stands for an extension/retraction rope pair (docs/model.md §2.2): a
// positive value is the net pull of the extension rope, a negative one that
// of the retraction rope (the extension rope is slack then); such steps are
// counted for /summary/slack_rope_steps and the first one is reported.
#pragma once

#include "boomdyn/model.hpp"
#include "boomdyn/output_channel.hpp"

#include <petscsys.h>

#include <string>
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
  std::vector<OutputChannel> ropes_;
  PetscInt slackSteps_ = 0;
};

} // namespace boomdyn
