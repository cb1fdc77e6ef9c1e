#include "boomdyn/damped_mode_refinement.hpp"

#include "boomdyn/local_block.hpp"
#include "boomdyn/log_events.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <complex>

namespace boomdyn {

namespace {

using Block = Eigen::MatrixXd; // local rows of vectors of x's layout, one column each

// The multiplier part of a Ritz vector. The subspace vectors satisfy the
// constraints (C v_q = 0), so their multiplier parts drop out of the
// projected matrices and x_mu = V_mu y is arbitrary. It is set instead to the
// least-squares multipliers of the residual: T(lambda) e_i = K e_i = c_i for
// a unit multiplier e_i (D and M vanish there), so adding sum a_i e_i to x
// adds sum a_i c_i to r; a = -(c^T c)^+ c^T r minimizes ||r||. For the exact
// q part this is the exact multiplier part.
struct MultiplierFit {
  Block c; // K e_i, one column per multiplier
  Eigen::MatrixXd gramInverse; // (c^T c)^+, once per analysis: a COD solve per call cost more than the rest
  PetscInt nq = 0;
  LocalBlocks *blocks = nullptr;

  PetscErrorCode setUp(Mat K, LocalBlocks &b, PetscInt coordinates, PetscInt multipliers)
  {
    const PetscInt n = b.localSize(), lo = b.firstRow();
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
    PetscFunctionBeginUser;
    blocks = &b;
    nq = coordinates;
    c.resize(n, multipliers);
    for (PetscInt i = 0; i < multipliers; ++i) {
      const PetscInt row = nq + i - lo;
      if (row >= 0 && row < n) e[row] = 1.0;
      PetscCall(b.multiply(K, e.data(), c.col(i).data()));
      if (row >= 0 && row < n) e[row] = 0.0;
    }
    Eigen::MatrixXd G;
    PetscCall(b.inner(c, c, &G));
    if (multipliers > 0) gramInverse = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(G).pseudoInverse();
    PetscFunctionReturn(0);
  }

  // v <- v + c a with a = -(c^T c)^+ c^T v (column by column): what is left
  // of v after its least-squares part in the span of the c_i; the a into *a.
  PetscErrorCode subtractRange(Eigen::Ref<Block> v, Eigen::MatrixXd *a) const
  {
    Eigen::MatrixXd dots;
    PetscFunctionBeginUser;
    PetscCall(blocks->inner(c, v, &dots));
    a->noalias() = -gramInverse * dots;
    v.noalias() += c * (*a);
    PetscFunctionReturn(0);
  }

  // v orthogonal to every c_i (twice, for round-off): for a vector with zero
  // multiplier part, the orthogonal projection of its coordinate part onto
  // the null space of C (the c_i span the range of C^T).
  PetscErrorCode projectOut(Eigen::Ref<Block> v) const
  {
    Eigen::MatrixXd a;
    PetscFunctionBeginUser;
    if (c.cols() == 0) PetscFunctionReturn(0);
    for (int pass = 0; pass < 2; ++pass) PetscCall(subtractRange(v, &a));
    PetscFunctionReturn(0);
  }

  // r <- r + c a and x_mu <- x_mu + a with a minimizing ||r|| (per column);
  // the a into *a (empty without multipliers).
  PetscErrorCode fit(Eigen::Ref<Block> r, Eigen::Ref<Block> x, Eigen::MatrixXd *a) const
  {
    const PetscInt n = blocks->localSize(), lo = blocks->firstRow();
    PetscFunctionBeginUser;
    a->resize(0, 0);
    if (c.cols() == 0) PetscFunctionReturn(0);
    PetscCall(subtractRange(r, a));
    for (PetscInt i = 0; i < (PetscInt)c.cols(); ++i)
      if (nq + i - lo >= 0 && nq + i - lo < n) x.row(nq + i - lo) += a->row(i);
    PetscFunctionReturn(0);
  }
};

// The real subspace V (Euclidean-orthonormal columns, local rows of x's
// layout) and the products of its columns with K, D, M; the first p columns
// of each block are in use.
struct Subspace {
  Block V, KV, DV, MV;
  int p = 0;
  PetscInt firstMultiplierRow = 0;     // local rows from here on are multipliers
  const MultiplierFit *null = nullptr; // projects onto the null space of C
  LocalBlocks *blocks = nullptr;

