// SIGINT / SIGTERM / SIGHUP / SIGPIPE: the handler only sets a flag; the time loop asks for it
// after every step (all ranks agree through an MPI reduction), writes a
// checkpoint and closes the results file as "interrupted".
#pragma once

#include <mpi.h>

namespace boomdyn {

void installInterruptHandlers();
// Collective: true on every rank when any rank received one of these signals.
bool interruptRequested(MPI_Comm comm);
int interruptSignal();

} // namespace boomdyn
