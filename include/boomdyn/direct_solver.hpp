// The direct solver every linear solve of the saddle-point system uses by
// default: KSPPREONLY + LU, from KLU on one rank and MUMPS on several, with
// (for MUMPS) more integer workspace than
// MUMPS's default because the zero multiplier diagonal forces delayed pivots
// (INFOG(1) = -8 otherwise, seen on eigen pencils). Command-line options
// (-ksp_type, -pc_type, -mat_mumps_icntl_14, ...) still override everything.
#pragma once

#include <petscksp.h>

namespace boomdyn {

// Call before KSPSetFromOptions / SNESSetFromOptions / EPSSetFromOptions.
PetscErrorCode useDirectSolver(KSP ksp);

} // namespace boomdyn
