#include "signals.hpp"

#include <csignal>

namespace boomdyn {

namespace {
volatile std::sig_atomic_t received = 0;
extern "C" void onSignal(int signal) { received = signal; }
} // namespace

void installInterruptHandlers()
{
  // Installed after PetscInitialize, replacing PETSc's handlers for these two
  // signals (PETSc's would abort without closing the results file).
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
}

bool interruptRequested(MPI_Comm comm)
{
  int local = received != 0, any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
  return any != 0;
}

int interruptSignal() { return static_cast<int>(received); }

} // namespace boomdyn
