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
  // (c^T c)^+, once per analysis: a COD solve per call cost more than the
  // rest. c (c^T c)^+ c^T is the orthogonal projection onto span{c_i}, the
  // range of C^T in the coordinate rows (Subspace::against).
  Eigen::MatrixXd gramInverse;
  PetscInt nq = 0;
  LocalBlocks *blocks = nullptr;

  PetscErrorCode setUp(Mat K, LocalBlocks &b, PetscInt coordinates, PetscInt multipliers)
  {
    PetscFunctionBeginUser;
    blocks = &b;
    nq = coordinates;
    c.resize(b.localSize(), multipliers);
    PetscCall(b.columns(K, nq, c)); // K e_i: K's multiplier columns, read off its entries
    Eigen::MatrixXd G;
    PetscCall(b.inner(c, c, &G));
    if (multipliers > 0) gramInverse = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(G).pseudoInverse();
    PetscFunctionReturn(0);
  }

  // r <- r + c a with a = -(c^T c)^+ c^T r minimizing ||r|| (per column),
  // the a into *a (empty without multipliers). The multiplier part of the
  // Ritz vector x is x_mu + a (the subspace's multiplier parts are zero).
  PetscErrorCode fit(Eigen::Ref<Block> r, Eigen::MatrixXd *a) const
  {
    Eigen::MatrixXd dots;
    PetscFunctionBeginUser;
    a->resize(0, 0);
    if (c.cols() == 0) PetscFunctionReturn(0);
    PetscCall(blocks->inner(c, r, &dots));
    a->noalias() = -gramInverse * dots;
    LocalBlocks::combine(c, *a, r, true);
    PetscFunctionReturn(0);
  }

  // x_mu <- x_mu + a for the columns of x (the local multiplier rows).
  void addMultipliers(Eigen::Ref<Block> x, const Eigen::MatrixXd &a) const
  {
    const PetscInt n = blocks->localSize(), lo = blocks->firstRow();
    for (PetscInt i = 0; i < (PetscInt)a.rows(); ++i)
      if (nq + i - lo >= 0 && nq + i - lo < n) x.row(nq + i - lo) += a.row(i);
  }
};

// The real subspace V (Euclidean-orthonormal columns, local rows of x's
// layout) and the products of its columns with K, D, M; the first p columns
// of V are in use, the first `multiplied` of KV, DV, MV.
struct Subspace {
  Block V, KV, DV, MV;
  int p = 0, multiplied = 0;
  PetscInt firstMultiplierRow = 0;     // local rows from here on are multipliers
  const MultiplierFit *null = nullptr; // c: onto the null space of C
  LocalBlocks *blocks = nullptr;

  // v - c (c^T c)^+ c^T v - V (V^T v): one classical Gram-Schmidt pass
  // against span{c_i} (the range of C^T, MultiplierFit) and V together (V is
  // orthogonal to the c_i), and its norm.
  PetscErrorCode against(Eigen::Ref<Block> v, bool withV, double *norm) const
  {
    Eigen::MatrixXd dc, dv;
    Eigen::VectorXd nv;
    const bool constrained = null->c.cols() > 0;
    PetscFunctionBeginUser;
    if (constrained) PetscCall(blocks->inner(null->c, v, &dc));
    if (withV && p > 0) PetscCall(blocks->inner(V.leftCols(p), v, &dv));
    if (constrained) v.noalias() -= null->c * (null->gramInverse * dc);
    if (withV && p > 0) v.noalias() -= V.leftCols(p) * dv;
    PetscCall(blocks->columnNorms(v, &nv));
    *norm = nv[0];
    PetscFunctionReturn(0);
  }

