#include "signals.hpp"

#include <csignal>

namespace boomdyn {

namespace {
volatile std::sig_atomic_t received = 0;
// The first signal is the one reported (SIGPIPE repeats on every later write).
extern "C" void onSignal(int signal)
{
  if (!received) received = signal;
}
} // namespace

void installInterruptHandlers()
{
  // Installed after PetscInitialize, replacing PETSc's handlers for these
  // signals (PETSc's would abort without closing the results file). A closed
  // terminal (SIGHUP) and a closed pipe on the output (SIGPIPE: boomdyn ... |
  // head -1) end the run like SIGTERM: checkpoint, results file closed as
  // "interrupted". After SIGPIPE, writes to the pipe fail with EPIPE and are lost.
  for (int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) std::signal(s, onSignal);
}

bool interruptRequested(MPI_Comm comm)
{
  int local = received != 0, any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
  return any != 0;
}

int interruptSignal() { return static_cast<int>(received); }

} // namespace boomdyn