  // Orthonormalizes v against V (classical Gram-Schmidt, twice) and appends
  // it unless it lies in span V to round-off.
  PetscErrorCode append(Mat K, Mat D, Mat M, Eigen::VectorXd v)
  {
    const PetscInt n = blocks->localSize();
    Eigen::VectorXd norm;
    Eigen::MatrixXd dots;
    PetscFunctionBeginUser;
    // Coordinate parts only: the multiplier parts drop out of the projection
    // (C v_q = 0) and are fitted to the Ritz vectors (MultiplierFit); kept,
    // they would make the q parts of an orthonormal V ill-conditioned.
    v.tail(n - firstMultiplierRow).setZero();
    // Exactly in the null space of C: a vector that violates the constraints
    // meets no constraint stiffness in the projection (its multiplier part is
    // zero) and makes spurious soft modes. Expansions are mostly in span V
    // already, so the solver's round-off in C u, left alone, grows by the
    // cancellation (seen: 1e-4 relative, and spurious modes at 0.01 Hz).
    PetscCall(null->projectOut(v));
    PetscCall(blocks->columnNorms(v, &norm));
    const double before = norm[0];
    if (!(before > 0) || !std::isfinite(before)) PetscFunctionReturn(0);
    // Against V twice (classical Gram-Schmidt), then onto the null space of C
    // again: an expansion is mostly in span V, and removing that part leaves
    // V's own round-off violation of the constraints divided by the small
    // remainder (seen: 1e-4 relative), then against V once more.
    for (int pass = 0; pass < 3 && p > 0; ++pass) {
      if (pass == 2) PetscCall(null->projectOut(v));
      PetscCall(blocks->inner(V.leftCols(p), v, &dots));
      v.noalias() -= V.leftCols(p) * dots;
    }
    PetscCall(blocks->columnNorms(v, &norm));
    const double after = norm[0];
    if (!(after > 1e-10 * before)) PetscFunctionReturn(0);
    v /= after;
    if (p == V.cols()) {
      const Eigen::Index grown = V.cols() + 8;
      for (Block *b : {&V, &KV, &DV, &MV}) b->conservativeResize(n, grown);
    }
    V.col(p) = v;
    PetscCall(blocks->multiply(K, V.col(p).data(), KV.col(p).data()));
    PetscCall(blocks->multiply(D, V.col(p).data(), DV.col(p).data()));
    PetscCall(blocks->multiply(M, V.col(p).data(), MV.col(p).data()));
    ++p;
    PetscFunctionReturn(0);
  }