  // Orthonormalizes v against V (classical Gram-Schmidt) and appends it
  // unless it lies in span V to round-off. The products with K, D, M are
  // made later for all new columns at once (multiply()).
  PetscErrorCode append(Eigen::VectorXd v)
  {
    const PetscInt n = blocks->localSize();
    PetscFunctionBeginUser;
    // Coordinate parts only: the multiplier parts drop out of the projection
    // (C v_q = 0) and are fitted to the Ritz vectors (MultiplierFit); kept,
    // they would make the q parts of an orthonormal V ill-conditioned.
    v.tail(n - firstMultiplierRow).setZero();
    // Exactly in the null space of C: a vector that violates the constraints
    // meets no constraint stiffness in the projection (its multiplier part is
    // zero) and makes spurious soft modes. Expansions are mostly in span V
    // already, so the solver's round-off in C u, left alone, grows by the
    // cancellation (seen: 1e-4 relative, and spurious modes at 0.01 Hz):
    // the passes against V are against the c_i too.
    Eigen::VectorXd norm;
    PetscCall(blocks->columnNorms(v, &norm));
    const double before = norm[0];
    if (!(before > 0) || !std::isfinite(before)) PetscFunctionReturn(0);
    double after;
    // Against [c V] until a pass no longer cancels (the norm stays above
    // 1/sqrt(2) of the last: Daniel, Gragg, Kaufman and Stewart's test), at
    // most three times: once for a vector mostly outside span V (the modes
    // at the start), twice for the expansions ("twice is enough"). The
    // earlier version made two passes against the c_i, two against V, two
    // against the c_i and one against V (four and three) every time.
    after = before;
    for (int pass = 0; pass < 3; ++pass) {
      const double last = after;
      PetscCall(against(v, true, &after));
      if (after >= M_SQRT1_2 * last) break;
    }
    if (!(after > 1e-10 * before)) PetscFunctionReturn(0);
    v /= after;
    if (p == V.cols()) {
      const Eigen::Index grown = V.cols() + 8;
      for (Block *b : {&V, &KV, &DV, &MV}) b->conservativeResize(n, grown);
    }
    V.col(p) = v;
    ++p;
    PetscFunctionReturn(0);
  }

  // K, D, M times the columns appended since the last call, as blocks (one
  // pass over each matrix for four columns, LocalBlocks::multiply).
  PetscErrorCode multiply(Mat K, Mat D, Mat M)
  {
    const int k = p - multiplied;
    PetscFunctionBeginUser;
    if (k > 0) {
      PetscCall(blocks->multiply(K, V.middleCols(multiplied, k), KV.middleCols(multiplied, k)));
      PetscCall(blocks->multiply(D, V.middleCols(multiplied, k), DV.middleCols(multiplied, k)));
      PetscCall(blocks->multiply(M, V.middleCols(multiplied, k), MV.middleCols(multiplied, k)));
    }
    multiplied = p;
    PetscFunctionReturn(0);
  }

  // V^T W for the products W, updated from column `from` on (the columns
  // before it did not change: V only grows). Symmetric: K, D, M are.
  // The block of the new columns with themselves as a symmetric product
  // (its upper triangle, LocalBlocks::innerSymmetric), the one with the old
  // columns as a full product.
  PetscErrorCode project(const Block &W, int from, Eigen::MatrixXd *P) const
  {
    Eigen::MatrixXd G;
    const int n = p - from;
    PetscFunctionBeginUser;
    P->conservativeResize(p, p);
    if (from > 0) {
      PetscCall(blocks->inner(V.leftCols(from), W.middleCols(from, n), &G));
      P->block(0, from, from, n) = G;
      P->block(from, 0, n, from) = G.transpose();
    }
    PetscCall(blocks->innerSymmetric(V.middleCols(from, n), W.middleCols(from, n), &G));
    P->bottomRightCorner(n, n) = G;
    PetscFunctionReturn(0);
  }
};

struct RitzPair {
  std::complex<double> lambda;
  Eigen::VectorXcd y;
  // Its Ritz vector met the tolerance in the full space at an earlier
  // projection: kept as it is (y padded with zeros gives the same x = V y,
  // the first columns of V do not change), no functional iteration, and
  // its residual and fitted multipliers are those of that projection.
  bool converged = false;
  double residual = 0;  // ||T(lambda) x|| / ||K x|| of its Ritz vector
  Eigen::VectorXd ar, ai; // the fitted multipliers of x = V y (MultiplierFit)
};

// K y, D y, M y for a complex y and real K, D, M: the functional iteration
// needs them for its residual test and for the Rayleigh functional of the
// same y (computed once, used twice).
struct Products {
  Eigen::VectorXcd K, D, M;
  void of(const Eigen::MatrixXd &Kp, const Eigen::MatrixXd &Dp, const Eigen::MatrixXd &Mp, const Eigen::VectorXcd &y)
  {
    K.noalias() = Kp * y;
    D.noalias() = Dp * y;
    M.noalias() = Mp * y;
  }
};

