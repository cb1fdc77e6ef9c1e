#include "boomdyn/damped_mode_refinement.hpp"

#include "boomdyn/log_events.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <complex>

namespace boomdyn {

namespace {


// The multiplier part of a Ritz vector. The subspace vectors satisfy the
// constraints (C v_q = 0), so their multiplier parts drop out of the
// projected matrices and x_mu = V_mu y is arbitrary. It is set instead to the
// least-squares multipliers of the residual: T(lambda) e_i = K e_i = c_i for
// a unit multiplier e_i (D and M vanish there), so adding sum a_i e_i to x
// adds sum a_i c_i to r; a = -(c^T c)^+ c^T r minimizes ||r||. For the exact
// q part this is the exact multiplier part.
struct MultiplierFit {
  std::vector<PetscHandle<Vec>> c; // K e_i
  std::vector<Vec> raw;            // the same vectors, for VecMDot/VecMAXPY
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> gram;
  PetscInt nq = 0;

  PetscErrorCode setUp(Mat K, Vec layout, PetscInt coordinates, PetscInt multipliers)
  {
    PetscHandle<Vec> e;
    PetscInt lo, hi;
    PetscFunctionBeginUser;
    nq = coordinates;
    c.clear();
    PetscCall(VecDuplicate(layout, e.address()));
    PetscCall(VecGetOwnershipRange(e, &lo, &hi));
    for (PetscInt i = 0; i < multipliers; ++i) {
      PetscHandle<Vec> ci;
      PetscCall(VecSet(e, 0.0));
      if (nq + i >= lo && nq + i < hi) PetscCall(VecSetValue(e, nq + i, 1.0, INSERT_VALUES));
      PetscCall(VecAssemblyBegin(e));
      PetscCall(VecAssemblyEnd(e));
      PetscCall(VecDuplicate(layout, ci.address()));
      PetscCall(MatMult(K, e, ci));
      c.push_back(std::move(ci));
    }
    raw.assign(c.begin(), c.end());
    Eigen::MatrixXd G(multipliers, multipliers);
    std::vector<PetscScalar> dots(c.size());
    for (PetscInt j = 0; j < multipliers; ++j) {
      PetscCall(VecMDot(c[j], multipliers, raw.data(), dots.data()));
      for (PetscInt i = 0; i < multipliers; ++i) G(i, j) = dots[i];
    }
    gram.compute(G);
    PetscFunctionReturn(0);
  }

  // v <- v + sum a_i c_i with a = -(c^T c)^+ c^T v: what is left of v after
  // its least-squares part in the span of the c_i; the a_i into *a.
  PetscErrorCode subtractRange(Vec v, Eigen::VectorXd *a) const
  {
    const PetscInt m = (PetscInt)raw.size();
    std::vector<PetscScalar> dots(m);
    PetscFunctionBeginUser;
    PetscCall(VecMDot(v, m, raw.data(), dots.data()));
    *a = -gram.solve(Eigen::Map<const Eigen::VectorXd>(dots.data(), m));
    for (PetscInt i = 0; i < m; ++i) dots[i] = (*a)[i];
    // PETSc 3.18 declares the array of VecMAXPY non-const; it only reads it.
    PetscCall(VecMAXPY(v, m, dots.data(), const_cast<Vec *>(raw.data())));
    PetscFunctionReturn(0);
  }

  // v orthogonal to every c_i (twice, for round-off): for a vector with zero
  // multiplier part, the orthogonal projection of its coordinate part onto
  // the null space of C (the c_i span the range of C^T).
  PetscErrorCode projectOut(Vec v) const
  {
    Eigen::VectorXd a;
    PetscFunctionBeginUser;
    if (raw.empty()) PetscFunctionReturn(0);
    for (int pass = 0; pass < 2; ++pass) PetscCall(subtractRange(v, &a));
    PetscFunctionReturn(0);
  }

  // r <- r + sum a_i c_i and x_mu <- x_mu + a with a minimizing ||r||.
  PetscErrorCode fit(Vec r, Vec x) const
  {
    Eigen::VectorXd a;
    PetscInt lo, hi;
    PetscScalar *xa;
    PetscFunctionBeginUser;
    if (raw.empty()) PetscFunctionReturn(0);
    PetscCall(subtractRange(r, &a));
    PetscCall(VecGetOwnershipRange(x, &lo, &hi));
    PetscCall(VecGetArray(x, &xa));
    for (PetscInt i = 0; i < (PetscInt)raw.size(); ++i)
      if (nq + i >= lo && nq + i < hi) xa[nq + i - lo] += a[i];
    PetscCall(VecRestoreArray(x, &xa));
    PetscFunctionReturn(0);
  }
};

// The real subspace V (Euclidean-orthonormal columns, layout of x) and the
// products of its columns with K, D, M.
struct Subspace {
  std::vector<PetscHandle<Vec>> V, KV, DV, MV;
  PetscInt nq = 0;                          // coordinates (the multipliers follow them in x)
  const MultiplierFit *null = nullptr;      // projects onto the null space of C