  // V^T W for the products W, updated from column `from` on (the columns
  // before it did not change: V only grows). Symmetric: K, D, M are.
  PetscErrorCode project(const Block &W, int from, Eigen::MatrixXd *P) const
  {
    Eigen::MatrixXd G;
    const int n = p - from;
    PetscFunctionBeginUser;
    P->conservativeResize(p, p);
    PetscCall(blocks->inner(V.leftCols(p), W.middleCols(from, n), &G));
    P->middleCols(from, n) = G;
    P->block(from, 0, n, from) = G.topRows(from).transpose();
    P->bottomRightCorner(n, n) = 0.5 * (P->bottomRightCorner(n, n) + P->bottomRightCorner(n, n).transpose()).eval();
    PetscFunctionReturn(0);
  }
};

struct RitzPair {
  std::complex<double> lambda;
  Eigen::VectorXcd y;
  // Its Ritz vector met the tolerance in the full space at an earlier
  // projection: kept as it is (y padded with zeros gives the same x = V y,
  // the first columns of V do not change), no functional iteration.
  bool converged = false;
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

} // namespace

// Gaussian elimination with partial pivoting on the real and imaginary
// parts kept apart (pivot by |re| + |im|). At p ~ 15-35 this is about twice as fast
// as Eigen's complex PartialPivLU (measured 8 against 12 us at p = 19, 20
// against 37 us at p = 30), which calls hypot for every pivot candidate and
// needs the complex copies of K, D, M. False when a pivot is zero or the
// result not finite (l an eigenvalue to round-off).
bool solveShifted(const Eigen::MatrixXd &K, const Eigen::MatrixXd &D, const Eigen::MatrixXd &M,
                  std::complex<double> l, const Eigen::VectorXcd &b, Eigen::VectorXcd *z)
{
  const int p = (int)K.rows();
  const std::complex<double> l2 = l * l;
  Eigen::MatrixXd Ar = K + l.real() * D + l2.real() * M, Ai = l.imag() * D + l2.imag() * M;
  Eigen::VectorXd br = b.real(), bi = b.imag();
  for (int k = 0; k < p; ++k) {
    int pivot = k;
    double best = -1;
    for (int i = k; i < p; ++i) {
      const double score = std::abs(Ar(i, k)) + std::abs(Ai(i, k));
      if (score > best) best = score, pivot = i;
    }
    if (!(best > 0)) return false;
    if (pivot != k) {
      Ar.row(k).swap(Ar.row(pivot));
      Ai.row(k).swap(Ai.row(pivot));
      std::swap(br[k], br[pivot]);
      std::swap(bi[k], bi[pivot]);
    }
    const double dr = Ar(k, k), di = Ai(k, k), den = dr * dr + di * di, ir = dr / den, ii = -di / den;
    for (int i = k + 1; i < p; ++i) { // the column of L: a_ik / a_kk
      const double lr = Ar(i, k) * ir - Ai(i, k) * ii, li = Ar(i, k) * ii + Ai(i, k) * ir;
      Ar(i, k) = lr;
      Ai(i, k) = li;
    }
    for (int j = k + 1; j < p; ++j) { // the trailing block, column by column
      const double ur = Ar(k, j), ui = Ai(k, j);
      for (int i = k + 1; i < p; ++i) {
        Ar(i, j) -= Ar(i, k) * ur - Ai(i, k) * ui;
        Ai(i, j) -= Ar(i, k) * ui + Ai(i, k) * ur;
      }
    }
    for (int i = k + 1; i < p; ++i) { // forward substitution as we go
      br[i] -= Ar(i, k) * br[k] - Ai(i, k) * bi[k];
      bi[i] -= Ar(i, k) * bi[k] + Ai(i, k) * br[k];
    }
  }
  for (int k = p - 1; k >= 0; --k) {
    double sr = br[k], si = bi[k];
    for (int j = k + 1; j < p; ++j) {
      sr -= Ar(k, j) * br[j] - Ai(k, j) * bi[j];
      si -= Ar(k, j) * bi[j] + Ai(k, j) * br[j];
    }
    const double dr = Ar(k, k), di = Ai(k, k), den = dr * dr + di * di;
    br[k] = (sr * dr + si * di) / den;
    bi[k] = (si * dr - sr * di) / den;
  }
  if (!br.allFinite() || !bi.allFinite()) return false;
  z->resize(p);
  z->real() = br;
  z->imag() = bi;
  return true;
}

namespace {


// Rayleigh functional iteration on the projected quadratic problem from
// pair (y, lambda): y <- T(lambda)^{-1} T'(lambda) y, lambda <- the root of
// the functional nearest the last; locally cubic. One dense p x p complex
// solve per step (p ~ 20-30, solveShifted), instead of the dense
// eigen-decomposition of the 2p linearization (1.5 ms per call on the paper
// scene, measured). Before each step the residual T(lambda) y is checked
// (p^2 work against the solve's p^3): a pair that is already an eigenpair of
// the projected problem to 1e-12 of its terms needs no step (lambda is the
// functional's root of y, so its error is of the order of the squared
// residual). On the paper scene this saves about a fifth of the solves
// (mostly the confirming step after a converged one; a pair whose subspace
// grew by the other pairs' expansions is typically off by 1e-11 to 1e-9 and
// takes its step).
bool functionalIteration(const Eigen::MatrixXd &K, const Eigen::MatrixXd &D, const Eigen::MatrixXd &M, RitzPair *pair)
{
  std::complex<double> l = pair->lambda;
  Eigen::VectorXcd y = pair->y, z;
  for (int i = 0; i < 30; ++i) {
    const Eigen::VectorXcd Ky = K * y, Dy = D * y, My = M * y;
    const double terms = Ky.norm() + std::abs(l) * Dy.norm() + std::norm(l) * My.norm();
    if ((Ky + l * Dy + (l * l) * My).norm() <= 1e-12 * terms) break;
    const Eigen::VectorXcd rhs = Dy + 2.0 * l * My;
    // T(l) singular to round-off: l is an eigenvalue, y its vector.
    if (!solveShifted(K, D, M, l, rhs, &z)) break;
    const double n = z.norm();
    if (!(n > 0)) break;
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
    if (!(pair.converged || functionalIteration(K, D, M, &pair)) ||
        !(pair.lambda.imag() > 1e-10 * std::abs(pair.lambda)))
      return false;
  std::sort(pairs->begin(), pairs->end(),
            [](const RitzPair &a, const RitzPair &b) { return std::abs(a.lambda) < std::abs(b.lambda); });
  for (int k = 1; k < count; ++k)
    if (std::abs((*pairs)[k].lambda - (*pairs)[k - 1].lambda) <= 1e-8 * std::abs((*pairs)[k].lambda)) return false;
  return true;
}

} // namespace

PetscErrorCode DampedModeRefiner::refine(double t, Vec q, Vec lambda, Mat K, Mat M, Mat D, KSP solver,
                                         const std::vector<PetscHandle<Vec>> &modes, int count,
                                         DampedModalResult *result, DampedRefinementInfo *info, bool *converged)
{
  Subspace sub;
  PetscFunctionBeginUser;
  *converged = false;
  *info = DampedRefinementInfo{};
  *result = DampedModalResult{};
  if (modes.empty() || count < 1) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(logEvents().eigen, 0, 0, 0, 0));
  if (!D) {
    if (!D_ || pattern_ != assembler_.patternVersion()) {
      D_.reset();
      PetscCall(assembler_.createMatrix(D_.address()));
      pattern_ = assembler_.patternVersion();
    }
    PetscCall(assembleDamping(assembler_, t, q, lambda, D_, pencilScale));
    PetscCall(Dc_.update(D_));
    D = Dc_.get();
  }
  if (!blocks_.ready()) PetscCall(blocks_.setUp(modes[0]));
  const PetscInt n = blocks_.localSize(), nq = assembler_.model().numCoordinates();
  MultiplierFit multipliers;
  PetscCall(multipliers.setUp(K, blocks_, nq, assembler_.model().numMultipliers()));
  sub.firstMultiplierRow = std::min<PetscInt>(n, std::max<PetscInt>(0, nq - blocks_.firstRow()));
  sub.null = &multipliers;
  sub.blocks = &blocks_;
  const int m = (int)modes.size();
  sub.V.resize(n, m + count + 2 * count * maxIterations);
  for (Block *b : {&sub.KV, &sub.DV, &sub.MV}) b->resize(n, sub.V.cols());

