// The direct solver every linear solve of the saddle-point system uses by
// default: KSPPREONLY + LU, from KLU on one rank and MUMPS on several (the
// time steps of a dynamic run replace it by the interface Schur complement
// on several ranks: NewtonSolver::setUp, -boom_schur_dd), with
// (for MUMPS) more integer workspace than
// MUMPS's default because the zero multiplier diagonal forces delayed pivots
// (INFOG(1) = -8 otherwise, seen on eigen pencils). Command-line options
// (-ksp_type, -pc_type, -mat_mumps_icntl_14, ...) still override everything.
#pragma once

#include <petscksp.h>

namespace boomdyn {

// Call before KSPSetFromOptions / SNESSetFromOptions / EPSSetFromOptions.
PetscErrorCode useDirectSolver(KSP ksp);

// The shift-and-invert solver of the eigen-analyses (full solves, tracking
// refinements): useDirectSolver()'s, except on several ranks with
// -boom_schur_dd given explicitly, where it is the interface Schur
// complement as for the time steps (schur_complement_solver.hpp; not by
// default: a pencil with a small shift can leave a rank's free piece almost
// singular). Besides being faster there, that
// makes two runs agree bitwise: MUMPS's distributed factorization adds the
// contributions of the ranks in the order its messages arrive, so two runs
// of the same tracking differed in the last bits (up to 3e-11 relative in
// the tracked frequencies on the paper scene).
PetscErrorCode useAnalysisDirectSolver(KSP ksp);

} // namespace boomdyn
