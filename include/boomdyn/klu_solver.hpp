// The one-rank direct solver (issue 18): SuiteSparse KLU behind PETSc's LU
// interface, registered as the MatSolverType "boomklu". It differs from
// PETSc's own KLU interface (MATSOLVERKLU) in two ways that the time steps
// and the tracking analyses pay for every step:
//  - Refactorization. A numeric factorization of a matrix with the pattern
//    of the last one reuses that one's pivot order (klu_refactor: no
//    depth-first searches, no pivot search), about half the cost of
//    klu_factor at the paper scene's 216 unknowns. Without pivoting it can
//    be unstable, so the reciprocal pivot growth is checked after each
//    refactorization and, when it fell below `growth_drop` times that of the
//    last full factorization, the matrix is factored again with pivoting.
//  - Several right-hand sides in one solve (kluSolveColumns(), used by the
//    tracking refinements): one pass over L and U for up to eight columns,
//    on the factors extracted from KLU's (klu_extract, once per numeric
//    factorization) and with the columns side by side as short vectors:
//    about half of KLU's own solve's instructions, each column bitwise
//    KLU's.
// Options (prefix of the factored matrix, none for boomdyn's matrices):
//   -mat_boomklu_refactor <reuse>       reuse the pivot order (false: klu_factor every time);
//                                       default: the value of -boom_jacobian_reuse (true), since
//                                       both keep history a checkpoint does not hold
//   -mat_boomklu_growth_drop <1e-2>     accept a refactorization while its reciprocal pivot
//                                       growth is at least this times the last full one's
// -pc_factor_mat_solver_type klu (with the solver's prefix) goes back to
// PETSc's interface. Same ordering (AMD after BTF), pivot tolerance (1e-3)
// and scaling (none) as PETSc's interface: the first factorization and its
// solves are bitwise those of MATSOLVERKLU.
#pragma once
#include <petscmat.h>

#include <vector>

namespace boomdyn {

inline constexpr const char *MATSOLVERBOOMKLU = "boomklu";

// Registers "boomklu" for sequential AIJ matrices (once per PETSc session;
// useDirectSolver() calls it).
PetscErrorCode registerKluSolver();

// For a factor made by "boomklu": overwrites the `columns` columns of x
// (leading dimension ld >= rows) with the solutions of A x = x, eight
// columns per pass over the factors (one column: KLU's own solve), and sets
// *done. For any other factor *done is false and x is
// untouched (the caller solves column by column). Each column's solution is
// bitwise that of MatSolve with the same factor.
PetscErrorCode kluSolveColumns(Mat factor, PetscInt columns, PetscInt ld, double *x, PetscBool *done);

// Marks unknowns of the sequential AIJ matrix A (last[i] != 0) that boomklu
// orders after all others when it factors A: CAMD with these as the last
// constraint set, in one block (no BTF). Must precede the symbolic
// factorization (KSPSetUp); kept on A (PetscObjectCompose) for every later
// one. Row pivoting can still move a marked unknown's pivot row earlier.
PetscErrorCode kluSetLastUnknowns(Mat A, PetscInt n, const PetscInt *last);

// The factors of boomklu's last numeric factorization of a matrix marked with
// kluSetLastUnknowns(), as compressed columns (klu_extract). boomklu factors
// the AIJ rows read as columns, M = A^T:  M(P[i], Q[j]) = (L U)(i, j), L unit
// lower triangular with its diagonal first in each column, U upper triangular
// with its diagonal last. So A x = b is U^T w = b(Q), L^T xbar = w, x(P) = xbar.
// The arrays are resized (kept when the sizes hold) and overwritten.
struct KluFactors {
  PetscInt n = 0;
  std::vector<int> Lp, Li, Up, Ui, P, Q;
  std::vector<double> Lx, Ux;
};
PetscErrorCode kluExtractFactors(Mat factor, KluFactors *factors);

// Counters of the factor's numeric factorizations (for tests and -ksp_view).
struct KluFactorCounts {
  PetscInt full = 0;      // klu_factor (with pivoting)
  PetscInt refactors = 0; // klu_refactor accepted
  PetscInt rejected = 0;  // klu_refactor whose pivot growth sent it back to klu_factor
  PetscInt offDiagonal = 0; // entries outside the diagonal blocks of the last factorization's block triangular form
};
PetscErrorCode kluFactorCounts(Mat factor, KluFactorCounts *counts, PetscBool *isKlu);

} // namespace boomdyn