// The root of y^T (l^2 M + l D + K) y = 0 nearest `near` (P: the products of
// y): the Rayleigh functional of the projected problem (bilinear, not
// Hermitian: K, D, M are real symmetric, so the left eigenvector is the
// right one and the functional is stationary at eigenvectors; its error is
// of the order of the squared vector error).
std::complex<double> rayleighFunctional(const Products &P, const Eigen::VectorXcd &y, std::complex<double> near)
{
  const std::complex<double> a = y.transpose() * P.M, b = y.transpose() * P.D, c = y.transpose() * P.K;
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
  Products P;
  P.of(K, D, M, y);
  for (int i = 0; i < 30; ++i) {
    const double terms = P.K.norm() + std::abs(l) * P.D.norm() + std::norm(l) * P.M.norm();
    if ((P.K + l * P.D + (l * l) * P.M).norm() <= 1e-12 * terms) break;
    const Eigen::VectorXcd rhs = P.D + 2.0 * l * P.M;
    // T(l) singular to round-off: l is an eigenvalue, y its vector.
    if (!solveShifted(K, D, M, l, rhs, &z)) break;
    const double n = z.norm();
    if (!(n > 0)) break;
    y = z / n;
    P.of(K, D, M, y); // for the functional and the next step's test
    const std::complex<double> next = rayleighFunctional(P, y, l);
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
      Products P;
      P.of(K, D, M, y);
      RitzPair pair;
      pair.lambda = rayleighFunctional(P, y, std::complex<double>(0.0, std::sqrt(w2[j])));
      pair.y = y;
      pairs->push_back(pair);
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
    PetscCall(sub.append(phi.col(k)));
  }
  // The first-order change of the modes by the damping: T(i w) (phi + dx) = 0
  // gives (K - w^2 M) dx ~ -i w D phi, approximated with P = K - tau M and
  // the first term of (K - w^2 M)^{-1} = P^{-1} + (w^2 - tau) P^{-1} M P^{-1}
  // + ...: u = P^{-1} D phi and P^{-1} M u. The second vector saves a
  // projection (3 instead of 4 on the paper scene at 10 ms, about a tenth
  // of a run with tracking every 1 ms); P^{-1} D u (second order in the
  // damping) saved none. The products as blocks, the appends in the order
  // u_0, P^{-1} M u_0, u_1, ...
  const int corrected = std::min(count, m); // the wanted ones; the guard modes need no correction
  Block rhs(n, corrected), U(n, corrected), U2(n, corrected);
  PetscCall(blocks_.multiply(D, phi.leftCols(corrected), rhs));
  PetscCall(blocks_.solveColumns(solver, rhs, U, &ok));
  if (ok) PetscCall(blocks_.multiply(M, U, rhs));
  if (ok) PetscCall(blocks_.solveColumns(solver, rhs, U2, &ok));
  for (int k = 0; k < corrected && ok; ++k) {
    PetscCall(sub.append(U.col(k)));
    PetscCall(sub.append(U2.col(k)));
  }

  double before = HUGE_VAL, bestWorst = HUGE_VAL;
  int bestP = 0;
  std::vector<RitzPair> pairs, best; // the wanted pairs of the projected problem, continued across expansions
  Eigen::MatrixXd Kp, Dp, Mp;        // the projected matrices, the first `projected` columns up to date
  int projected = 0;
  for (int it = 1; ok && it <= maxIterations && sub.p <= maxSubspace; ++it) {
    PetscCall(sub.multiply(K, D, M));
    PetscCall(sub.project(sub.KV, projected, &Kp));
    PetscCall(sub.project(sub.DV, projected, &Dp));
    PetscCall(sub.project(sub.MV, projected, &Mp));
    projected = sub.p;
    const bool found = projectedModes(Kp, Dp, Mp, count, &pairs);
    if (!found) break; // the full solve decides (and may report fewer)
    // The pairs whose Ritz vector did not meet the tolerance at an earlier
    // projection: a converged pair keeps its x (RitzPair::converged), its
    // residual and multipliers, so only these need products here.
    std::vector<int> open;
    for (int k = 0; k < count; ++k)
      if (!pairs[k].converged) open.push_back(k);
    const int o = (int)open.size();
    // Real and imaginary parts side by side: columns j and o + j for open[j].
    Eigen::MatrixXd Y(sub.p, 2 * o), Dc(sub.p, 2 * o), Mc(sub.p, 2 * o);
    for (int j = 0; j < o; ++j) {
      const RitzPair &pair = pairs[open[j]];
      const std::complex<double> l = pair.lambda, l2 = l * l;
      const Eigen::VectorXd yr = pair.y.real(), yi = pair.y.imag();
      Y.col(j) = yr, Y.col(o + j) = yi;
      Dc.col(j) = l.real() * yr - l.imag() * yi;
      Dc.col(o + j) = l.real() * yi + l.imag() * yr;
      Mc.col(j) = l2.real() * yr - l2.imag() * yi;
      Mc.col(o + j) = l2.real() * yi + l2.imag() * yr;
    }
    // K x and r = K x + lambda D x + lambda^2 M x, real and imaginary parts,
    // from the products kept with V (no product with the matrices here);
    // the D and M terms as one product each with the combined coefficients.
    // x = V y itself is needed for the best iterate only (at the end).
    const auto KV = sub.KV.leftCols(sub.p), DV = sub.DV.leftCols(sub.p), MV = sub.MV.leftCols(sub.p);
    // Tall times small: LocalBlocks::combine.
    Block KX(n, 2 * o), R(n, 2 * o);
    LocalBlocks::combine(KV, Y, KX);
    R = KX;
    LocalBlocks::combine(DV, Dc, R, true);
    LocalBlocks::combine(MV, Mc, R, true);
    // The fitted multipliers a add K e_i a_i = c a to K x as well.
    Eigen::MatrixXd a;
    PetscCall(multipliers.fit(R, &a));
    if (a.size()) LocalBlocks::combine(multipliers.c, a, KX, true);
    Eigen::VectorXd kn, rn;
    PetscCall(blocks_.columnNorms(KX, &kn));
    PetscCall(blocks_.columnNorms(R, &rn));
    // The expansions: the solver applied to the residuals of the pairs that
    // did not converge (real and imaginary part each), as one block.
    std::vector<int> expand;
    double worst = 0;
    for (int j = 0; j < o; ++j) {
      RitzPair &pair = pairs[open[j]];
      const double knorm = std::hypot(kn[j], kn[o + j]);
      pair.residual = knorm > 0 ? std::hypot(rn[j], rn[o + j]) / knorm : 1.0;
      if (a.size()) pair.ar = a.col(j), pair.ai = a.col(o + j);
      pair.converged = pair.residual <= tolerance;
      if (!pair.converged) expand.insert(expand.end(), {j, o + j});
    }
    Block residuals(n, (Eigen::Index)expand.size()), expansion(n, (Eigen::Index)expand.size());
    for (std::size_t c = 0; c < expand.size(); ++c) residuals.col(c) = R.col(expand[c]);
    PetscCall(blocks_.solveColumns(solver, residuals, expansion, &ok));
    for (int k = 0; k < count; ++k) worst = std::max(worst, pairs[k].residual);
    info->iterations = it;
    info->subspace = sub.p;
    if (worst < bestWorst) {
      // The best iterate so far: past the round-off floor of the residual
      // (about 1e-9 on the paper scene) further expansions are noise and can
      // make the projection worse (spurious Ritz pairs near the wanted ones).
      bestWorst = worst;
      best.assign(pairs.begin(), pairs.begin() + count);
      bestP = sub.p;
    }
    if (worst <= tolerance || worst > before) break; // converged, or past the round-off floor
    before = worst;
    for (Eigen::Index c = 0; ok && c < expansion.cols(); ++c) PetscCall(sub.append(expansion.col(c)));
  }
  info->worstResidual = bestWorst;
  if (bestWorst <= tolerance) {
    // x = V y of the best iterate (V's first bestP columns are those of its
    // projection) and the fitted multipliers.
    Eigen::MatrixXd Y(bestP, 2 * count), A;
    for (int k = 0; k < count; ++k) {
      Y.col(k) = best[k].y.real().head(bestP), Y.col(count + k) = best[k].y.imag().head(bestP);
    }
    Block X(n, 2 * count);
    LocalBlocks::combine(sub.V.leftCols(bestP), Y, X);
    if (multipliers.c.cols() > 0) {
      A.resize(multipliers.c.cols(), 2 * count);
      for (int k = 0; k < count; ++k) A.col(k) = best[k].ar, A.col(count + k) = best[k].ai;
      multipliers.addMultipliers(X, A);
    }
    PetscHandle<Vec> xr, xi;
    PetscCall(VecDuplicate(modes[0], xr.address()));
    PetscCall(VecDuplicate(modes[0], xi.address()));
    for (int k = 0; k < count; ++k) {
      PetscCall(blocks_.toVec(X.col(k).data(), xr));
      PetscCall(blocks_.toVec(X.col(count + k).data(), xi));
      PetscCall(appendDampedMode(assembler_, best[k].lambda, xr, xi, best[k].residual, keepVectors, result));
    }
    *converged = true;
  }
  PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
