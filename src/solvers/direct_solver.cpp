#include "boomdyn/direct_solver.hpp"

#include "boomdyn/klu_solver.hpp"
#include "boomdyn/schur_complement_solver.hpp"

namespace boomdyn {

PetscErrorCode useDirectSolver(KSP ksp)
{
  PC pc;
  const char *prefix;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  // One rank: KLU (SuiteSparse) factors these small, banded saddle-point
  // systems about twice as fast as MUMPS (measured on the paper extraction
  // scene, same results), and boomdyn's interface to it (klu_solver.hpp)
  // refactors with the last pivot order and solves several columns at once;
  // several ranks: MUMPS, the distributed one.
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)ksp), &size));
  if (size == 1) PetscCall(registerKluSolver());
  PetscCall(PCFactorSetMatSolverType(pc, size == 1 ? MATSOLVERBOOMKLU : MATSOLVERMUMPS));
  // MUMPS reads ICNTL(14) from the options database under the KSP's prefix
  // when the factor is created; give a default only if the user has none.
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  PetscCall(PetscOptionsHasName(nullptr, prefix, "-mat_mumps_icntl_14", &set));
  if (!set) {
    char name[256];
    PetscCall(PetscSNPrintf(name, sizeof name, "-%smat_mumps_icntl_14", prefix ? prefix : ""));
    PetscCall(PetscOptionsSetValue(nullptr, name, "200"));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode useRedundantDirectSolver(KSP ksp)
{
  PC pc, innerPc;
  KSP inner;
  PetscFunctionBeginUser;
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCREDUNDANT));
  PetscCall(PCRedundantGetKSP(pc, &inner));
  PetscCall(KSPSetType(inner, KSPPREONLY));
  PetscCall(KSPGetPC(inner, &innerPc));
  PetscCall(PCSetType(innerPc, PCLU));
  PetscCall(registerKluSolver());
  PetscCall(PCFactorSetMatSolverType(innerPc, MATSOLVERBOOMKLU));
  PetscFunctionReturn(0);
}

PetscErrorCode useAnalysisDirectSolver(KSP ksp)
{
  PetscMPIInt size;
  PetscBool schur = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)ksp), &size));
  // The Schur complement only when given: unlike the time steps' iteration
  // matrix, whose mass term keeps every interior block well conditioned
  // (and where it is the default on several ranks), a pencil A - tau B with
  // a small shift leaves a rank's piece that is free apart from its
  // interface almost singular: with the Schur complement by default a modal
  // test on 2 ranks (TelescopeModes, extended) failed to converge. The
  // redundant factorization factors the whole pencil.
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-boom_schur_dd", &schur, nullptr));
  if (size > 1 && !schur) PetscCall(useRedundantDirectSolver(ksp));
  else {
    PetscCall(useDirectSolver(ksp));
    if (size > 1) PetscCall(useSchurComplementSolver(ksp));
  }
  PetscFunctionReturn(0);
}

} // namespace boomdyn
