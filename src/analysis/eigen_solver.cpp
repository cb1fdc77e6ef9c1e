#include "boomdyn/eigen_solver.hpp"

#include "boomdyn/gather.hpp"

#include "boomdyn/direct_solver.hpp"

#include "boomdyn/log_events.hpp"

#include <slepceps.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

namespace boomdyn {

template <>
struct PetscDestroyer<EPS> {
  static PetscErrorCode destroy(EPS *eps) { return EPSDestroy(eps); }
};

namespace {

// Which converged pairs are modes, in ascending order of omega^2. Rejected,
// each with a reason: a non-finite omega^2; an infinite eigenvalue of the
// constraint rows that leaked through the transform (its operator eigenvalue
// theta = 1/(omega^2 - target) is at round-off level against the largest
// |theta|, i.e. |omega^2| ~ 1e36); a clearly negative omega^2 (below
// -1e-8 of the largest accepted one: rigid-body modes at round-off level stay).
std::vector<PetscInt> acceptFinitePairs(const std::vector<PetscScalar> &values, double target,
                                        std::vector<std::string> *rejected)
{
  double thetaMax = 0;
  for (PetscScalar w : values)
    if (std::isfinite(w) && w != target) thetaMax = std::max(thetaMax, 1.0 / std::abs(w - target));
  std::vector<PetscInt> finite;
  double scale = 0;
  char line[256];
  for (PetscInt i = 0; i < (PetscInt)values.size(); ++i) {
    const double w = values[i];
    if (!std::isfinite(w)) {
      std::snprintf(line, sizeof line, "eigenvalue %g is not finite", w);
      rejected->push_back(line);
    } else if (w != target && 1.0 / std::abs(w - target) < 1e-12 * thetaMax) {
      std::snprintf(line, sizeof line,
                    "omega^2 = %.3g rad^2/s^2 is an infinite eigenvalue of the constraint rows (spurious)", w);
      rejected->push_back(line);
    } else {
      finite.push_back(i);
      scale = std::max(scale, w);
    }
  }
  std::vector<PetscInt> order;
  for (PetscInt i : finite) {
    if (values[i] < -1e-8 * scale) {
      std::snprintf(line, sizeof line,
                    "omega^2 = %.6g rad^2/s^2 is negative: the state is not a stable equilibrium (or the pair is "
                    "spurious)", (double)values[i]);
      rejected->push_back(line);
    } else {
      order.push_back(i);
    }
  }
  std::sort(order.begin(), order.end(), [&](PetscInt a, PetscInt b) { return values[a] < values[b]; });
  return order;
}

// The first five rejections of a process: tracking analyses many states.
PetscErrorCode reportRejected(MPI_Comm comm, const std::string &why)
{
  static int reported = 0;
  PetscFunctionBeginUser;
  if (reported++ < 5)
    PetscCall(PetscPrintf(comm, "warning: eigen-analysis: pair not reported as a mode: %s%s\n", why.c_str(),
                          reported == 5 ? " (further rejections not shown)" : ""));
  PetscFunctionReturn(0);
}

// SLEPc's stopping test with an interrupt: the basic test, then the caller's
// stop() (SIGINT/SIGTERM), so that a long solve ends within one iteration
// instead of after it (issue 40). EPS_CONVERGED_USER ends EPSSolve normally.
struct StopRequest {
  const std::function<bool()> *stop;
  bool stopped = false;
};

PetscErrorCode stopOnRequest(EPS eps, PetscInt its, PetscInt maxIts, PetscInt nconv, PetscInt nev,
                             EPSConvergedReason *reason, void *context)
{
  auto *request = static_cast<StopRequest *>(context);
  PetscFunctionBeginUser;
  PetscCall(EPSStoppingBasic(eps, its, maxIts, nconv, nev, reason, nullptr));
  if (*reason == EPS_CONVERGED_ITERATING && (*request->stop)()) {
    request->stopped = true;
    *reason = EPS_CONVERGED_USER;
  }
  PetscFunctionReturn(0);
}

// Relative residuals of a pair at the round-off floor of the pencil (see
// solveModes): above kFloorWarned the run is told the frequency is uncertain
// by about that much; above kFloorRefused the analysis stops.
constexpr double kFloorWarned = 1e-5, kFloorRefused = 1e-2;

// The finest beam mesh of the model, for the messages about the floor: the
// beam whose element bending frequency sqrt(EI / rhoA) / l^2 is highest
// (the stiffest element modes set the floor).
std::string finestMesh(const Model &model)
{
  const BodySpec *finest = nullptr;
  double highest = 0;
  for (const BodySpec &b : model.scene().bodies) {
    if (b.type != BodySpec::Type::AncfBeam || !(b.section.rhoA > 0) || b.elements < 1) continue;
    const double l = b.length / b.elements, w = std::sqrt(b.section.EI / b.section.rhoA) / (l * l);
    if (!finest || w > highest) finest = &b, highest = w;
  }
  if (!finest) return "the pencil is ill-conditioned";
  char text[256];
  std::snprintf(text, sizeof text,
                "the mesh is too fine for double precision: body '%s' has %d elements of %.3g m (the floor grows about "
                "like the 3.5th power of the element count)",
                finest->name.c_str(), finest->elements, finest->length / finest->elements);
  return text;
}

// The first five pairs of a process accepted at a floor above kFloorWarned.
PetscErrorCode reportFloor(MPI_Comm comm, int mode, double hz, double residual, const std::string &mesh)
{
  static int reported = 0;
  PetscFunctionBeginUser;
  if (reported++ < 5)
    PetscCall(PetscPrintf(comm,
                          "warning: eigen-analysis: mode %d (%.6g Hz) lies at the round-off floor of the pencil "
                          "(relative residual %.2g): its frequency may be off by several times that; %s%s\n",
                          mode, hz, residual, mesh.c_str(), reported == 5 ? " (further warnings not shown)" : ""));
  PetscFunctionReturn(0);
}

} // namespace

PetscInt finiteModeBound(const Model &model)
{
  return model.numCoordinates() - model.numMultipliers() - static_cast<PetscInt>(model.firstOrderCoordinates().size());
}

PetscErrorCode pencilState(Assembler &assembler, Vec q, Vec lambda, Vec x, double *sigmaOut)
{
  const PetscInt nq = assembler.model().numCoordinates();
  PetscFunctionBeginUser;
  // x = [q | lambda / sigma]. The constraint blocks are scaled by sigma, a
  // typical stiffness diagonal: with sigma = 1 they are ~1e-9 of K for steel
  // booms and MUMPS's threshold pivoting declares A - target B singular.
  // The eigenvalues do not depend on sigma.
  double sigma = *sigmaOut;
  if (!(sigma > 0)) {
    PetscReal massScale, stiffScale;
    // The scales at q itself: characteristicScales gathers q through the
    // offsets (qc + x), and whatever ran last may have left them nonzero
    // (an eigen-analysis' own passes leave qc = its state). The pencil's
    // passes set their own offsets, so clearing them here changes nothing
    // else.
    PetscCall(assembler.setOffsets(nullptr, nullptr, nullptr));
    PetscCall(assembler.characteristicScales(q, &massScale, &stiffScale));
    sigma = stiffScale > 0 ? stiffScale : 1.0;
  }
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
  *sigmaOut = sigma;
  PetscFunctionReturn(0);
}

PetscErrorCode assemblePencil(Assembler &assembler, double t, Vec q, Vec lambda, Mat A, Mat B, double *sigmaOut,
                              Mat D, Vec work)
{
  PetscHandle<Vec> made;
  double sigma = 0; // computed by pencilState
  PetscFunctionBeginUser;
  if (!work) PetscCall(assembler.createVector(made.address()));
  Vec x = work ? work : made.get(); // pencilState writes all of it
  PetscCall(pencilState(assembler, q, lambda, x, &sigma));
  AssemblyContext ctx;
  ctx.t = t;
  ctx.sigma = sigma;
  // A, B (and D) in one pass over the items; B and D have A's pattern
  // (explicit zeros), so ST and the refinement can combine them cheaply.
  PetscCall(assembler.evaluatePencil(ctx, x, A, B, D));
  if (sigmaOut) *sigmaOut = sigma;
  PetscFunctionReturn(0);
}

void normalizeShape(std::vector<double> &shape)
{
  double big = 0;
  for (double s : shape)
    if (std::abs(s) > std::abs(big)) big = s;
  if (big != 0)
    for (double &s : shape) s /= big;
}

PetscErrorCode gatherShape(Assembler &assembler, Vec v, std::vector<double> *shape, ZeroGather *gather)
{
  ZeroGather once; // without a caller's gather: one for this call
  PetscFunctionBeginUser;
  // The coordinates only: the multipliers are not copied out.
  PetscCall((gather ? gather : &once)->gather(v, *shape, assembler.model().numCoordinates()));
  if (!shape->empty()) normalizeShape(*shape); // rank 0
  PetscFunctionReturn(0);
}

PetscErrorCode solveModes(Assembler &assembler, double t, Vec q, Vec lambda, int count, ModalResult *result,
                          const ModalOptions &options)
{
  const PetscInt nq = assembler.model().numCoordinates();
  // Owned by handles: an error (an eigenpair that did not converge) leaks nothing.
  PetscHandle<Mat> A, B;
  PetscHandle<Vec> xr, gathered, zero;
  PetscHandle<EPS> eps;
  PetscHandle<VecScatter> toZero;
  ST st;
  KSP ksp;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().eigen, 0, 0, 0, 0));
  PetscCall(assembler.createMatrix(A.address()));
  PetscCall(assembler.createMatrix(B.address()));
  PetscCall(assemblePencil(assembler, t, q, lambda, A, B));

  // Only finite eigenvalues are modes. The pencil has n - nf infinite ones
  // (a multiplier and the coordinate direction it fixes per constraint row,
  // and every first-order state), with nf = nq - nconstraint - nfirstorder.
  // Once the Krylov subspace is larger than nf, shift-and-invert can only
  // fill it with directions of those infinite eigenvalues (operator
  // eigenvalue theta = 0, shifted back to omega^2 ~ +-1e36), and such a pair
  // passes every residual test: seen on cantilevers of 2-3 elements, where
  // the default ncv = nev + 15 exceeds nf. So ncv <= nf (issue 13, item 3).
  const PetscInt finiteBound = finiteModeBound(assembler.model());
  PetscCheck(count <= finiteBound, assembler.comm(), PETSC_ERR_USER_INPUT,
             "eigen-analysis: %d modes requested, but the model has at most %" PetscInt_FMT
             " finite modes (%" PetscInt_FMT " coordinates - %" PetscInt_FMT " constraint rows - %" PetscInt_FMT
             " first-order states); ask for fewer modes (modal: count, tracking: count)",
             count, finiteBound, nq, assembler.model().numMultipliers(),
             static_cast<PetscInt>(assembler.model().firstOrderCoordinates().size()));

  PetscCall(EPSCreate(assembler.comm(), eps.address()));
  PetscCall(EPSSetOptionsPrefix(eps, "modal_"));
  PetscCall(EPSSetOperators(eps, A, B));
  PetscCall(EPSSetProblemType(eps, EPS_GHEP));
  PetscCall(EPSSetType(eps, EPSKRYLOVSCHUR));
  // B-orthogonal projection of the computed vectors (one more application
  // of the operator): removes what is left of the null space of B.
  PetscCall(EPSSetPurify(eps, PETSC_TRUE));
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
  PetscCall(useAnalysisDirectSolver(ksp));
  StopRequest request{&options.stop};
  if (options.stop) PetscCall(EPSSetStoppingTestFunction(eps, stopOnRequest, &request, nullptr));

  // Solve for nev pairs; keep the finite, non-negative ones; if fewer than
  // `count` remain, ask for more (never beyond nf).
  std::vector<PetscInt> order; // accepted pairs, ascending omega^2
  std::vector<PetscScalar> values;
  for (PetscInt nev = count;;) {
    // Krylov-Schur needs ncv > nev: with nev = nf one infinite direction
    // enters, and acceptFinitePairs() drops it.
    const PetscInt ncv = std::max(std::min(std::max(2 * nev, nev + 15), finiteBound), nev + 1);
    PetscCall(EPSSetDimensions(eps, nev, ncv, PETSC_DEFAULT));
    PetscCall(EPSSetFromOptions(eps));
    if (options.stop && !request.stopped && options.stop()) request.stopped = true;
    if (!request.stopped) PetscCall(EPSSolve(eps));
    if (request.stopped) {
      *result = ModalResult{};
      result->interrupted = true;
      PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
      PetscFunctionReturn(0);
    }
    PetscInt nconv;
    PetscCall(EPSGetConverged(eps, &nconv));
    PetscCheck(nconv >= count, assembler.comm(), PETSC_ERR_NOT_CONVERGED,
               "eigen-analysis: %" PetscInt_FMT " of %d eigenpairs converged", nconv, count);
    values.assign(nconv, 0.0);
    for (PetscInt i = 0; i < nconv; ++i) PetscCall(EPSGetEigenpair(eps, i, &values[i], nullptr, nullptr, nullptr));
    std::vector<std::string> rejected;
    order = acceptFinitePairs(values, options.target, &rejected);
    for (const std::string &why : rejected) PetscCall(reportRejected(assembler.comm(), why));
    if ((PetscInt)order.size() >= count) break;
    PetscCheck(nev < finiteBound, assembler.comm(), PETSC_ERR_NOT_CONVERGED,
               "eigen-analysis: only %zu finite, non-negative eigenvalues of %d requested were found (%zu rejected)",
               order.size(), count, rejected.size());
    nev = std::min(finiteBound, nev + count - (PetscInt)order.size() + 1);
  }

  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(assembler.comm(), &rank));
  PetscCall(MatCreateVecs(A, xr.address(), nullptr));
  PetscCall(VecScatterCreateToZero(xr, toZero.address(), gathered.address()));
  *result = ModalResult{};
  PetscCall(VecDuplicate(xr, zero.address()));
  PetscCall(VecSet(zero, 0.0));
  double sharesSigma = 0; // the constraint scale of the labels' state, computed by the first mode's
  for (int k = 0; k < count; ++k) {
    const PetscInt i = order[k];
    PetscScalar w;
    PetscReal err;
    PetscCall(EPSGetEigenpair(eps, i, &w, nullptr, xr, nullptr));
    PetscCall(EPSComputeError(eps, i, EPS_ERROR_RELATIVE, &err));
    {
      // The Rayleigh quotient of the (purified) vector on the pencil itself:
      // its error is of the order of the squared residual, while the value
      // SLEPc maps back from the shift-and-invert operator moved by up to
      // 2e-8 relative (the low mode of the paper scene on 2 ranks, 6 pairs
      // against 4), which the refined tracking could then not match.
      PetscScalar xax, xbx;
      PetscCall(MatMult(A, xr, zero));
      PetscCall(VecDot(xr, zero, &xax));
      PetscCall(MatMult(B, xr, zero));
      PetscCall(VecDot(xr, zero, &xbx));
      PetscCall(VecSet(zero, 0.0));
      const double rq = xax / xbx;
      if (xbx > 0 && std::isfinite(rq)) w = rq;
    }
    // An eigenpair that did not converge (rigid-body modes of a mechanism:
    // a singular stiffness) must not be reported as a frequency. The relative
    // residual |A x - w B x| / |w x| of a low mode of a fine mesh sits at the
    // round-off floor of the pencil (backward error at round-off level): the
    // stiffest element modes, whose omega^2 grows like the 4th power of the
    // element count, swamp the low ones in double precision, and the
    // eigenvalue's error follows the residual (measured on the 2 m
    // cantilever, docs/model.md §5: frequency error 0.5-3 times the residual,
    // the residual growing about like the 3.5th power of the element count;
    // 2.7e-6 was seen for a 12 Hz mode at 32 elements per boom). Such a pair
    // is kept up to kFloorRefused, with a warning above kFloorWarned; above it
    // the frequency is not determined and the analysis stops, saying so.
    PetscReal backward;
    PetscCall(EPSComputeError(eps, i, EPS_ERROR_BACKWARD, &backward));
    const bool atFloor = backward < 1e-10;
    const bool converged = err < 1e-6 || (atFloor && w > 1e-2 && err <= kFloorRefused);
    // A value well away from 0 (residual below the value itself) that is not
    // determined: the mesh, not a mechanism.
    PetscCheck(converged || !atFloor || !(err < 1.0), assembler.comm(), PETSC_ERR_NOT_CONVERGED,
               "eigen-analysis: eigenpair %" PetscInt_FMT " (omega^2 = %.4g rad^2/s^2) is not determined in double "
               "precision: its relative residual %.3g is the round-off floor of the pencil (backward error %.1e), and "
               "the frequency can be off by several times that: %s; use fewer elements (docs/model.md §5)",
               (PetscInt)(k + 1), (double)w, (double)err, (double)backward,
               finestMesh(assembler.model()).c_str());
    // A model error found by the analysis: reported like the user errors (one line, no location).
    PetscCheck(converged, assembler.comm(), PETSC_ERR_NOT_CONVERGED,
               "eigen-analysis: eigenpair %" PetscInt_FMT " (%.3g rad^2/s^2) did not converge (relative residual %.3g): "
               "the stiffness is singular, the system is a mechanism with rigid-body modes (a body or motion without "
               "support)%s", (PetscInt)(k + 1), (double)w, (double)err,
               atFloor ? (" (or the pencil's round-off floor hides the lowest modes: " + finestMesh(assembler.model()) + ")").c_str() : "");
    if (err > kFloorWarned)
      PetscCall(reportFloor(assembler.comm(), (int)k + 1, std::sqrt(std::max(w, 0.0)) / (2 * M_PI), err,
                            finestMesh(assembler.model())));
    if (options.keepVectors) {
      PetscHandle<Vec> v;
      PetscCall(VecDuplicate(xr, v.address()));
      PetscCall(VecCopy(xr, v));
      PetscCall(assembler.copyMultipliers(zero, v, 0.0)); // shape only: drop the multiplier part
      result->vectors.push_back(std::move(v));
    }
    if (options.energyShares) {
      EnergyShares shares;
      PetscCall(modeEnergyShares(assembler, t, q, lambda, xr, &shares, &sharesSigma));
      result->energyShares.push_back(shares);
    }
    result->omega2.push_back(w);
    result->frequencyHz.push_back(std::sqrt(std::max(w, 0.0)) / (2.0 * M_PI));
    result->residuals.push_back(err);
    std::vector<double> shape;
    PetscCall(scatterValues(toZero, xr, gathered, shape));
    if (rank == 0) {
      shape.resize(nq); // coordinates only
      normalizeShape(shape);
      result->shapes.push_back(std::move(shape));
    }
  }
  PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