  bool ok = true;
  Block phi(n, m);
  for (int k = 0; k < m; ++k) {
    PetscCall(blocks_.fromVec(modes[k], phi.col(k).data()));
    PetscCall(sub.append(K, D, M, phi.col(k)));
  }
  // The first-order change of the modes by the damping: T(i w) (phi + dx) = 0
  // gives (K - w^2 M) dx ~ -i w D phi, approximated with P = K - tau M and
  // the first term of (K - w^2 M)^{-1} = P^{-1} + (w^2 - tau) P^{-1} M P^{-1}
  // + ...: u = P^{-1} D phi and P^{-1} M u. The second vector saves a
  // projection (3 instead of 4 on the paper scene at 10 ms, about a tenth
  // of a run with tracking every 1 ms); P^{-1} D u (second order in the
  // damping) saved none.
  Eigen::VectorXd rhs(n), u(n), u2(n);
  for (int k = 0; k < count && k < m && ok; ++k) { // the wanted ones; the guard modes need no correction
    PetscCall(blocks_.multiply(D, phi.col(k).data(), rhs.data()));
    PetscCall(blocks_.solve(solver, rhs.data(), u.data(), &ok));
    if (!ok) break;
    PetscCall(sub.append(K, D, M, u));
    PetscCall(blocks_.multiply(M, u.data(), rhs.data()));
    PetscCall(blocks_.solve(solver, rhs.data(), u2.data(), &ok));
    if (ok) PetscCall(sub.append(K, D, M, u2));
  }

