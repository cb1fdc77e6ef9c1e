#include "boomdyn/eigen_solver.hpp"

#include "boomdyn/gather.hpp"

#include "boomdyn/direct_solver.hpp"

#include "boomdyn/log_events.hpp"

#include <slepceps.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace boomdyn {

template <>
struct PetscDestroyer<EPS> {
  static PetscErrorCode destroy(EPS *eps) { return EPSDestroy(eps); }
};

PetscErrorCode solveModes(Assembler &assembler, double t, Vec q, Vec lambda, int count, ModalResult *result,
                          const ModalOptions &options)
{
  const PetscInt nq = assembler.model().numCoordinates();
  // Owned by handles: an error (an eigenpair that did not converge) leaks nothing.
  PetscHandle<Mat> A, B;
  PetscHandle<Vec> x, xr, gathered, zero;
  PetscHandle<EPS> eps;
  PetscHandle<VecScatter> toZero;
  ST st;
  KSP ksp;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().eigen, 0, 0, 0, 0));
  // x = [q | lambda / sigma]. The constraint blocks are scaled by sigma, a
  // typical stiffness diagonal: with sigma = 1 they are ~1e-9 of K for steel
  // booms and MUMPS's threshold pivoting declares A - target B singular.
  // The eigenvalues do not depend on sigma.
  PetscReal massScale, stiffScale;
  PetscCall(assembler.characteristicScales(q, &massScale, &stiffScale));
  const double sigma = stiffScale > 0 ? stiffScale : 1.0;
  PetscCall(assembler.createVector(x.address()));
  {
    PetscInt lo, hi;
    const PetscScalar *qa, *la;
    PetscScalar *xa;
    PetscCall(VecGetOwnershipRange(x, &lo, &hi));
    PetscCall(VecGetArrayRead(q, &qa));
    PetscCall(VecGetArrayRead(lambda, &la));
    PetscCall(VecGetArray(x, &xa));
    for (PetscInt i = lo; i < hi; ++i) xa[i - lo] = i < nq ? qa[i - lo] : la[i - lo] / sigma;
    PetscCall(VecRestoreArray(x, &xa));
    PetscCall(VecRestoreArrayRead(lambda, &la));
    PetscCall(VecRestoreArrayRead(q, &qa));
  }
  AssemblyContext ctx;
  ctx.t = t;
  ctx.sigma = sigma;
  PetscCall(assembler.setOffsets(nullptr, nullptr, nullptr));
  PetscCall(assembler.createMatrix(A.address()));
  PetscCall(assembler.createMatrix(B.address()));
  ctx.kin = {1.0, 0.0, 0.0};
  PetscCall(assembler.evaluate(ctx, x, nullptr, A));
  // B: the same pattern as A (explicit zeros), so ST can combine them cheaply.
  ctx.kin = {0.0, 0.0, 1.0};
  ctx.constraintBlocks = false;
  PetscCall(assembler.setOffsets(x, nullptr, nullptr)); // q = x (cQ = 0), so every kernel sees the real state
  PetscCall(assembler.evaluate(ctx, x, nullptr, B));

  PetscCall(EPSCreate(assembler.comm(), eps.address()));
  PetscCall(EPSSetOptionsPrefix(eps, "modal_"));
  PetscCall(EPSSetOperators(eps, A, B));
  PetscCall(EPSSetProblemType(eps, EPS_GHEP));
  PetscCall(EPSSetType(eps, EPSKRYLOVSCHUR));
  PetscCall(EPSSetDimensions(eps, count, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetTolerances(eps, 1e-12, 500));
  // A slightly negative target keeps A - target B nonsingular when the
  // mechanism has rigid-body modes (omega = 0).
  PetscCall(EPSSetTarget(eps, options.target));
  if (options.initialGuess) {
    Vec guess = options.initialGuess;
    PetscCall(EPSSetInitialSpace(eps, 1, &guess));
  }
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  PetscCall(EPSGetST(eps, &st));
  PetscCall(STSetType(st, STSINVERT));
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(useDirectSolver(ksp));
  PetscCall(EPSSetFromOptions(eps));
  PetscCall(EPSSolve(eps));
  PetscInt nconv;
  PetscCall(EPSGetConverged(eps, &nconv));
  PetscCheck(nconv >= count, assembler.comm(), PETSC_ERR_NOT_CONVERGED,
             "eigen-analysis: %" PetscInt_FMT " of %d eigenpairs converged", nconv, count);

  // Order by eigenvalue (SLEPc returns them by distance to the target).
  std::vector<PetscScalar> values(nconv);
  for (PetscInt i = 0; i < nconv; ++i) PetscCall(EPSGetEigenpair(eps, i, &values[i], nullptr, nullptr, nullptr));
  std::vector<PetscInt> order(nconv);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](PetscInt a, PetscInt b) { return values[a] < values[b]; });

  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(assembler.comm(), &rank));
  PetscCall(MatCreateVecs(A, xr.address(), nullptr));
  PetscCall(VecScatterCreateToZero(xr, toZero.address(), gathered.address()));
  *result = ModalResult{};
  PetscCall(VecDuplicate(xr, zero.address()));
  PetscCall(VecSet(zero, 0.0));
  for (int k = 0; k < count; ++k) {
    const PetscInt i = order[k];
    PetscScalar w;
    PetscReal err;
    PetscCall(EPSGetEigenpair(eps, i, &w, nullptr, xr, nullptr));
    PetscCall(EPSComputeError(eps, i, EPS_ERROR_RELATIVE, &err));
    // An eigenpair that did not converge (rigid-body modes of a mechanism:
    // a singular stiffness) must not be reported as a frequency. The relative
    // residual |A x - w B x| / |w x| of a low mode of a stiff, fine mesh sits
    // at a round-off floor of order eps |A| / w (2.7e-6 was seen for a 12 Hz
    // mode at 32 elements per boom), so a clearly positive eigenvalue whose
    // backward error is at round-off level is accepted as well.
    PetscReal backward;
    PetscCall(EPSComputeError(eps, i, EPS_ERROR_BACKWARD, &backward));
    const bool converged = err < 1e-6 || (backward < 1e-10 && w > 1e-2);
    // A model error found by the analysis: reported like the user errors (one line, no location).
    PetscCheck(converged, assembler.comm(), PETSC_ERR_NOT_CONVERGED,
               "eigen-analysis: eigenpair %" PetscInt_FMT " (%.3g rad^2/s^2) did not converge (relative residual %.3g): "
               "the stiffness is singular, the system is a mechanism with rigid-body modes (a body or motion without "
               "support)", (PetscInt)(k + 1), (double)w, (double)err);
    if (options.keepVectors) {
      PetscHandle<Vec> v;
      PetscCall(VecDuplicate(xr, v.address()));
      PetscCall(VecCopy(xr, v));
      PetscCall(assembler.copyMultipliers(zero, v, 0.0)); // shape only: drop the multiplier part
      result->vectors.push_back(std::move(v));
    }
    result->omega2.push_back(w);
    result->frequencyHz.push_back(std::sqrt(std::max(w, 0.0)) / (2.0 * M_PI));
    result->residuals.push_back(err);
    std::vector<double> shape;
    PetscCall(scatterValues(toZero, xr, gathered, shape));
    if (rank == 0) {
      shape.resize(nq); // coordinates only
      // Sign and scale fixed so that runs on any rank count compare directly.
      double big = 0;
      for (double s : shape)
        if (std::abs(s) > std::abs(big)) big = s;
      if (big != 0)
        for (double &s : shape) s /= big;
      result->shapes.push_back(std::move(shape));
    }
  }
  PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