  std::vector<Vec> raw(const std::vector<PetscHandle<Vec>> &w) const
  {
    std::vector<Vec> r(w.size());
    for (std::size_t i = 0; i < w.size(); ++i) r[i] = w[i];
    return r;
  }

  // Orthonormalizes v against V (classical Gram-Schmidt, twice) and appends
  // it unless it lies in span V to round-off.
  PetscErrorCode append(Mat K, Mat D, Mat M, PetscHandle<Vec> &&v)
  {
    PetscReal before, after;
    PetscInt lo, hi;
    PetscScalar *va;
    PetscFunctionBeginUser;
    // Coordinate parts only: the multiplier parts drop out of the projection
    // (C v_q = 0) and are fitted to the Ritz vectors (MultiplierFit); kept,
    // they would make the q parts of an orthonormal V ill-conditioned.
    PetscCall(VecGetOwnershipRange(v, &lo, &hi));
    PetscCall(VecGetArray(v, &va));
    for (PetscInt i = std::max(lo, nq); i < hi; ++i) va[i - lo] = 0.0;
    PetscCall(VecRestoreArray(v, &va));
    // Exactly in the null space of C: a vector that violates the constraints
    // meets no constraint stiffness in the projection (its multiplier part is
    // zero) and makes spurious soft modes. Expansions are mostly in span V
    // already, so the solver's round-off in C u, left alone, grows by the
    // cancellation (seen: 1e-4 relative, and spurious modes at 0.01 Hz).
    PetscCall(null->projectOut(v));
    PetscCall(VecNorm(v, NORM_2, &before));
    if (!(before > 0) || !std::isfinite(before)) PetscFunctionReturn(0);
    std::vector<Vec> basis = raw(V);
    std::vector<PetscScalar> dots(basis.size());
    // Against V twice (classical Gram-Schmidt), then onto the null space of C
    // again: an expansion is mostly in span V, and removing that part leaves
    // V's own round-off violation of the constraints divided by the small
    // remainder (seen: 1e-4 relative), then against V once more.
    for (int pass = 0; pass < 3 && !basis.empty(); ++pass) {
      if (pass == 2) PetscCall(null->projectOut(v));
      PetscCall(VecMDot(v, (PetscInt)basis.size(), basis.data(), dots.data()));
      for (PetscScalar &d : dots) d = -d;
      PetscCall(VecMAXPY(v, (PetscInt)basis.size(), dots.data(), basis.data()));
    }
    PetscCall(VecNorm(v, NORM_2, &after));
    if (!(after > 1e-10 * before)) PetscFunctionReturn(0);
    PetscCall(VecScale(v, 1.0 / after));
    PetscHandle<Vec> kv, dv, mv;
    PetscCall(VecDuplicate(v, kv.address()));
    PetscCall(VecDuplicate(v, dv.address()));
    PetscCall(VecDuplicate(v, mv.address()));
    PetscCall(MatMult(K, v, kv));
    PetscCall(MatMult(D, v, dv));
    PetscCall(MatMult(M, v, mv));
    V.push_back(std::move(v));
    KV.push_back(std::move(kv));
    DV.push_back(std::move(dv));
    MV.push_back(std::move(mv));
    PetscFunctionReturn(0);
  }

  // V^T W for the products W, updated from column `from` on (the columns
  // before it did not change: V only grows). Symmetric: K, D, M are.
  PetscErrorCode project(const std::vector<PetscHandle<Vec>> &W, int from, Eigen::MatrixXd *P) const
  {
    const int p = (int)V.size();
    std::vector<Vec> basis = raw(V);
    std::vector<PetscScalar> dots(p);
    PetscFunctionBeginUser;
    P->conservativeResize(p, p);
    for (int j = from; j < p; ++j) {
      PetscCall(VecMDot(W[j], p, basis.data(), dots.data()));
      for (int i = 0; i < p; ++i) (*P)(i, j) = dots[i];
      for (int i = 0; i < from; ++i) (*P)(j, i) = dots[i];
    }
    const int n = p - from;
    P->bottomRightCorner(n, n) = 0.5 * (P->bottomRightCorner(n, n) + P->bottomRightCorner(n, n).transpose()).eval();
    PetscFunctionReturn(0);
  }

