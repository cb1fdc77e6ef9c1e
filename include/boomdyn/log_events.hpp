// -log_view events around the phases of a run.
#pragma once

#include <petscsys.h>

namespace boomdyn {

struct LogEvents {
  PetscLogEvent assembly = 0;  // residual and Jacobian of the saddle-point system
  PetscLogEvent step = 0;      // one accepted or rejected time step (Newton solve inside)
  PetscLogEvent start = 0;     // the filtered start of the first step after a (re)start (outside step)
  PetscLogEvent multipliers = 0; // the reported multipliers from the acceleration-level equations (outside step)
  PetscLogEvent statics = 0;   // static solve
  PetscLogEvent eigen = 0;     // eigen-analysis
  PetscLogEvent output = 0;    // sensors and HDF5 output
};

// Registered once per process (idempotent).
PetscErrorCode registerLogEvents();
const LogEvents &logEvents();

} // namespace boomdyn
