// Checkpoints of a dynamic run: every interval of simulated time (not at
// the last step: the run is complete there) and when the run is interrupted.
#include "boomdyn/monitors.hpp"
#include "boomdyn/schedule.hpp"
#include "boomdyn/simulation.hpp"

namespace boomdyn {

PetscErrorCode Checkpointer::write(double t)
{
  PetscFunctionBeginUser;
  PetscCall(sim_.writeCheckpoint(path_));
  if (!quiet_) PetscCall(PetscPrintf(sim_.comm(), "checkpoint at t = %g s -> %s\n", t, path_.c_str()));
  PetscFunctionReturn(0);
}

PetscErrorCode Checkpointer::afterStep(const RunState &s, std::string *)
{
  PetscFunctionBeginUser;
  if (!s.dynamic || interval_ <= 0 || s.t < next_ - 1e-9 * s.h || s.last) PetscFunctionReturn(0);
  // The schedule moves on first: the checkpoint holds the next time.
  next_ = nextScheduledTime(next_, interval_, s.t, 1e-9 * s.h);
  PetscCall(write(s.t));
  PetscFunctionReturn(0);
}

PetscErrorCode Checkpointer::finish(const RunState &, const RunOutcome &outcome)
{
  PetscFunctionBeginUser;
  if (outcome.dynamic && outcome.interrupted()) PetscCall(write(outcome.endTime));
  PetscFunctionReturn(0);
}

PetscErrorCode Checkpointer::save(CheckpointWriter &out) const
{
  PetscFunctionBeginUser;
  out.addScalar("next_checkpoint", next_);
  PetscFunctionReturn(0);
}

PetscErrorCode Checkpointer::restore(const CheckpointReader &in)
{
  PetscFunctionBeginUser;
  next_ = in.scalar("next_checkpoint");
  PetscFunctionReturn(0);
}

} // namespace boomdyn