  // out = sum_j c_j w_j
  PetscErrorCode combine(const std::vector<PetscHandle<Vec>> &w, const Eigen::VectorXd &c, Vec out) const
  {
    std::vector<Vec> vs = raw(w);
    std::vector<PetscScalar> coef(c.data(), c.data() + c.size());
    PetscFunctionBeginUser;
    PetscCall(VecSet(out, 0.0));
    PetscCall(VecMAXPY(out, (PetscInt)vs.size(), coef.data(), vs.data()));
    PetscFunctionReturn(0);
  }
};

struct RitzPair {
  std::complex<double> lambda;
  Eigen::VectorXcd y;
};

// The root of y^T (l^2 M + l D + K) y = 0 nearest `near`: the Rayleigh
// functional of the projected problem (bilinear, not Hermitian: K, D, M are
// real symmetric, so the left eigenvector is the right one and the
// functional is stationary at eigenvectors; its error is of the order of the
// squared vector error).
std::complex<double> rayleighFunctional(const Eigen::MatrixXd &K, const Eigen::MatrixXd &D, const Eigen::MatrixXd &M,
                                        const Eigen::VectorXcd &y, std::complex<double> near)
{
  const std::complex<double> a = y.transpose() * (M * y), b = y.transpose() * (D * y), c = y.transpose() * (K * y);
  if (std::abs(a) == 0) return near;
  const std::complex<double> root = std::sqrt(b * b - 4.0 * a * c);
  const std::complex<double> r1 = (-b + root) / (2.0 * a), r2 = (-b - root) / (2.0 * a);
  return std::abs(r1 - near) < std::abs(r2 - near) ? r1 : r2;
}

// Rayleigh functional iteration on the projected quadratic problem from
// pair (y, lambda): y <- T(lambda)^{-1} T'(lambda) y, lambda <- the root of
// the functional nearest the last; locally cubic. Dense p x p complex LU per
// step (p ~ 20-30), instead of the dense eigen-decomposition of the 2p
// linearization (1.5 ms per call on the paper scene, measured).
bool functionalIteration(const Eigen::MatrixXd &K, const Eigen::MatrixXd &D, const Eigen::MatrixXd &M, RitzPair *pair)
{
  std::complex<double> l = pair->lambda;
  Eigen::VectorXcd y = pair->y;
  for (int i = 0; i < 30; ++i) {
    const Eigen::MatrixXcd T = K.cast<std::complex<double>>() + l * D.cast<std::complex<double>>() +
                               (l * l) * M.cast<std::complex<double>>();
    const Eigen::VectorXcd rhs = (D.cast<std::complex<double>>() + 2.0 * l * M.cast<std::complex<double>>()) * y;
    const Eigen::VectorXcd z = Eigen::PartialPivLU<Eigen::MatrixXcd>(T).solve(rhs);
    const double n = z.norm();
    if (!z.allFinite() || !(n > 0)) break; // T(l) singular to round-off: l is an eigenvalue, y its vector
    y = z / n;
    const std::complex<double> next = rayleighFunctional(K, D, M, y, l);
    const double change = std::abs(next - l);
    l = next;
    if (!(change > 1e-14 * std::abs(l))) break;
    if (i == 29) return false;
  }
  if (!std::isfinite(l.real()) || !std::isfinite(l.imag())) return false;
  pair->lambda = l;
  pair->y = y;
  return true;
}

// The `count` damped pairs of the projected problem that continue `pairs`
// (ascending |lambda|). With no pairs yet, started from the lowest undamped
// Ritz pairs of (K, M) with omega^2 > 0. False when an iteration fails, two
// pairs meet, or a pair is not oscillating (Im lambda > 0): the full solve
// decides (it also reports overdamped cases with fewer modes).
bool projectedModes(const Eigen::MatrixXd &K, const Eigen::MatrixXd &D, const Eigen::MatrixXd &M, int count,
                    std::vector<RitzPair> *pairs)
{
  const int p = (int)K.rows();
  if (pairs->empty()) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> undamped(K, M);
    if (undamped.info() != Eigen::Success) return false;
    const Eigen::VectorXd w2 = undamped.eigenvalues();
    const double scale = std::abs(w2[p - 1]);
    for (int j = 0; j < p && (int)pairs->size() < count; ++j) {
      if (!(w2[j] > 1e-8 * scale)) continue; // rigid-body modes: not oscillating
      Eigen::VectorXcd y = undamped.eigenvectors().col(j).cast<std::complex<double>>();
      y /= y.norm();
      pairs->push_back({rayleighFunctional(K, D, M, y, std::complex<double>(0.0, std::sqrt(w2[j]))), y});
    }
    if ((int)pairs->size() < count) return false;
  } else {
    for (RitzPair &pair : *pairs) pair.y.conservativeResizeLike(Eigen::VectorXcd::Zero(p)); // V grew
  }
  for (RitzPair &pair : *pairs)
    if (!functionalIteration(K, D, M, &pair) || !(pair.lambda.imag() > 1e-10 * std::abs(pair.lambda))) return false;
  std::sort(pairs->begin(), pairs->end(),
            [](const RitzPair &a, const RitzPair &b) { return std::abs(a.lambda) < std::abs(b.lambda); });
  for (int k = 1; k < count; ++k)
    if (std::abs((*pairs)[k].lambda - (*pairs)[k - 1].lambda) <= 1e-8 * std::abs((*pairs)[k].lambda)) return false;
  return true;
}

} // namespace

