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

// Every rank factors the whole matrix with KLU (PCREDUNDANT: the matrix is
// gathered onto each rank, the solution scattered back). On several ranks
// this replaces MUMPS for the eigen-analyses and the statics: on these
// banded saddle-point systems MUMPS's distributed factorization was slower
// than one rank's KLU (paper scene, 2 ranks: the tracking's solves 4.6 s
// against 1.2-1.5 s, docs/performance-history.md "Tenth round"), and it adds
// the ranks' contributions in the order its messages arrive, so that two runs
// differed in the last bits. The redundant factorization is the same
// sequential one on every rank: two runs agree bitwise. Its cost is that of
// one rank's factorization plus gathering the matrix, and every rank holds
// the whole factor. Options under <prefix>redundant_ change the inner
// solver; -<prefix>pc_type lu -<prefix>pc_factor_mat_solver_type mumps puts
// MUMPS back.
PetscErrorCode useRedundantDirectSolver(KSP ksp);

// The shift-and-invert solver of the eigen-analyses (full solves, tracking
// refinements): KLU on one rank; on several ranks the redundant KLU
// factorization above, or with -boom_schur_dd given explicitly the
// interface Schur complement as for the time steps
// (schur_complement_solver.hpp; not by default: a pencil with a small shift
// can leave a rank's free piece almost singular). Both make two runs agree
// bitwise: with MUMPS two runs of the same tracking differed in the last
// bits (up to 3e-11 relative in the tracked frequencies on the paper scene).
PetscErrorCode useAnalysisDirectSolver(KSP ksp);

} // namespace boomdyn
