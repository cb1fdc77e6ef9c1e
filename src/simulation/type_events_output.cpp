// Events of the registered types (type_event.hpp): every event source looks
// at its watched coordinates after each converged dynamic step; what it
// reports goes to /type_events and to one console line per event, like the
// stick/slip events of friction_output.cpp.
#include "boomdyn/monitors.hpp"
#include "boomdyn/simulation.hpp"

namespace boomdyn {

namespace {
PetscErrorCode printEvent(const char *format, const TypeEvent &e)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_SELF, format, e.t, e.component.c_str(), e.kind.c_str(), e.direction));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode TypeEventsOutput::detect(const RunState &s, bool first)
{
  PetscMPIInt rank;
  std::vector<TypeEvent> events;
  PetscFunctionBeginUser;
  const auto &sources = sim_.model().eventSources();
  if (sources.empty()) PetscFunctionReturn(0);
  PetscCall(sim_.sensors().readEventCoordinates(s.q, s.v, qs_, vs_));
  PetscCallMPI(MPI_Comm_rank(sim_.comm(), &rank));
  if (rank == 0) { // the gathered values live on rank 0; the sources keep their state there
    std::size_t offset = 0;
    for (const EventSource &src : sources) {
      src.detect(s.t, s.h, qs_.data() + offset, vs_.data() + offset, first, events);
      offset += src.watched.size();
    }
  }
  if (writer_) PetscCall(writer_->appendTypeEvents(events));
  for (const TypeEvent &e : events) {
    if (!quiet_) PetscCall(printEvent("event: t = %.6f s, '%s': %s (direction %d)\n", e));
    events_.push_back(e);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TypeEventsOutput::start(const RunState &s, bool)
{
  PetscFunctionBeginUser;
  if (s.dynamic) PetscCall(detect(s, true));
  PetscFunctionReturn(0);
}

PetscErrorCode TypeEventsOutput::afterStep(const RunState &s, std::string *)
{
  PetscFunctionBeginUser;
  if (s.dynamic) PetscCall(detect(s, false));
  PetscFunctionReturn(0);
}

PetscErrorCode TypeEventsOutput::finish(const RunState &, const RunOutcome &outcome)
{
  PetscFunctionBeginUser;
  if (!outcome.dynamic || sim_.model().eventSources().empty() || quiet_) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(sim_.comm(), "type events: %zu\n", events_.size()));
  for (const TypeEvent &e : events_) PetscCall(printEvent("  t = %10.6f s  %-12s %s (direction %d)\n", e));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
