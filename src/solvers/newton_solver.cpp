#include "boomdyn/newton_solver.hpp"

#include "boomdyn/direct_solver.hpp"

namespace boomdyn {

NewtonSolver::~NewtonSolver()
{
  if (snes_) (void)SNESDestroy(&snes_);
  if (J_) (void)MatDestroy(&J_);
  if (F_) (void)VecDestroy(&F_);
}

PetscErrorCode NewtonSolver::setUp(Assembler &assembler, const char *prefix, PetscInt maxIterations)
{
  KSP ksp;
  SNESLineSearch ls;
  PetscFunctionBeginUser;
  assembler_ = &assembler;
  patternVersion_ = assembler.patternVersion();
  PetscCall(assembler.createMatrix(&J_));
  PetscCall(assembler.createVector(&F_));
  PetscCall(SNESCreate(assembler.comm(), &snes_));
  if (prefix) PetscCall(SNESSetOptionsPrefix(snes_, prefix));
  PetscCall(SNESSetFunction(snes_, F_, formFunction, this));
  PetscCall(SNESSetJacobian(snes_, J_, J_, formJacobian, this));
  PetscCall(SNESSetType(snes_, SNESNEWTONLS));
  PetscCall(SNESGetLineSearch(snes_, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  // Residuals are forces whose round-off grows like eps M/(beta h^2): an
  // absolute tolerance that fits one step size fails at another, so the
  // tests are relative to the first residual and to the size of x.
  PetscCall(SNESSetTolerances(snes_, 1e-50, 1e-10, 1e-10, maxIterations, 10 * maxIterations));
  // No divergence test on the residual: with stiff axial terms the first
  // Newton iterate routinely raises the residual by many orders (transverse
  // motion stretches the axis) on the way to quadratic convergence. The
  // iteration limit still ends a hopeless solve (-snes_divergence_tolerance
  // restores PETSc's test).
  PetscCall(SNESSetDivergenceTolerance(snes_, -1.0));
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(useDirectSolver(ksp));
  PetscCall(SNESSetFromOptions(snes_));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::solve(Vec x, PetscInt *iterations, SNESConvergedReason *reason)
{
  PetscFunctionBeginUser;
  if (patternVersion_ != assembler_->patternVersion()) {
    // A sliding joint moved to another element: a new matrix with the new
    // pattern and a reset KSP, so that MUMPS redoes its symbolic
    // factorization (reusing it is wrong on more than one rank: trap 1).
    KSP ksp;
    PetscCall(MatDestroy(&J_));
    PetscCall(assembler_->createMatrix(&J_));
    PetscCall(SNESGetKSP(snes_, &ksp));
    PetscCall(KSPReset(ksp));
    PetscCall(SNESSetJacobian(snes_, J_, J_, formJacobian, this));
    patternVersion_ = assembler_->patternVersion();
  }
  PetscCall(SNESSolve(snes_, nullptr, x));
  PetscCall(SNESGetIterationNumber(snes_, iterations));
  PetscCall(SNESGetConvergedReason(snes_, reason));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::formFunction(SNES, Vec x, Vec F, void *self)
{
  auto *me = static_cast<NewtonSolver *>(self);
  PetscFunctionBeginUser;
  PetscCall(me->assembler_->evaluate(me->ctx, x, F, nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::formJacobian(SNES, Vec x, Mat J, Mat, void *self)
{
  auto *me = static_cast<NewtonSolver *>(self);
  PetscFunctionBeginUser;
  PetscCall(me->assembler_->evaluate(me->ctx, x, nullptr, J));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
