// Exact direct solver for several ranks by static condensation onto the
// rank interfaces (a PCSHELL; -boom_schur_dd). Every rank owns a contiguous
// piece of each boom; its interior unknowns (rows without couplings to other
// ranks) are eliminated with a local KLU factorization, which leaves a small
// dense Schur complement on the interface unknowns (a few per cut, plus the
// multiplier rows of constraints that span ranks):
//
//     S = A_GG - sum_p A_{G I_p} A_{I_p I_p}^{-1} A_{I_p G}.
//
// S is assembled by an all-gather and factored redundantly on every rank. A
// solve is then one local sparse triangular solve per rank, a small dense
// solve and a dense update with W_p = A_{I_p I_p}^{-1} A_{I_p G_p}, so the
// work per rank falls like 1/P. MUMPS, the default on several ranks, factors
// a boom's chain-like elimination tree front by front, which is slower than
// one KLU solve on one rank at every size measured (docs/performance.md).
//
// Rows with a zero diagonal (multipliers, massless slack coordinates) are
// put on the interface, so the interior blocks are mass-bearing coordinates
// only: nonsingular in every dynamic iteration matrix and at acceleration
// level. Statics of a free piece between two ranks has a singular interior
// block (no mass, no support), so the static solver keeps MUMPS unless
// -static_boom_schur_dd is given.
#pragma once

#include <petscksp.h>

namespace boomdyn {

// Makes ksp a KSPPREONLY with the interface Schur-complement PCSHELL.
PetscErrorCode useSchurComplementSolver(KSP ksp);

} // namespace boomdyn
