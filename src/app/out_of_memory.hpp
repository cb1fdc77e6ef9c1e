// Out of memory, reported as one line with the sizes involved: the request
// that failed (when known), the address-space limit of the process
// (ulimit -v) and the machine's memory. A std::bad_alloc from boomdyn's own
// code (a mesh too large for the address space: the Jacobian pattern) and
// PETSc's PETSC_ERR_MEM both end here instead of in std::terminate or a
// PETSc-internal message.
#pragma once

#include <string>

namespace boomdyn {

// Bytes of the last operator new request that failed (0: none seen).
double lastFailedAllocation();
// The error text: "out of memory: ..." with requestedBytes (<= 0: unknown).
std::string outOfMemoryMessage(double requestedBytes);
// The bytes PETSc's message asked for ("Memory requested 1e+09"), or 0.
double petscRequestedBytes(const std::string &petscMessage);

} // namespace boomdyn
