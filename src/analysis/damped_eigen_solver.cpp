#include "boomdyn/damped_eigen_solver.hpp"

#include "boomdyn/direct_solver.hpp"
#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/gather.hpp"
#include "boomdyn/log_events.hpp"
#include "boomdyn/petsc_handle.hpp"

#include <slepcpep.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>

namespace boomdyn {

template <>
struct PetscDestroyer<PEP> {
  static PetscErrorCode destroy(PEP *pep) { return PEPDestroy(pep); }
};

PetscErrorCode assembleDamping(Assembler &assembler, double t, Vec q, Vec lambda, Mat D, double sigma)
{
  PetscHandle<Vec> x, vc;
  PetscFunctionBeginUser;
  PetscCall(assembler.createVector(x.address()));
  PetscCall(pencilState(assembler, q, lambda, x, &sigma));
  // q = x (cQ = 0) and v = vc + x = 0 with vc = -x: D is taken at rest, the
  // state about which the modes are defined. First-order states keep a zero
  // rate (cZ = 0, vc = 0 there).
  PetscCall(VecDuplicate(x, vc.address()));
  PetscCall(VecCopy(x, vc));
  PetscCall(VecScale(vc, -1.0));
  {
    PetscInt lo, hi;
    PetscCall(VecGetOwnershipRange(vc, &lo, &hi));
    for (PetscInt i : assembler.model().firstOrderCoordinates())
      if (i >= lo && i < hi) PetscCall(VecSetValue(vc, i, 0.0, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(vc));
    PetscCall(VecAssemblyEnd(vc));
  }
  AssemblyContext ctx;
  ctx.t = t;
  ctx.sigma = sigma;
  ctx.kin = {0.0, 1.0, 0.0, 0.0};
  ctx.pencil = true;
  ctx.constraintBlocks = false; // same pattern as the pencil, zeros in the constraint blocks
  PetscCall(assembler.setOffsets(x, vc, nullptr));
  PetscCall(assembler.evaluate(ctx, x, nullptr, D));
  PetscCall(assembler.setOffsets(x, nullptr, nullptr)); // as assemblePencil leaves them
  PetscFunctionReturn(0);
}

namespace {

struct Candidate {
  PetscInt index;
  double re, im;
};

// Modes among the converged eigenvalues: finite (an infinite eigenvalue of
// the constraint rows maps to an operator eigenvalue theta = 1/(lambda -
// target) at round-off level against the largest |theta|), oscillating
// (|Im| above round-off of |lambda|), and the member of its conjugate pair
// with Im > 0; ascending |lambda| (the undamped-equivalent frequency). Not by
// omega_d: shift-and-invert about a target near 0 finds the eigenvalues of
// smallest |lambda| first, so only this order is complete; a heavily damped
// mode can have a small omega_d and a large |lambda| (seen: zeta = 0.999999,
// |lambda| = 3.9e6 rad/s, omega_d = 4.7e3 rad/s, below modes of lower
// |lambda|, and not reproducible between rank counts: a near-double real
// eigenvalue split by round-off).
// keepReal (modal analyses): a real eigenvalue is an overdamped motion, not
// a failure, and is kept (Im set to 0); so is a near-real one, |Im| <= 1e-6
// |lambda|: a double real eigenvalue (critical damping) is split by
// round-off into a conjugate pair of Im ~ sqrt(eps) |lambda| (seen:
// zeta = 0.999999 reported as oscillating).
std::vector<Candidate> acceptModes(const std::vector<double> &re, const std::vector<double> &im, double target,
                                   bool keepReal, int *dropped)
{
  double thetaMax = 0;
  for (std::size_t i = 0; i < re.size(); ++i)
    if (std::isfinite(re[i]) && std::isfinite(im[i]))
      thetaMax = std::max(thetaMax, 1.0 / std::abs(std::complex<double>(re[i] - target, im[i])));
  std::vector<Candidate> modes;
  *dropped = 0;
  for (std::size_t i = 0; i < re.size(); ++i) {
    const std::complex<double> l(re[i], im[i]);
    const bool finite = std::isfinite(re[i]) && std::isfinite(im[i]) &&
                        1.0 / std::abs(l - target) >= 1e-12 * thetaMax;
    if (finite && keepReal && std::abs(im[i]) <= 1e-6 * std::abs(l)) {
      modes.push_back({(PetscInt)i, re[i], 0.0});
      continue;
    }
    if (!finite || !(std::abs(im[i]) > 1e-10 * std::abs(l))) {
      ++*dropped;
      continue;
    }
    if (im[i] > 0) modes.push_back({(PetscInt)i, re[i], im[i]});
  }
  std::sort(modes.begin(), modes.end(), [](const Candidate &a, const Candidate &b) { return std::hypot(a.re, a.im) < std::hypot(b.re, b.im); });
  return modes;
}

// x^H A y for complex x = xr + i xi and y = A x computed from real parts.
PetscErrorCode hermitianForm(Mat A, Vec xr, Vec xi, Vec work, std::complex<double> *value)
{
  PetscScalar rr, ii, ri, ir;
  PetscFunctionBeginUser;
  PetscCall(MatMult(A, xr, work));
  PetscCall(VecDot(work, xr, &rr));  // xr . A xr
  PetscCall(VecDot(work, xi, &ir));  // xi . A xr
  PetscCall(MatMult(A, xi, work));
  PetscCall(VecDot(work, xi, &ii));  // xi . A xi
  PetscCall(VecDot(work, xr, &ri));  // xr . A xi
  // (xr - i xi)^T A (xr + i xi) = xr A xr + xi A xi + i (xr A xi - xi A xr)
  *value = std::complex<double>(rr + ii, ri - ir);
  PetscFunctionReturn(0);
}

// The root of x^H P(lambda) x = 0 nearest *lambda (ops = {K, D, M}).
PetscErrorCode quadraticRayleighQuotient(Mat ops[3], Vec xr, Vec xi, std::complex<double> *lambda)
{
  PetscHandle<Vec> work;
  std::complex<double> c, b, a;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(xr, work.address()));
  PetscCall(hermitianForm(ops[0], xr, xi, work, &c));
  PetscCall(hermitianForm(ops[1], xr, xi, work, &b));
  PetscCall(hermitianForm(ops[2], xr, xi, work, &a));
  if (std::abs(a) == 0) PetscFunctionReturn(0);
  const std::complex<double> root = std::sqrt(b * b - 4.0 * a * c);
  const std::complex<double> r1 = (-b + root) / (2.0 * a), r2 = (-b - root) / (2.0 * a);
  const std::complex<double> nearest = std::abs(r1 - *lambda) < std::abs(r2 - *lambda) ? r1 : r2;
  // Only a correction: a quotient far off (a vector dominated by the
  // multiplier part) keeps the computed value.
  if (std::isfinite(nearest.real()) && std::isfinite(nearest.imag()) && std::abs(nearest - *lambda) < 1e-6 * std::abs(*lambda))
    *lambda = nearest;
  PetscFunctionReturn(0);
}

// As in solveModes: SLEPc's basic stopping test, then the caller's stop().
struct StopRequest {
  const std::function<bool()> *stop;
  bool stopped = false;
};

PetscErrorCode stopOnRequest(PEP pep, PetscInt its, PetscInt maxIts, PetscInt nconv, PetscInt nev,
                             PEPConvergedReason *reason, void *context)
{
  auto *request = static_cast<StopRequest *>(context);
  PetscFunctionBeginUser;
  PetscCall(PEPStoppingBasic(pep, its, maxIts, nconv, nev, reason, nullptr));
  if (*reason == PEP_CONVERGED_ITERATING && (*request->stop)()) {
    request->stopped = true;
    *reason = PEP_CONVERGED_USER;
  }
  PetscFunctionReturn(0);
}

// One undamped mode x0 = [phi | 0] (multiplier part dropped) tried as an
// eigenvector of the quadratic problem: classical damping (stiffness- or
// mass-proportional, Rayleigh) leaves it one, with the roots of the scalar
// quadratic mass lambda^2 + damping lambda + stiffness = 0 (x0's Rayleigh
// forms). The multiplier part of the damped eigenvector is a multiple s of
// the undamped one (for D = eta K: s = 1 + eta lambda); its force
// c = sigma C^T mu = omega^2 M x0 - K x0 (q rows) enters the residual with
// the s of least squares. residual: the worse root's
// ||T(lambda) x|| / (||K x|| + |lambda| ||D x|| + |lambda|^2 ||M x||), the
// backward error of the pair in the full problem, computed from the vectors
// (a Gram-matrix form would stop at sqrt(eps)).
struct ClassicalMode {
  double mass = 0, damping = 0, stiffness = 0;
  double residual = 0;
};

std::array<std::complex<double>, 2> quadraticRoots(double m, double d, double k)
{
  const double disc = d * d - 4 * m * k;
  if (disc < 0) {
    const std::complex<double> l(-d / (2 * m), std::sqrt(-disc) / (2 * m));
    return {l, std::conj(l)};
  }
  // Real roots without cancellation: the larger in magnitude first, the
  // other from the product k / m.
  const double big = -(d + std::sqrt(disc)) / (2 * m);
  return {big != 0 ? std::complex<double>(k / (m * big)) : 0.0, big};
}

PetscErrorCode classicalMode(Mat K, Mat D, Mat M, Vec x0, double omega2, ClassicalMode *out)
{
  PetscHandle<Vec> a, dv, mv, c, rr, ri;
  PetscScalar ca, cd, cm, cc;
  PetscFunctionBeginUser;
  for (PetscHandle<Vec> *v : {&a, &dv, &mv, &c, &rr, &ri}) PetscCall(VecDuplicate(x0, v->address()));
  PetscCall(MatMult(K, x0, a));
  PetscCall(MatMult(D, x0, dv));
  PetscCall(MatMult(M, x0, mv));
  PetscCall(VecDot(x0, mv, &out->mass));
  PetscCall(VecDot(x0, dv, &out->damping));
  PetscCall(VecDot(x0, a, &out->stiffness));
  PetscCall(VecAXPBYPCZ(c, omega2, -1.0, 0.0, mv, a)); // c = omega2 M x0 - K x0
  PetscCall(VecDot(c, a, &ca));
  PetscCall(VecDot(c, dv, &cd));
  PetscCall(VecDot(c, mv, &cm));
  PetscCall(VecDot(c, c, &cc));
  PetscReal na, nd, nm, nc;
  PetscCall(VecNorm(a, NORM_2, &na));
  PetscCall(VecNorm(dv, NORM_2, &nd));
  PetscCall(VecNorm(mv, NORM_2, &nm));
  PetscCall(VecNorm(c, NORM_2, &nc));
  out->residual = 0;
  for (const std::complex<double> &l : quadraticRoots(out->mass, out->damping, out->stiffness)) {
    const std::complex<double> l2 = l * l;
    const std::complex<double> s = cc > 0 ? -(ca + l * cd + l2 * cm) / cc : 0.0;
    // r = K x0 + lambda D x0 + lambda^2 M x0 + s c, real and imaginary parts.
    PetscCall(VecCopy(a, rr));
    PetscCall(VecAXPBYPCZ(rr, l.real(), l2.real(), 1.0, dv, mv));
    PetscCall(VecAXPY(rr, s.real(), c));
    PetscCall(VecAXPBYPCZ(ri, l.imag(), l2.imag(), 0.0, dv, mv));
    PetscCall(VecAXPY(ri, s.imag(), c));
    PetscReal nr, ni;
    PetscCall(VecNorm(rr, NORM_2, &nr));
    PetscCall(VecNorm(ri, NORM_2, &ni));
    // ||K x|| of x = [phi | s mu]: K x = a + s c.
    const double kx = std::abs(s) * nc + na;
    const double scale = kx + std::abs(l) * nd + std::norm(l) * nm;
    out->residual = std::max(out->residual, scale > 0 ? std::hypot(nr, ni) / scale : 0.0);
  }
  PetscFunctionReturn(0);
}

// The damped modes of the undamped ones when every one of them is an
// eigenvector of the quadratic problem to 1e-8 (*classical); otherwise
// nothing is filled.
PetscErrorCode classicalDampedModes(Mat K, Mat D, Mat M, const ModalResult &undamped, int count,
                                    DampedModalResult *result, bool *classical)
{
  std::vector<ClassicalMode> modes(count);
  PetscFunctionBeginUser;
  *classical = false;
  if ((int)undamped.vectors.size() < count) PetscFunctionReturn(0);
  for (int k = 0; k < count; ++k) {
    PetscCall(classicalMode(K, D, M, undamped.vectors[k], undamped.omega2[k], &modes[k]));
    if (!(modes[k].residual <= 1e-8) || !(modes[k].mass > 0) || !(modes[k].stiffness >= 0))
      PetscFunctionReturn(0);
  }
  *classical = true;
  *result = DampedModalResult{};
  result->classical = true;
  for (const ClassicalMode &c : modes) {
    const double m = c.mass, d = c.damping, k = c.stiffness;
    const double omega = std::sqrt(k / m), disc = d * d - 4 * m * k;
    result->omega.push_back(omega);
    result->dampingRatio.push_back(omega > 0 ? d / (2 * std::sqrt(m * k)) : std::nan(""));
    result->dampedOmega.push_back(disc < 0 ? std::sqrt(-disc) / (2 * m) : 0.0);
    const std::array<std::complex<double>, 2> roots = quadraticRoots(m, d, k);
    std::array<double, 2> rates{-roots[0].real(), -roots[1].real()};
    if (rates[0] > rates[1]) std::swap(rates[0], rates[1]);
    result->decayRates.push_back(rates);
    result->residuals.push_back(c.residual);
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode appendDampedMode(Assembler &assembler, std::complex<double> lambda, Vec xr, Vec xi, double residual,
                                bool keepVector, DampedModalResult *result)
{
  PetscMPIInt rank, size;
  std::vector<double> real, imag;
  PetscFunctionBeginUser;
  const double modulus = std::abs(lambda);
  result->dampedOmega.push_back(std::abs(lambda.imag()));
  result->omega.push_back(modulus);
  const bool isReal = lambda.imag() == 0;
  // A lone real eigenvalue (overdamped; its partner is not among those
  // reported): no damping ratio of its own.
  result->dampingRatio.push_back(isReal ? std::nan("") : -lambda.real() / modulus);
  result->decayRates.push_back(std::array<double, 2>{-lambda.real(), isReal ? std::nan("") : -lambda.real()});
  result->residuals.push_back(residual);
  if (keepVector) {
    PetscHandle<Vec> r, i;
    PetscCall(VecDuplicate(xr, r.address()));
    PetscCall(VecCopy(xr, r));
    PetscCall(VecDuplicate(xi, i.address()));
    PetscCall(VecCopy(xi, i));
    // One of the conjugate pair: the one with Im lambda > 0.
    if (lambda.imag() < 0) PetscCall(VecScale(i, -1.0));
    result->real.push_back(std::move(r));
    result->imag.push_back(std::move(i));
  }
  PetscCallMPI(MPI_Comm_rank(assembler.comm(), &rank));
  PetscCallMPI(MPI_Comm_size(assembler.comm(), &size));
  if (size == 1) {
    // All of x is local: no scatter (creating one per vector cost as much as
    // the rest of a refined damped analysis).
    const PetscScalar *a;
    PetscInt n;
    PetscCall(VecGetLocalSize(xr, &n));
    PetscCall(VecGetArrayRead(xr, &a));
    real.assign(a, a + n);
    PetscCall(VecRestoreArrayRead(xr, &a));
    PetscCall(VecGetArrayRead(xi, &a));
    imag.assign(a, a + n);
    PetscCall(VecRestoreArrayRead(xi, &a));
  } else {
    PetscCall(gatherToZero(xr, real));
    PetscCall(gatherToZero(xi, imag));
  }
  if (rank == 0) {
    // The phase is free: rotate the vector so that its largest entry is
    // real, then keep the real part (independent of the rank count and of
    // the complex scale of the vector).
    const std::size_t nq = (std::size_t)assembler.model().numCoordinates();
    // Largest by the squared modulus (hypot per entry cost about a tenth of
    // a refined damped analysis on the paper scene).
    std::size_t big = 0;
    double largest = -1;
    for (std::size_t i = 0; i < nq; ++i) {
      const double modulus2 = real[i] * real[i] + imag[i] * imag[i];
      if (modulus2 > largest) largest = modulus2, big = i;
    }
    const double phase = std::atan2(imag[big], real[big]);
    std::vector<double> shape(nq);
    for (std::size_t i = 0; i < nq; ++i) shape[i] = real[i] * std::cos(phase) + imag[i] * std::sin(phase);
    normalizeShape(shape);
    result->shapes.push_back(std::move(shape));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode solveDampedModes(Assembler &assembler, double t, Vec q, Vec lambda, int count,
                                DampedModalResult *result, const DampedModalOptions &options)
{
  PetscHandle<Mat> K, D, M;
  PetscHandle<Vec> vr, vi;
  PetscHandle<PEP> pep;
  ST st;
  KSP ksp;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().eigen, 0, 0, 0, 0));
  PetscCall(assembler.createMatrix(K.address()));
  PetscCall(assembler.createMatrix(D.address()));
  PetscCall(assembler.createMatrix(M.address()));
  PetscCall(assembleDamping(assembler, t, q, lambda, D));
  PetscCall(assemblePencil(assembler, t, q, lambda, K, M));

  // 2 nf finite eigenvalues (nf as in the symmetric pencil); the Krylov
  // subspace of the linearization must not exceed them (see solveModes).
  const PetscInt finiteBound = finiteModeBound(assembler.model());
  PetscCheck(count <= finiteBound, assembler.comm(), PETSC_ERR_USER_INPUT,
             "damped eigen-analysis: %d modes requested, but the model has at most %" PetscInt_FMT
             " finite modes; ask for fewer modes (modal: count, tracking: count)",
             count, finiteBound);

  Mat ops[3] = {K, D, M};
  if (options.undamped && !options.allowFewer) {
    // Classical damping: the damped versions of the undamped modes, no PEP
    // solve (heavy damping puts the slow real eigenvalues of every higher
    // mode into a cluster at -1/eta, of smallest |lambda|, where PEP ran
    // into thousands of near-equal eigenvalues on fine meshes).
    bool classical;
    PetscCall(classicalDampedModes(K, D, M, *options.undamped, count, result, &classical));
    if (classical) {
      result->shapes = options.undamped->shapes;
      if (options.keepVectors)
        for (int k = 0; k < count; ++k) {
          PetscHandle<Vec> r, i;
          PetscCall(VecDuplicate(options.undamped->vectors[k], r.address()));
          PetscCall(VecCopy(options.undamped->vectors[k], r));
          PetscCall(VecDuplicate(r, i.address()));
          PetscCall(VecSet(i, 0.0));
          result->real.push_back(std::move(r));
          result->imag.push_back(std::move(i));
        }
      PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(PEPCreate(assembler.comm(), pep.address()));
  PetscCall(PEPSetOptionsPrefix(pep, "modal_"));
  PetscCall(PEPSetOperators(pep, 3, ops));
  PetscCall(PEPSetProblemType(pep, PEP_GENERAL));
  PetscCall(PEPSetType(pep, PEPTOAR));
  PetscCall(PEPSetTolerances(pep, 1e-12, 500));
  PetscCall(PEPSetTarget(pep, options.target));
  PetscCall(PEPSetWhichEigenpairs(pep, PEP_TARGET_MAGNITUDE));
  PetscCall(PEPGetST(pep, &st));
  PetscCall(STSetType(st, STSINVERT));
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(useAnalysisDirectSolver(ksp));
  StopRequest request{&options.stop};
  if (options.stop) PetscCall(PEPSetStoppingTestFunction(pep, stopOnRequest, &request, nullptr));

  std::vector<Candidate> modes;
  std::vector<double> re, im;
  for (PetscInt nev = 2 * count;;) {
    const PetscInt ncv = std::max(std::min(std::max(2 * nev, nev + 15), 2 * finiteBound), nev + 1);
    PetscCall(PEPSetDimensions(pep, nev, ncv, PETSC_DEFAULT));
    PetscCall(PEPSetFromOptions(pep));
    if (options.stop && !request.stopped && options.stop()) request.stopped = true;
    if (!request.stopped) PetscCall(PEPSolve(pep));
    if (request.stopped) {
      *result = DampedModalResult{};
      result->interrupted = true;
      PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
      PetscFunctionReturn(0);
    }
    PetscInt nconv;
    PetscCall(PEPGetConverged(pep, &nconv));
    re.assign(nconv, 0.0);
    im.assign(nconv, 0.0);
    for (PetscInt i = 0; i < nconv; ++i) PetscCall(PEPGetEigenpair(pep, i, &re[i], &im[i], nullptr, nullptr));
    int dropped;
    modes = acceptModes(re, im, options.target, !options.allowFewer, &dropped);
    if ((PetscInt)modes.size() >= count || options.allowFewer) break;
    PetscCheck(nev < 2 * finiteBound, assembler.comm(), PETSC_ERR_NOT_CONVERGED,
               "damped eigen-analysis: only %zu modes of %d requested were found (%" PetscInt_FMT
               " eigenvalues converged, %d infinite or non-oscillating)",
               modes.size(), count, nconv, dropped);
    nev = std::min(2 * finiteBound, nev + 2 * (count - (PetscInt)modes.size()) + 2);
  }

  PetscCall(MatCreateVecs(K, vr.address(), nullptr));
  PetscCall(VecDuplicate(vr, vi.address()));
  *result = DampedModalResult{};
  for (int k = 0, found = 0; k < (int)modes.size() && found < count; ++k) {
    const Candidate &c = modes[k];
    PetscScalar kr, ki;
    PetscReal err;
    PetscCall(PEPGetEigenpair(pep, c.index, &kr, &ki, vr, vi));
    PetscCall(PEPComputeError(pep, c.index, PEP_ERROR_BACKWARD, &err));
    if (options.allowFewer && !(err < 1e-8)) continue;
    ++found;
    // Refined by the quadratic Rayleigh quotient: the root of
    // x^H (lambda^2 M + lambda D + K) x = 0 nearest the computed lambda. Its
    // error is of the order of the squared eigenvector error, while the
    // value from the transformed problem differed by up to 1.7e-10 relative
    // between 1 and 2 ranks (as in solveModes).
    std::complex<double> lambdaPair(c.re, c.im);
    if (c.im != 0) PetscCall(quadraticRayleighQuotient(ops, vr, vi, &lambdaPair)); // a real one stays real
    const double modulus = std::abs(lambdaPair);
    PetscCheck(err < 1e-8, assembler.comm(), PETSC_ERR_NOT_CONVERGED,
               "damped eigen-analysis: mode %d (%.6g rad/s) did not converge (backward error %.3g)", k + 1, modulus,
               (double)err);
    PetscCall(appendDampedMode(assembler, lambdaPair, vr, vi, err, options.keepVectors, result));
  }
  PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
