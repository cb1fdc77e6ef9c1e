#include "boomdyn/newton_solver.hpp"

#include "boomdyn/direct_solver.hpp"
#include "boomdyn/schur_complement_solver.hpp"

// The SNES monitors, to know whether anything prints the line search norms (setUp).
#include <petsc/private/snesimpl.h>

#include <cmath>
#include <limits>
#include <string>

namespace boomdyn {

PetscErrorCode NewtonSolver::setUp(Assembler &assembler, const char *prefix, PetscInt maxIterations,
                                   bool reuseByDefault)
{
  KSP ksp;
  SNESLineSearch ls;
  PetscFunctionBeginUser;
  assembler_ = &assembler;
  patternVersion_ = assembler.patternVersion();
  PetscCall(assembler.createMatrix(J_.address()));
  PetscCall(assembler.createVector(F_.address()));
  PetscCall(assembler.createVector(x0_.address()));
  PetscCall(SNESCreate(assembler.comm(), snes_.address()));
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

  // Several ranks, dynamics: the interface Schur complement by default (exact
  // like MUMPS, 1.8x one rank on the 10^5-element boom where MUMPS was slower
  // than one rank, and bitwise reproducible from run to run, which MUMPS is
  // not: docs/performance-history.md, "Ninth round"). Statics (prefix
  // static_) does not: a free piece between two ranks has a singular
  // interior block.
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(assembler.comm(), &size));
  PetscBool schur = size > 1 && !prefix ? PETSC_TRUE : PETSC_FALSE, blockTest = PETSC_TRUE;
  reuse_.enabled = reuseByDefault;
  PetscCall(readNewtonOptions(assembler.comm(), prefix, &reuse_, &schur, &blockTest));
  if (schur) PetscCall(useSchurComplementSolver(ksp));
  // Statics on several ranks: every rank factors the whole Jacobian
  // (direct_solver.hpp), reproducible from run to run, unlike MUMPS.
  else if (size > 1 && prefix) PetscCall(useRedundantDirectSolver(ksp));
  // The modified iteration contracts linearly and stops just inside the step
  // test, while Newton's last step squares the error and ends far inside it:
  // at 1e-10 of |x| the position error left in a stiff element becomes a
  // force error (EA/L 1e9 N/m x 1e-9 m on a 100 kg payload: g/1000), and a
  // pendulum on such a rope swung 1.0e-3 slow (WinchVerification). 1e-12
  // keeps the accuracy (3e-6) at the same cost: the paper scene 4.92 s CPU
  // against 5.03 s, 1665 factorizations against 993 (full Newton: 15615),
  // since an update at the round-off floor ends the iteration without a
  // Newton step. -snes_stol still overrides it.
  if (reuse_.enabled) PetscCall(SNESSetTolerances(snes_, 1e-50, 1e-10, 1e-12, maxIterations, 10 * maxIterations));
  blockTest_ = blockTest;
  if (blockTest_) PetscCall(blocks_.setUp(assembler.model(), F_));
  if (reuse_.enabled || blockTest_) PetscCall(SNESSetConvergenceTest(snes_, convergenceTest, this, nullptr));
  // The block test judges the iterate by its own sums over x, dx and F
  // (block_convergence.cpp), which give the 2-norms as well. With it the
  // full step is a line search of our own (fullStep): x -= dx in place and
  // the residual, without the basic line search's three norms (passes over
  // F, dx and x that the test then repeats) and its copy of the new iterate
  // from a work vector. The same x and F bit for bit. Only while nothing
  // else reads the line search's norms: -snes_linesearch_type, or an SNES
  // monitor (which prints them), keeps PETSc's line search.
  if (blockTest_) {
    PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHSHELL));
    PetscCall(SNESLineSearchShellSetUserFunc(ls, fullStep, this));
  }
  PetscCall(SNESSetFromOptions(snes_));
  PetscBool shell = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare((PetscObject)ls, SNESLINESEARCHSHELL, &shell));
  ownNorms_ = blockTest_ && shell && snes_.get()->numbermonitors == 0;
  if (blockTest_ && shell && !ownNorms_) {
    PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
    PetscCall(SNESLineSearchSetComputeNorms(ls, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

// The line search with the block test (setUp): the full Newton step, as
// SNESLINESEARCHBASIC at damping 1 takes it (there W = X - Y, F(W), X = W;
// here X - Y in place, the same numbers), without norms: convergenceTest
// takes them from the block test's sums, of which the update takes those
// over X and Y in its pass.
PetscErrorCode NewtonSolver::fullStep(SNESLineSearch ls, void *self)
{
  auto *me = static_cast<NewtonSolver *>(self);
  SNES snes;
  Vec X, F, Y;
  PetscBool domainError;
  PetscFunctionBeginUser;
  PetscCall(SNESLineSearchGetVecs(ls, &X, &F, &Y, nullptr, nullptr));
  PetscCall(SNESLineSearchGetSNES(ls, &snes));
  PetscCall(SNESLineSearchSetReason(ls, SNES_LINESEARCH_SUCCEEDED));
  PetscCall(me->blocks_.step(X, Y)); // X -= Y, with the block test's sums over X and Y
  PetscCall(SNESComputeFunction(snes, X, F));
  PetscCall(SNESGetFunctionDomainError(snes, &domainError));
  if (domainError) PetscCall(SNESLineSearchSetReason(ls, SNES_LINESEARCH_FAILED_DOMAIN));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::lastFunctionNorm(PetscReal *fnorm) const
{
  PetscFunctionBeginUser;
  if (ownNorms_) *fnorm = blocks_.fnorm();
  else PetscCall(SNESGetFunctionNorm(snes_, fnorm));
  PetscFunctionReturn(0);
}

PetscErrorCode readNewtonOptions(MPI_Comm comm, const char *prefix, JacobianReuse *reuse, PetscBool *schur,
                                 PetscBool *blockTest)
{
  PetscBool blocks = blockTest ? *blockTest : PETSC_TRUE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, prefix, "Newton iteration matrix reuse", "boomdyn");
  PetscBool enabled = reuse->enabled ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscOptionsBool("-boom_jacobian_reuse",
                             "Keep the factored Jacobian across iterations and steps (modified Newton)", "", enabled,
                             &enabled, nullptr));
  reuse->enabled = enabled;
  PetscCall(PetscOptionsReal("-boom_jacobian_refresh_ratio",
                             "Rebuild the Jacobian when |F_k|/|F_k-1| exceeds this", "", reuse->refreshRatio,
                             &reuse->refreshRatio, nullptr));
  PetscCall(PetscOptionsInt("-boom_jacobian_max_age", "Rebuild the Jacobian after this many solves (0: never)", "",
                            reuse->maxAge, &reuse->maxAge, nullptr));
  PetscCall(PetscOptionsBool("-boom_schur_dd",
                             "Direct solves by condensation onto the rank interfaces (KLU per rank) instead of MUMPS (default on for dynamic runs "
                             "on several ranks; given explicitly, the tracking's eigen-analyses too)", "",
                             *schur, schur, nullptr));
  PetscCall(PetscOptionsBool("-boom_newton_block_test",
                             "Judge Newton convergence per block of unknowns (body and slack coordinates, first-order states, "
                             "multipliers), each on its own scale, instead of on the whole vector",
                             "", blocks, &blocks, nullptr));
  if (blockTest) *blockTest = blocks;
  PetscOptionsEnd();
  PetscCheck(reuse->refreshRatio > 0 && reuse->refreshRatio < 1, comm, PETSC_ERR_USER_INPUT,
             "-boom_jacobian_refresh_ratio must lie in (0, 1), got %g", (double)reuse->refreshRatio);
  PetscCheck(reuse->maxAge >= 0, comm, PETSC_ERR_USER_INPUT,
             "-boom_jacobian_max_age must be >= 0, got %" PetscInt_FMT, reuse->maxAge);
  PetscFunctionReturn(0);
}

bool NewtonSolver::sameIterationMatrix(const AssemblyContext &a, const AssemblyContext &b) const
{
  // The iteration matrix depends on the step size through the coefficients
  // of the affine map and the row scaling; a different kind of solve
  // (acceleration level, statics) has a different matrix altogether.
  auto same = [](double u, double v) { return std::abs(u - v) <= 1e-12 * std::max(std::abs(u), std::abs(v)); };
  return same(a.kin.cQ, b.kin.cQ) && same(a.kin.cV, b.kin.cV) && same(a.kin.cA, b.kin.cA) &&
         same(a.kin.cZ, b.kin.cZ) && same(a.sigma, b.sigma) && a.accelerationLevel == b.accelerationLevel &&
         a.velocityLevel == b.velocityLevel &&
         a.constraintBlocks == b.constraintBlocks;
}

PetscErrorCode NewtonSolver::followPattern()
{
  PetscFunctionBeginUser;
  if (patternVersion_ != assembler_->patternVersion()) {
    // A sliding joint moved to another element: a new matrix with the new
    // pattern and a reset KSP, so that MUMPS redoes its symbolic
    // factorization (reusing it is wrong on more than one rank: trap 1).
    KSP ksp;
    PetscCall(assembler_->createMatrix(J_.address()));
    PetscCall(SNESGetKSP(snes_, &ksp));
    PetscCall(KSPReset(ksp));
    PetscCall(SNESSetJacobian(snes_, J_, J_, formJacobian, this));
    patternVersion_ = assembler_->patternVersion();
    jacobianValid_ = false;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::solveLinear(const std::function<PetscErrorCode(Mat)> &assemble, Vec b, Vec y,
                                         bool *solved)
{
  KSP ksp;
  PC pc;
  KSPConvergedReason kspReason = KSP_DIVERGED_PC_FAILED;
  PetscFunctionBeginUser;
  PetscCall(followPattern());
  jacobianValid_ = false;
  PetscCall(assemble(J_));
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(KSPSetOperators(ksp, J_, J_));
  PetscCall(KSPGetPC(ksp, &pc));
  // As in factor(): a breakdown is recognised by its error code, kept out of the error log.
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  PetscErrorCode ierr = PCSetUp(pc);
  if (!ierr) ierr = KSPSolve(ksp, b, y);
  PetscCall(PetscPopErrorHandler());
  if (!ierr) PetscCall(KSPGetConvergedReason(ksp, &kspReason));
  *solved = !ierr && kspReason > 0;
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::solve(Vec x, PetscInt *iterations, SNESConvergedReason *reason)
{
  PetscFunctionBeginUser;
  PetscCall(followPattern());
  ++stats_.solves;
  if (!reuse_.enabled) {
    PetscCall(solveOnce(x, iterations, reason));
    PetscFunctionReturn(0);
  }
  const bool sameMatrix = jacobianValid_ && sameIterationMatrix(ctx, jacobianCtx_);
  const bool fresh = !sameMatrix || (reuse_.maxAge > 0 && jacobianAge_ >= reuse_.maxAge);
  // The round-off floor was seen with this iteration matrix; another one
  // (a new step size, another kind of solve) maps round-off differently.
  if (!sameMatrix) floor_ = RoundoffFloor{};
  PetscCall(VecCopy(x, x0_));
  // lag -2: build the Jacobian at the first iterate, then keep it (-1).
  PetscCall(SNESSetLagJacobian(snes_, fresh ? -2 : -1));
  jacobianFresh_ = false;
  PetscCall(solveOnce(x, iterations, reason));
  if (*reason <= 0) {
    // Failed with a matrix kept over several iterates (from an earlier solve
    // or rebuilt only when the contraction was poor): redo from the same
    // guess with full Newton, a fresh matrix at every iterate, so that reuse
    // never turns a step full Newton solves into a rejected one (a large h
    // on a strongly nonlinear step needs more modified iterations than the
    // iteration limit allows).
    PetscInt more;
    ++stats_.retriesWithFreshJacobian;
    PetscCall(PetscInfo(snes_.get(), "solve with a reused Jacobian failed (%s); retrying with full Newton\n",
                        SNESConvergedReasons[*reason]));
    PetscCall(VecCopy(x0_, x));
    PetscCall(SNESSetLagJacobian(snes_, 1));
    fullNewton_ = true;
    PetscCall(solveOnce(x, &more, reason));
    fullNewton_ = false;
    *iterations += more;
  }
  if (*reason <= 0) jacobianValid_ = false; // do not carry a matrix from a failed solve
  ++jacobianAge_;
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::solveOnce(Vec x, PetscInt *iterations, SNESConvergedReason *reason)
{
  PetscFunctionBeginUser;
  previousFnorm_ = 0;
  floorProbe_ = false;
  PetscCall(SNESSolve(snes_, nullptr, x));
  PetscCall(SNESGetIterationNumber(snes_, iterations));
  PetscCall(SNESGetConvergedReason(snes_, reason));
  stats_.iterations += *iterations;
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::convergenceTest(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm,
                                             PetscReal fnorm, SNESConvergedReason *reason, void *self)
{
  auto *me = static_cast<NewtonSolver *>(self);
  PetscFunctionBeginUser;
  if (me->blockTest_) {
    Vec x, dx, F;
    PetscReal atol, rtol, stol;
    PetscInt maxIt, maxF;
    PetscCall(SNESGetSolution(snes, &x));
    PetscCall(SNESGetSolutionUpdate(snes, &dx));
    PetscCall(SNESGetFunction(snes, &F, nullptr, nullptr));
    PetscCall(SNESGetTolerances(snes, &atol, &rtol, &stol, &maxIt, &maxF));
    PetscCall(me->blocks_.test(it, x, dx, F, rtol, stol, atol, reason));
    // Without PETSc's line search norms (fullStep): the block test's. Their
    // sums run in another order than BLAS's, so they may differ from
    // VecNorm's in the last bits; they only enter the comparisons below.
    if (me->ownNorms_) fnorm = me->blocks_.fnorm(), xnorm = me->blocks_.xnorm(), snorm = me->blocks_.snorm();
  } else PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, nullptr));
  // Full Newton, or the retry of a failed reuse: a fresh matrix at every iterate already.
  if (!me->reuse_.enabled || me->fullNewton_) PetscFunctionReturn(0);
  // Was the last update a Newton step (matrix built at the previous iterate)?
  const bool newtonStep = me->jacobianFresh_ && me->jacobianIteration_ == it - 1;
  const PetscReal rho = it > 0 && me->previousFnorm_ > 0 ? fnorm / me->previousFnorm_ : 0;
  const bool slow = it > 0 && rho > me->reuse_.refreshRatio;
  me->previousFnorm_ = fnorm;
  if (newtonStep && me->floorProbe_) {
    // The Newton step asked for at a stagnating residual (below): if it did
    // not lower the residual either, the residual is at its round-off floor,
    // and this update is the size round-off produces. Kept for the next solves.
    me->floorProbe_ = false;
    if (*reason > 0 && slow) {
      me->floor_ = {true, snorm / xnorm, fnorm};
      PetscCall(PetscInfo(snes, "iteration %d: round-off floor: update %g |x|, residual %g (rho %g)\n", (int)it,
                          (double)(snorm / xnorm), (double)fnorm, (double)rho));
    }
  }
  // Round-off of the increments (100 eps |q|, what an increment can
  // resolve), and whether a Newton step has shown a round-off floor well
  // above it (same iteration matrix). Large systems only: on the
  // 10^5-element boom round-off in the residual produces updates of
  // 1.9e-13 |x| against 100 eps |q| = 2.2e-14 |x| (8.4x). Of the stored
  // scenes only hoist_extraction reaches 4x (with the acceleration
  // predictor: 214 solves end at the floor there, results within 6e-8).
  const PetscReal resolution = me->blockTest_ ? me->blocks_.incrementRoundoff()
                                              : 100 * std::numeric_limits<PetscReal>::epsilon() * xnorm;
  const PetscReal floorUpdate = me->floor_.update * xnorm;
  const bool largeFloor = me->floor_.known && floorUpdate >= 4 * resolution;
  if (newtonStep || it == 0) PetscFunctionReturn(0); // Newton's own tests
  // A stale matrix that made the residual grow after the iteration had
  // started to converge has led the iterate away from Newton's path; from
  // there the iteration can end at another solution of the step equations
  // (fast extraction at h = 10 ms: a different end state, 10x the energy
  // error). Such a solve is ended and redone by full Newton from its initial
  // guess (solve()). The first iteration is exempt: there even Newton's step
  // routinely raises the residual of stiff beams.
  // Not at round-off size: there the residual's noise can rise by chance
  // (512-element cantilever: 2.6x the Jacobians without this guard).
  if (*reason == SNES_CONVERGED_ITERATING && it > 1 && rho > 1 && snorm > 1e-8 * xnorm) {
    *reason = SNES_DIVERGED_DTOL;
    PetscFunctionReturn(0);
  }
  // Unless the update is at the round-off of the increments (100 eps |q|,
  // the block test's floor): then the residual stagnates at its own
  // round-off floor, which a Newton step does not lower either (long
  // cantilever, 1000 to 10^5 elements: a Jacobian at every step without this).
  const bool atRoundoff = me->blockTest_ ? me->blocks_.incrementAtRoundoff() : snorm <= resolution;
  if (*reason == SNES_CONVERGED_SNORM_RELATIVE && slow && !atRoundoff) {
    // A small update from a stale matrix proves nothing when the residual
    // stagnates: the update of a block far smaller than |x| (the LuGre
    // bristle states, ~1e-5 m next to metres) passes the step test while
    // that block is not solved at all (tilting incline at sigma0 = 1e6:
    // residual stuck at 6e-4 of the first, the block never slides). Accepted
    // only after a Newton step with a fresh matrix; then the stagnation is
    // the residual's round-off floor, as for full Newton.
    // Unless such a Newton step has shown a large floor already (above):
    // then a residual and an update no larger than twice the ones it left
    // are that floor again (the 10^5-element boom built a Jacobian at
    // every step without this: 41 in 50 steps; the 2048-element cantilever
    // 3555 instead of 3010 in 1 s, its tip within 2.3e-11 m of full Newton
    // either way). Both must be at the floor: a residual near it alone
    // says little (accepting residuals within 1.5x of it put that
    // cantilever's tip 3.5e-6 m off), since a smooth residual as small as
    // the round-off noise can still carry a large error.
    if (largeFloor && snorm <= 2 * floorUpdate && fnorm <= 2 * me->floor_.residual) {
      ++me->stats_.acceptedAtRoundoffFloor;
      PetscCall(PetscInfo(snes, "iteration %d: update %g |x| and residual %g at the round-off floor (%g |x|, %g; increments resolve %g |x|) a Newton step showed\n",
                          (int)it, (double)(snorm / xnorm), (double)fnorm, (double)me->floor_.update, (double)me->floor_.residual,
                          (double)(resolution / xnorm)));
      PetscFunctionReturn(0);
    }
    *reason = SNES_CONVERGED_ITERATING;
    me->floorProbe_ = true;
    PetscCall(SNESSetLagJacobian(snes, -2));
    PetscFunctionReturn(0);
  }
  if (*reason != SNES_CONVERGED_ITERATING) PetscFunctionReturn(0);
  // A reused matrix that contracts the residual too slowly is rebuilt at the
  // current iterate (then the iteration is Newton's again) -- unless the
  // update is already at round-off size: on fine meshes the residual stalls
  // at its round-off floor, and no Jacobian helps there.
  if (slow && snorm > 1e-8 * xnorm) PetscCall(SNESSetLagJacobian(snes, -2));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::formFunction(SNES, Vec x, Vec F, void *self)
{
  auto *me = static_cast<NewtonSolver *>(self);
  PetscFunctionBeginUser;
  PetscCall(me->assembler_->evaluate(me->ctx, x, F, nullptr));
  if (me->residualShift) PetscCall(VecAXPY(F, -1.0, me->residualShift));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::formJacobian(SNES snes, Vec x, Mat J, Mat, void *self)
{
  auto *me = static_cast<NewtonSolver *>(self);
  PetscFunctionBeginUser;
  PetscCall(me->assembler_->evaluate(me->ctx, x, nullptr, J));
  PetscCall(factor(snes, J));
  ++me->stats_.jacobians;
  PetscCall(SNESGetIterationNumber(snes, &me->jacobianIteration_));
  me->jacobianValid_ = me->jacobianFresh_ = true;
  me->jacobianCtx_ = me->ctx;
  me->jacobianAge_ = 0;
  PetscFunctionReturn(0);
}

// Factors the new iteration matrix here, before SNES's linear solve would,
// so that a failure is recognised by its error code rather than by the text
// of a message: KLU (and MUMPS with -ksp_error_if_not_converged) raise
// PETSC_ERR_LIB when the numeric factorization breaks down, which for these
// saddle-point matrices means they are singular. The library's own error is
// kept out of the error log (PetscReturnErrorHandler) and replaced by one
// that says what is wrong with the model. MUMPS otherwise records a factor
// error without raising one; SNES then ends with DIVERGED_LINEAR_SOLVE and
// the step is cut, as before. The solve that follows reuses this
// factorization (the matrix state is unchanged).
namespace {

// The first error inside a factorization, kept instead of printed.
struct FactorFailure {
  PetscErrorCode code = 0;
  std::string message, function;
  bool outOfMemory() const
  {
    return code == PETSC_ERR_MEM || function == "PetscMallocAlign" || message.find("allocate") != std::string::npos;
  }
};

PetscErrorCode keepFactorFailure(MPI_Comm, int, const char *function, const char *, PetscErrorCode n,
                                 PetscErrorType type, const char *message, void *context)
{
  auto *failure = static_cast<FactorFailure *>(context);
  if (type == PETSC_ERROR_INITIAL && failure->code == 0)
    failure->code = n, failure->message = message ? message : "", failure->function = function ? function : "";
  return n;
}

} // namespace

PetscErrorCode NewtonSolver::factor(SNES snes, Mat J)
{
  KSP ksp;
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetOperators(ksp, J, J));
  PetscCall(KSPGetPC(ksp, &pc));
  FactorFailure failure;
  PetscCall(PetscPushErrorHandler(keepFactorFailure, &failure));
  const PetscErrorCode ierr = PCSetUp(pc);
  PetscCall(PetscPopErrorHandler());
  // Memory that ran out inside the factorization (MUMPS: "Cannot allocate
  // required memory N megabytes", raised as PETSC_ERR_LIB like a breakdown;
  // PETSc's own allocator) is no singular matrix.
  PetscCheck(ierr == 0 || !failure.outOfMemory(), PetscObjectComm((PetscObject)snes), PETSC_ERR_MEM,
             "the direct solver ran out of memory factorizing the system matrix (%s)", failure.message.c_str());
  PetscCheck(ierr != PETSC_ERR_LIB, PetscObjectComm((PetscObject)snes), PETSC_ERR_MAT_LU_ZRPVT,
             "the system matrix is singular: a body or motion without support, or redundant or contradictory "
             "constraints (two drives on one joint, a clamp plus an angle drive at one point, ...); the direct "
             "solver's LU decomposition broke down");
  PetscCheck(ierr == 0, PetscObjectComm((PetscObject)snes), ierr,
             "the direct solver failed to set up (PETSc error code %d; run with -on_error_abort for its trace)", (int)ierr);
  PetscFunctionReturn(0);
}

} // namespace boomdyn
