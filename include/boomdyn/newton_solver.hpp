// SNES on the assembled saddle-point system, shared by statics, dynamics and
// the consistent-acceleration solve. Defaults: Newton with a basic (full)
// step, KSPPREONLY + LU (KLU on one rank; on several, the interface Schur complement in dynamics, MUMPS in statics); every one of
// them can be changed with the usual -snes_/-ksp_/-pc_ options under the
// solver's prefix.
//
// Jacobian reuse (modified Newton, on by default; -boom_jacobian_reuse 0 for
// full Newton): the factored iteration matrix is kept across Newton
// iterations and across solves, and rebuilt only when it no longer contracts
// the residual well enough, when the iteration coefficients change (a new
// step size or another kind of solve), when the sparsity pattern changes, or
// when it is older than a given number of solves. A convergence by a small
// update with a kept matrix while the residual stagnates is accepted only
// after a Newton step, unless the update is at round-off (100 eps |q|) or
// at the round-off floor an earlier such Newton step showed (residual and
// update at most twice the ones it left); a solve in which a kept matrix made the residual grow,
// or that fails, is redone by full Newton from the same initial guess, so
// reuse never turns a step full Newton solves into a rejected one.
#pragma once

#include "boomdyn/assembler.hpp"
#include "boomdyn/block_convergence.hpp"
#include "boomdyn/petsc_handle.hpp"

#include <petscsnes.h>

#include <functional>

namespace boomdyn {

template <>
struct PetscDestroyer<SNES> {
  static PetscErrorCode destroy(SNES *s) { return SNESDestroy(s); }
};

struct JacobianReuse {
  // On by default (docs/defaults.md; docs/performance-history.md, "Defaults
  // and start-up": the moves of the results against full Newton are far
  // below each scene's time-step error).
  bool enabled = true;
  // Rebuild when |F_k| / |F_{k-1}| exceeds this (a stale matrix contracts slowly).
  double refreshRatio = 0.25;
  // Rebuild after this many solves with one matrix (0: no limit).
  PetscInt maxAge = 0;
};

// The Newton solver's own options (-boom_jacobian_*, -boom_schur_dd) in one
// PetscOptionsBegin/End block with help text, checked; called by setUp(),
// and by the program for -help without a scene, so -help lists them too.
// -boom_newton_block_test (default on) selects the per-block convergence test
// (block_convergence.hpp) instead of PETSc's test on the whole vector; it is
// read (and listed by -help) also when blockTest is null.
PetscErrorCode readNewtonOptions(MPI_Comm comm, const char *prefix, JacobianReuse *reuse, PetscBool *schur,
                                 PetscBool *blockTest = nullptr);

struct NewtonStatistics {
  PetscInt solves = 0, iterations = 0, jacobians = 0, retriesWithFreshJacobian = 0;
  // Solves ended by a kept matrix's update at the round-off floor that an
  // earlier Newton step showed (instead of by a Newton step).
  PetscInt acceptedAtRoundoffFloor = 0;
};

class NewtonSolver {
public:
  NewtonSolver() = default;
  NewtonSolver(const NewtonSolver &) = delete;
  NewtonSolver &operator=(const NewtonSolver &) = delete;

  // prefix may be null (then -snes_monitor etc. apply directly). Reads
  // -boom_jacobian_reuse, -boom_jacobian_refresh_ratio, -boom_jacobian_max_age;
  // reuseByDefault is the value of -boom_jacobian_reuse when it is not given
  // (dynamics: on; statics: off, a few load steps where reuse saves nothing).
  PetscErrorCode setUp(Assembler &assembler, const char *prefix, PetscInt maxIterations, bool reuseByDefault = true);
  // Solve from the initial guess in x; the solution overwrites x.
  PetscErrorCode solve(Vec x, PetscInt *iterations, SNESConvergedReason *reason);
  // The next solve starts with a fresh Jacobian.
  void invalidateJacobian() { jacobianValid_ = false; }
  // One linear solve J y = b with the solver's own matrix (current with the
  // pattern) and direct solver: `assemble` fills the matrix, which is then
  // factored in place of the Newton Jacobian (so no second matrix or factor
  // is held; the next Newton solve builds a fresh Jacobian). *solved is
  // false when the factorization or the solve failed (a singular matrix).
  PetscErrorCode solveLinear(const std::function<PetscErrorCode(Mat)> &assemble, Vec b, Vec y, bool *solved);

  AssemblyContext ctx; // set by the caller before solve()
  // Subtracted from every residual when not null (set by the caller; the
  // velocity projection removes the finite forces this way).
  Vec residualShift = nullptr;
  SNES snes() const { return snes_; }
  // The 2-norm of the last residual (SNESGetFunctionNorm unless the block
  // test's own norms replace the line search's, see setUp()).
  PetscErrorCode lastFunctionNorm(PetscReal *fnorm) const;
  Mat jacobian() const { return J_; }
  const JacobianReuse &reuse() const { return reuse_; }
  const NewtonStatistics &statistics() const { return stats_; }

private:
  static PetscErrorCode formFunction(SNES, Vec x, Vec F, void *self);
  static PetscErrorCode formJacobian(SNES, Vec x, Mat J, Mat P, void *self);
  static PetscErrorCode convergenceTest(SNES, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm,
                                        SNESConvergedReason *reason, void *self);
  static PetscErrorCode fullStep(SNESLineSearch ls, void *self);
  PetscErrorCode solveOnce(Vec x, PetscInt *iterations, SNESConvergedReason *reason);
  // After a sliding joint moved to another element: a matrix of the new pattern.
  PetscErrorCode followPattern();
  static PetscErrorCode factor(SNES snes, Mat J);
  bool sameIterationMatrix(const AssemblyContext &a, const AssemblyContext &b) const;

  Assembler *assembler_ = nullptr;
  int patternVersion_ = 0;
  PetscHandle<SNES> snes_;
  PetscHandle<Mat> J_;
  PetscHandle<Vec> F_, x0_;
  JacobianReuse reuse_;
  NewtonStatistics stats_;
  bool jacobianValid_ = false;   // J_ holds a factored matrix usable for ctx
  bool jacobianFresh_ = false;   // J_ was built during the current solve
  AssemblyContext jacobianCtx_;  // coefficients J_ was built with
  PetscInt jacobianAge_ = 0;     // solves since J_ was built
  PetscInt jacobianIteration_ = 0; // SNES iteration at which J_ was built (meaningful when jacobianFresh_)
  bool fullNewton_ = false;      // retrying a failed solve with a fresh matrix at every iterate
  PetscReal previousFnorm_ = 0;
  // The round-off floor of the residual and of the update it produces, as a
  // Newton step at a stagnating residual showed them (update relative to |x|).
  struct RoundoffFloor {
    bool known = false;
    PetscReal update = 0, residual = 0;
  };
  RoundoffFloor floor_;
  bool floorProbe_ = false; // the current iteration is such a Newton step
  bool blockTest_ = true;
  bool ownNorms_ = false; // fullStep is the line search; the norms are the block test's
  BlockConvergence blocks_;
};

} // namespace boomdyn