PetscErrorCode DampedModeRefiner::refine(double t, Vec q, Vec lambda, Mat K, Mat M, KSP solver,
                                         const std::vector<PetscHandle<Vec>> &modes, int count,
                                         DampedModalResult *result, DampedRefinementInfo *info, bool *converged)
{
  Subspace sub;
  PetscHandle<Vec> rhs;
  PetscFunctionBeginUser;
  *converged = false;
  *info = DampedRefinementInfo{};
  *result = DampedModalResult{};
  if (modes.empty() || count < 1) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(logEvents().eigen, 0, 0, 0, 0));
  if (!D_ || pattern_ != assembler_.patternVersion()) {
    D_.reset();
    PetscCall(assembler_.createMatrix(D_.address()));
    pattern_ = assembler_.patternVersion();
  }
  PetscCall(assembleDamping(assembler_, t, q, lambda, D_));
  PetscCall(VecDuplicate(modes[0], rhs.address()));
  MultiplierFit multipliers;
  PetscCall(multipliers.setUp(K, modes[0], assembler_.model().numCoordinates(), assembler_.model().numMultipliers()));
  sub.nq = assembler_.model().numCoordinates();
  sub.null = &multipliers;

  // Solve P u = b, P the factorization of K - tau M; false on a failed solve.
  const auto precondition = [&](Vec b, PetscHandle<Vec> *u, bool *ok) -> PetscErrorCode {
    KSPConvergedReason reason;
    PetscFunctionBeginUser;
    PetscCall(VecDuplicate(b, u->address()));
    PetscCall(KSPSolve(solver, b, *u));
    PetscCall(KSPGetConvergedReason(solver, &reason));
    *ok = reason >= 0;
    PetscFunctionReturn(0);
  };
  bool ok = true;
  for (const PetscHandle<Vec> &phi : modes) {
    PetscHandle<Vec> v;
    PetscCall(VecDuplicate(phi, v.address()));
    PetscCall(VecCopy(phi, v));
    PetscCall(sub.append(K, D_, M, std::move(v)));
  }
  // The first-order change of the modes by the damping: T(i w) (phi + dx) = 0
  // gives (K - w^2 M) dx ~ -i w D phi, approximated with P.
  for (int k = 0; k < count && k < (int)modes.size(); ++k) { // the wanted ones; the guard modes need no correction
    const PetscHandle<Vec> &phi = modes[k];
    PetscHandle<Vec> u;
    PetscCall(MatMult(D_, phi, rhs));
    PetscCall(precondition(rhs, &u, &ok));
    if (!ok) break;
    PetscCall(sub.append(K, D_, M, std::move(u)));
  }

  PetscHandle<Vec> kr, ki, dr, di, mr, mi, rr, ri;
  for (Vec *w : {kr.address(), ki.address(), dr.address(), di.address(), mr.address(), mi.address(), rr.address(),
                 ri.address()})
    PetscCall(VecDuplicate(modes[0], w));
  std::vector<PetscHandle<Vec>> xr(count), xi(count); // the Ritz vectors, multiplier parts fitted
  for (int k = 0; k < count; ++k) {
    PetscCall(VecDuplicate(modes[0], xr[k].address()));
    PetscCall(VecDuplicate(modes[0], xi[k].address()));
  }
  double before = HUGE_VAL, bestWorst = HUGE_VAL;
  std::vector<std::complex<double>> bestLambda;
  std::vector<double> bestResidual;
  std::vector<PetscHandle<Vec>> bestXr(count), bestXi(count);
  for (int k = 0; k < count; ++k) {
    PetscCall(VecDuplicate(modes[0], bestXr[k].address()));
    PetscCall(VecDuplicate(modes[0], bestXi[k].address()));
  }
  std::vector<RitzPair> pairs; // the wanted pairs of the projected problem, continued across expansions
  Eigen::MatrixXd Kp, Dp, Mp;  // the projected matrices, the first `projected` columns up to date
  int projected = 0;
  for (int it = 1; ok && it <= maxIterations && (int)sub.V.size() <= maxSubspace; ++it) {
    PetscCall(sub.project(sub.KV, projected, &Kp));
    PetscCall(sub.project(sub.DV, projected, &Dp));
    PetscCall(sub.project(sub.MV, projected, &Mp));
    projected = (int)sub.V.size();
    const bool found = projectedModes(Kp, Dp, Mp, count, &pairs);
    if (!found) break; // the full solve decides (and may report fewer)
    std::vector<double> residual(count);
    std::vector<PetscHandle<Vec>> expansion;
    double worst = 0;
    for (int k = 0; k < count; ++k) {
      const std::complex<double> l = pairs[k].lambda, l2 = l * l;
      const Eigen::VectorXd yr = pairs[k].y.real(), yi = pairs[k].y.imag();
      PetscCall(sub.combine(sub.V, yr, xr[k]));
      PetscCall(sub.combine(sub.V, yi, xi[k]));
      PetscCall(sub.combine(sub.KV, yr, kr));
      PetscCall(sub.combine(sub.KV, yi, ki));
      PetscCall(sub.combine(sub.DV, yr, dr));
      PetscCall(sub.combine(sub.DV, yi, di));
      PetscCall(sub.combine(sub.MV, yr, mr));
      PetscCall(sub.combine(sub.MV, yi, mi));
      // r = K x + lambda D x + lambda^2 M x, real and imaginary parts.
      PetscReal knr, kni, rnr, rni;
      PetscCall(VecCopy(kr, rr));
      {
        const PetscScalar a[4] = {l.real(), -l.imag(), l2.real(), -l2.imag()};
        Vec w[4] = {dr, di, mr, mi};
        PetscCall(VecMAXPY(rr, 4, a, w));
      }
      PetscCall(VecCopy(ki, ri));
      {
        const PetscScalar a[4] = {l.real(), l.imag(), l2.real(), l2.imag()};
        Vec w[4] = {di, dr, mi, mr};
        PetscCall(VecMAXPY(ri, 4, a, w));
      }
      PetscCall(multipliers.fit(rr, xr[k]));
      PetscCall(multipliers.fit(ri, xi[k]));
      PetscCall(MatMult(K, xr[k], kr));
      PetscCall(MatMult(K, xi[k], ki));
      PetscCall(VecNorm(kr, NORM_2, &knr));
      PetscCall(VecNorm(ki, NORM_2, &kni));
      PetscCall(VecNorm(rr, NORM_2, &rnr));
      PetscCall(VecNorm(ri, NORM_2, &rni));
      const double kn = std::hypot(knr, kni);
      const double rel = kn > 0 ? std::hypot(rnr, rni) / kn : 1.0;
      worst = std::max(worst, rel);
      residual[k] = rel;
      if (rel > tolerance) {
        for (Vec r : {rr.get(), ri.get()}) {
          PetscHandle<Vec> u;
          PetscCall(precondition(r, &u, &ok));
          if (!ok) break;
          expansion.push_back(std::move(u));
        }
      }
    }
    info->iterations = it;
    info->subspace = (int)sub.V.size();
    if (worst < bestWorst) {
      // The best iterate so far: past the round-off floor of the residual
      // (about 1e-9 on the paper scene) further expansions are noise and can
      // make the projection worse (spurious Ritz pairs near the wanted ones).
      bestWorst = worst;
      bestLambda.clear();
      bestResidual = residual;
      for (int k = 0; k < count; ++k) {
        bestLambda.push_back(pairs[k].lambda);
        PetscCall(VecCopy(xr[k], bestXr[k]));
        PetscCall(VecCopy(xi[k], bestXi[k]));
      }
    }
    if (worst <= tolerance || worst > before) break; // converged, or past the round-off floor
    before = worst;
    for (PetscHandle<Vec> &u : expansion) PetscCall(sub.append(K, D_, M, std::move(u)));
  }
  info->worstResidual = bestWorst;
  if (bestWorst <= tolerance) {
    for (int k = 0; k < count; ++k)
      PetscCall(appendDampedMode(assembler_, bestLambda[k], bestXr[k], bestXi[k], bestResidual[k], true, result));
    *converged = true;
  }
  PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
