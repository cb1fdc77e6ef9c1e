// Exact direct solver for several ranks by static condensation onto the
// rank interfaces (a PCSHELL; -boom_schur_dd). Every rank owns a contiguous
// piece of each boom; its interior unknowns (rows without couplings to other
// ranks) are eliminated with a local KLU factorization, which leaves a small
// dense Schur complement on the interface unknowns (a few per cut, plus the
// multiplier rows of constraints that span ranks):
//
//     S = A_GG - sum_p A_{G I_p} A_{I_p I_p}^{-1} A_{I_p G}.
//
// S is assembled by an all-gather and factored redundantly on every rank.
// The interior unknowns that couple to the interface are ordered last in the
// interior factorization, so S needs only the trailing rows of the factors,
// and a solve is one forward and one backward sweep over each rank's interior
// factors (the cost of one KLU solve) around a small dense solve: the work
// per rank falls like 1/P, with no dense A_II^{-1} A_IG block at all
// (docs/performance-history.md, "Two ranks: the Schur complement without
// W"). It is the dynamic runs' default on several ranks (NewtonSolver::setUp;
// -boom_schur_dd 0: MUMPS). MUMPS factors a boom's chain-like elimination
// tree front by front, which is slower than one KLU solve on one rank at
// every size measured (docs/performance.md, "Several ranks"), and is not
// bitwise reproducible from run to run.
//
// A group of rows all of whose columns are another rank's or the group's own
// (a clamp's multipliers, numbered last on the last rank, with the clamped
// node on rank 0) is adopted by that rank inside the preconditioner: its
// values and right-hand side are sent there, it is interior there, and its
// solution comes back. Otherwise rows with a zero diagonal (multipliers,
// massless slack coordinates) are put on the interface, so the interior
// blocks are mass-bearing coordinates (and adopted clamps) only:
// nonsingular in every dynamic iteration matrix and at acceleration level. Statics of a free piece between two ranks has a singular interior
// block (no mass, no support), so the static solver keeps MUMPS unless
// -static_boom_schur_dd is given.
#pragma once

#include <petscksp.h>

#include <vector>

namespace boomdyn {

// Makes ksp a KSPPREONLY with the interface Schur-complement PCSHELL.
PetscErrorCode useSchurComplementSolver(KSP ksp);

// This rank's split at the last set-up of such a ksp (tests, -info): the
// interior unknowns coupled to the interface (J) come last in the interior
// factorization when firstRow = firstColumn = interior - coupled; pivoting
// that moved a J column earlier shows as a smaller firstColumn (only slower).
struct SchurComplementLayout {
  PetscInt interior = 0, interface = 0;
  PetscInt coupled = 0;     // |J|
  PetscInt firstRow = 0;    // first J row of A_IG in the factors' row order
  PetscInt firstColumn = 0; // first J column of A_GI in the factors' column order
  // Adoption: other ranks' rows in this rank's interior (global rows) and
  // the number of this rank's rows in other ranks' interiors.
  std::vector<PetscInt> adoptedRows;
  PetscInt given = 0;
  std::vector<PetscInt> interfaceRows; // this rank's interface unknowns (global rows)
};
PetscErrorCode schurComplementLayout(KSP ksp, SchurComplementLayout *layout);

} // namespace boomdyn
