// Stick/slip of frictional joints: readings every step (/friction),
// transitions as events (/events and a console line each).
#include "boomdyn/monitors.hpp"
#include "boomdyn/simulation.hpp"

namespace boomdyn {

namespace {
PetscErrorCode printEvent(const char *format, const StickSlipEvent &e)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_SELF, format, e.t, e.joint.c_str(), e.toSlip ? "stick -> slip" : "slip -> stick",
                        e.direction > 0 ? "s decreasing" : "s increasing"));
  PetscFunctionReturn(0);
}
} // namespace

FrictionOutput::FrictionOutput(Simulation &sim, ResultsWriter &writer, bool quiet)
  : sim_(sim), writer_(writer), quiet_(quiet), stickSlip_(sim.model())
{
}

PetscErrorCode FrictionOutput::record(const RunState &s)
{
  PetscFunctionBeginUser;
  if (sim_.model().frictions().empty()) PetscFunctionReturn(0);
  PetscCall(sim_.sensors().readFriction(s.q, s.v, s.lambda, values_));
  const std::vector<StickSlipEvent> events = stickSlip_.update(s.t, values_, readings_);
  PetscCall(writer_.appendFriction(readings_));
  PetscCall(writer_.appendEvents(events));
  for (const StickSlipEvent &e : events) PetscCall(printEvent("event: t = %.4f s, joint '%s': %s (%s)\n", e));
  PetscFunctionReturn(0);
}

PetscErrorCode FrictionOutput::start(const RunState &s, bool restarted)
{
  PetscFunctionBeginUser;
  if (s.dynamic && !restarted) PetscCall(record(s));
  PetscFunctionReturn(0);
}

PetscErrorCode FrictionOutput::afterStep(const RunState &s, std::string *)
{
  PetscFunctionBeginUser;
  if (s.dynamic) PetscCall(record(s));
  PetscFunctionReturn(0);
}

PetscErrorCode FrictionOutput::finish(const RunState &, const RunOutcome &outcome)
{
  PetscFunctionBeginUser;
  if (!outcome.dynamic || sim_.model().frictions().empty() || quiet_) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(sim_.comm(), "stick/slip events: %zu\n", stickSlip_.events().size()));
  for (const StickSlipEvent &e : stickSlip_.events()) PetscCall(printEvent("  t = %8.4f s  %-12s %s (%s)\n", e));
  PetscFunctionReturn(0);
}

PetscErrorCode FrictionOutput::save(CheckpointWriter &out) const
{
  PetscFunctionBeginUser;
  out.addArray("stick_slip", stickSlip_.state());
  PetscFunctionReturn(0);
}

PetscErrorCode FrictionOutput::restore(const CheckpointReader &in)
{
  PetscFunctionBeginUser;
  stickSlip_.setState(in.array("stick_slip"));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