  Block Xr(n, count), Xi(n, count), Rr(n, count), Ri(n, count), KXr(n, count), KXi(n, count);
  Block bestXr, bestXi;
  double before = HUGE_VAL, bestWorst = HUGE_VAL;
  std::vector<std::complex<double>> bestLambda;
  std::vector<double> bestResidual;
  std::vector<RitzPair> pairs; // the wanted pairs of the projected problem, continued across expansions
  Eigen::MatrixXd Kp, Dp, Mp;  // the projected matrices, the first `projected` columns up to date
  int projected = 0;
  for (int it = 1; ok && it <= maxIterations && sub.p <= maxSubspace; ++it) {
    PetscCall(sub.project(sub.KV, projected, &Kp));
    PetscCall(sub.project(sub.DV, projected, &Dp));
    PetscCall(sub.project(sub.MV, projected, &Mp));
    projected = sub.p;
    const bool found = projectedModes(Kp, Dp, Mp, count, &pairs);
    if (!found) break; // the full solve decides (and may report fewer)
    Eigen::MatrixXd Yr(sub.p, count), Yi(sub.p, count);
    for (int k = 0; k < count; ++k) Yr.col(k) = pairs[k].y.real(), Yi.col(k) = pairs[k].y.imag();
    const auto V = sub.V.leftCols(sub.p), KV = sub.KV.leftCols(sub.p), DV = sub.DV.leftCols(sub.p),
               MV = sub.MV.leftCols(sub.p);
    Xr.noalias() = V * Yr;
    Xi.noalias() = V * Yi;
    // K x and r = K x + lambda D x + lambda^2 M x, real and imaginary parts,
    // from the products kept with V (no product with the matrices here);
    // the D and M terms as one product each with the combined coefficients.
    KXr.noalias() = KV * Yr;
    KXi.noalias() = KV * Yi;
    Eigen::MatrixXd Dr(sub.p, count), Di(sub.p, count), Mr(sub.p, count), Mi(sub.p, count);
    for (int k = 0; k < count; ++k) {
      const std::complex<double> l = pairs[k].lambda, l2 = l * l;
      Dr.col(k) = l.real() * Yr.col(k) - l.imag() * Yi.col(k);
      Di.col(k) = l.real() * Yi.col(k) + l.imag() * Yr.col(k);
      Mr.col(k) = l2.real() * Yr.col(k) - l2.imag() * Yi.col(k);
      Mi.col(k) = l2.real() * Yi.col(k) + l2.imag() * Yr.col(k);
    }
    Rr = KXr;
    Rr.noalias() += DV * Dr;
    Rr.noalias() += MV * Mr;
    Ri = KXi;
    Ri.noalias() += DV * Di;
    Ri.noalias() += MV * Mi;
    // The fitted multipliers a add K e_i a_i = c a to K x as well.
    Eigen::MatrixXd ar, ai;
    PetscCall(multipliers.fit(Rr, Xr, &ar));
    PetscCall(multipliers.fit(Ri, Xi, &ai));
    if (ar.size()) KXr.noalias() += multipliers.c * ar;
    if (ai.size()) KXi.noalias() += multipliers.c * ai;
    Eigen::VectorXd knr, kni, rnr, rni;
    PetscCall(blocks_.columnNorms(KXr, &knr));
    PetscCall(blocks_.columnNorms(KXi, &kni));
    PetscCall(blocks_.columnNorms(Rr, &rnr));
    PetscCall(blocks_.columnNorms(Ri, &rni));
    std::vector<double> residual(count);
    std::vector<Eigen::VectorXd> expansion;
    double worst = 0;
    for (int k = 0; k < count; ++k) {
      const double kn = std::hypot(knr[k], kni[k]);
      const double rel = kn > 0 ? std::hypot(rnr[k], rni[k]) / kn : 1.0;
      worst = std::max(worst, rel);
      residual[k] = rel;
      pairs[k].converged = rel <= tolerance;
      if (rel > tolerance) {
        for (const auto &r : {Rr.col(k), Ri.col(k)}) {
          PetscCall(blocks_.solve(solver, r.data(), u.data(), &ok));
          if (!ok) break;
          expansion.push_back(u);
        }
      }
    }
    info->iterations = it;
    info->subspace = sub.p;
    if (worst < bestWorst) {
      // The best iterate so far: past the round-off floor of the residual
      // (about 1e-9 on the paper scene) further expansions are noise and can
      // make the projection worse (spurious Ritz pairs near the wanted ones).
      bestWorst = worst;
      bestLambda.clear();
      bestResidual = residual;
      for (int k = 0; k < count; ++k) bestLambda.push_back(pairs[k].lambda);
      bestXr = Xr;
      bestXi = Xi;
    }
    if (worst <= tolerance || worst > before) break; // converged, or past the round-off floor
    before = worst;
    for (const Eigen::VectorXd &e : expansion) PetscCall(sub.append(K, D, M, e));
  }
  info->worstResidual = bestWorst;
  if (bestWorst <= tolerance) {
    PetscHandle<Vec> xr, xi;
    PetscCall(VecDuplicate(modes[0], xr.address()));
    PetscCall(VecDuplicate(modes[0], xi.address()));
    for (int k = 0; k < count; ++k) {
      PetscCall(blocks_.toVec(bestXr.col(k).data(), xr));
      PetscCall(blocks_.toVec(bestXi.col(k).data(), xi));
      PetscCall(appendDampedMode(assembler_, bestLambda[k], xr, xi, bestResidual[k], keepVectors, result));
    }
    *converged = true;
  }
  PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
