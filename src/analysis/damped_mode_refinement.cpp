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
  // Its Ritz vector met the tolerance in the full space: no further
  // functional iteration (its subspace is not expanded any more).
  bool converged = false;
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

// Continues `pair` on the projected problem of its grown subspace (its y
// padded with zeros: the first columns of the subspace did not change). A
// pair that met the tolerance at an earlier projection keeps its vector
// (RitzPair::converged). False when the iteration fails or the pair is not
// oscillating (Im lambda > 0): the full solve decides (it also reports
// overdamped cases with fewer modes).
bool continuePair(const Eigen::MatrixXd &K, const Eigen::MatrixXd &D, const Eigen::MatrixXd &M, RitzPair *pair)
{
  pair->y.conservativeResizeLike(Eigen::VectorXcd::Zero(K.rows()));
  return (pair->converged || functionalIteration(K, D, M, pair)) &&
         pair->lambda.imag() > 1e-10 * std::abs(pair->lambda);
}

} // namespace

PetscErrorCode DampedModeRefiner::refine(double t, Vec q, Vec lambda, Mat K, Mat M, Mat D, KSP solver,
                                         const std::vector<PetscHandle<Vec>> &modes, int count,
                                         DampedModalResult *result, DampedRefinementInfo *info, bool *converged)
{
  Subspace base;
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
  PencilNorms ownNorms;
  PencilNorms *pencilNorms = norms;
  if (!pencilNorms) ownNorms.set(K, M, D), pencilNorms = &ownNorms;
  const PetscInt n = blocks_.localSize(), nq = assembler_.model().numCoordinates();
  MultiplierFit multipliers;
  PetscCall(multipliers.setUp(K, blocks_, nq, assembler_.model().numMultipliers()));
  base.firstMultiplierRow = std::min<PetscInt>(n, std::max<PetscInt>(0, nq - blocks_.firstRow()));
  base.null = &multipliers;
  base.blocks = &blocks_;
  const int m = (int)modes.size();
  base.V.resize(n, m);
  for (Block *b : {&base.KV, &base.DV, &base.MV}) b->resize(n, m);

  // The undamped modes, shared by every pair's subspace: orthonormalized,
  // multiplied and projected once.
  bool ok = true;
  Block phi(n, m);
  for (int k = 0; k < m; ++k) {
    PetscCall(blocks_.fromVec(modes[k], phi.col(k).data()));
    PetscCall(base.append(phi.col(k)));
  }
  PetscCall(base.multiply(K, D, M));
  Eigen::MatrixXd K0, D0, M0, C;
  PetscCall(base.project(base.KV, 0, &K0));
  PetscCall(base.project(base.DV, 0, &D0));
  PetscCall(base.project(base.MV, 0, &M0));
  const int m0 = base.p;
  // The modes in the basis of base.V, and their omega^2 (Rayleigh quotients):
  // the `count` lowest oscillating ones are followed (rigid-body modes of a
  // mechanism, omega^2 ~ 0, are not).
  PetscCall(blocks_.inner(base.V.leftCols(m0), phi, &C));
  std::vector<int> wanted;
  std::vector<double> w2(m);
  double scale = 0;
  for (int k = 0; k < m; ++k) {
    const double mk = C.col(k).dot(M0 * C.col(k));
    w2[k] = mk > 0 ? C.col(k).dot(K0 * C.col(k)) / mk : 0.0;
    scale = std::max(scale, std::abs(w2[k]));
  }
  for (int k = 0; k < m && (int)wanted.size() < count; ++k)
    if (w2[k] > 1e-8 * scale) wanted.push_back(k);
  if ((int)wanted.size() < count) ok = false;

  // The first-order change of the modes by the damping: T(i w) (phi + dx) = 0
  // gives (K - w^2 M) dx ~ -i w D phi, approximated with P = K - tau M and
  // the first term of (K - w^2 M)^{-1} = P^{-1} + (w^2 - tau) P^{-1} M P^{-1}
  // + ...: u = P^{-1} D phi and P^{-1} M u (the second saves a projection;
  // P^{-1} D u, second order in the damping, and a third term of the series
  // cost more than they save: docs/performance-history.md, "Tenth round"). The
  // products and solves of all pairs as blocks.
  Block rhs(n, count), U(n, count), U2(n, count), W(n, count);
  for (int j = 0; ok && j < count; ++j) W.col(j) = phi.col(wanted[j]);
  if (ok) PetscCall(blocks_.multiply(D, W, rhs));
  if (ok) PetscCall(blocks_.solveColumns(solver, rhs, U, &ok));
  if (ok) PetscCall(blocks_.multiply(M, U, rhs));
  if (ok) PetscCall(blocks_.solveColumns(solver, rhs, U2, &ok));

  // One subspace per wanted pair: [the modes, its u, P^{-1} M u, its own
  // expansions]. Each pair's projected quadratic problem stays small (p <=
  // m + 2 + 2 maxIterations, against m + 2 count + 2 count maxIterations for
  // a subspace shared by all pairs), and its dense solves are most of a
  // projection's cost; the pairs' products and solves are still one block.
  struct Pair {
    Subspace sub;
    Eigen::MatrixXd Kp, Dp, Mp; // projected on sub's first `projected` columns
    int projected = 0;
    RitzPair ritz;
    bool open = true;           // still iterating
    bool exact = true;          // needed: to `tolerance`; else to provisionalTolerance
    double limit = 0;           // that tolerance
    // The best iterate's |lambda|, |x| and |K x|, for its round-off floor
    // (roundOffFloor), taken only if the pair misses its tolerance.
    std::complex<double> bestLambda = 0;
    double bestX = 0, bestKx = 0;
    double best = HUGE_VAL;     // residual of the best iterate
    Block x;                    // its vector (real, imaginary part)
    Eigen::MatrixXd a;          // its fitted multipliers
  };
  std::vector<Pair> pairs(ok ? count : 0);
  for (int j = 0; j < (int)pairs.size(); ++j) {
    Pair &pr = pairs[j];
    Subspace &sub = pr.sub;
    sub.firstMultiplierRow = base.firstMultiplierRow, sub.null = base.null, sub.blocks = base.blocks;
    const Eigen::Index capacity = m0 + 2 + 2 * maxIterations;
    for (Block *b : {&sub.V, &sub.KV, &sub.DV, &sub.MV}) b->resize(n, capacity);
    sub.V.leftCols(m0) = base.V.leftCols(m0), sub.KV.leftCols(m0) = base.KV.leftCols(m0);
    sub.DV.leftCols(m0) = base.DV.leftCols(m0), sub.MV.leftCols(m0) = base.MV.leftCols(m0);
    sub.p = sub.multiplied = pr.projected = m0;
    pr.Kp = K0, pr.Dp = D0, pr.Mp = M0;
    // The start: the undamped mode (its coordinates in base.V) and the root
    // of its Rayleigh functional nearest i omega.
    const int k = wanted[j];
    Eigen::VectorXcd y = C.col(k).cast<std::complex<double>>();
    y /= y.norm();
    Products P;
    P.of(K0, D0, M0, y);
    pr.ritz.lambda = rayleighFunctional(P, y, std::complex<double>(0.0, std::sqrt(w2[k])));
    pr.ritz.y = y;
    PetscCall(sub.append(U.col(j)));
    PetscCall(sub.append(U2.col(j)));
  }
  // Which pairs go to `tolerance`: the needed ones, or all.
  bool all = needed.empty();
  for (int k : needed) all = all || std::find(wanted.begin(), wanted.end(), k) == wanted.end();
  for (int j = 0; j < (int)pairs.size(); ++j) {
    pairs[j].exact = all || std::find(needed.begin(), needed.end(), wanted[j]) != needed.end();
    pairs[j].limit = pairs[j].exact ? tolerance : provisionalTolerance;
  }

  int rounds = 0, largest = m0;
  for (int it = 1; ok && it <= maxIterations; ++it) {
    rounds = it;
    // K, D, M times every open pair's new columns, as one block.
    std::vector<int> fresh(count, 0);
    int total = 0;
    for (int j = 0; j < count; ++j)
      if (pairs[j].open) fresh[j] = pairs[j].sub.p - pairs[j].sub.multiplied, total += fresh[j];
    if (total > 0) {
      Block X(n, total), KX(n, total), DX(n, total), MX(n, total);
      for (int j = 0, c = 0; j < count; c += fresh[j], ++j)
        if (fresh[j]) X.middleCols(c, fresh[j]) = pairs[j].sub.V.middleCols(pairs[j].sub.multiplied, fresh[j]);
      PetscCall(blocks_.multiply(K, X, KX));
      PetscCall(blocks_.multiply(D, X, DX));
      PetscCall(blocks_.multiply(M, X, MX));
      for (int j = 0, c = 0; j < count; c += fresh[j], ++j) {
        if (!fresh[j]) continue;
        Subspace &sub = pairs[j].sub;
        sub.KV.middleCols(sub.multiplied, fresh[j]) = KX.middleCols(c, fresh[j]);
        sub.DV.middleCols(sub.multiplied, fresh[j]) = DX.middleCols(c, fresh[j]);
        sub.MV.middleCols(sub.multiplied, fresh[j]) = MX.middleCols(c, fresh[j]);
        sub.multiplied = sub.p;
      }
    }
    // Each open pair: projection, its functional iteration, its residual
    // r = K x + lambda D x + lambda^2 M x from the products kept with V
    // (real and imaginary parts side by side), the fitted multipliers.
    std::vector<int> expand;
    Block residuals(n, 2 * count);
    for (int j = 0; ok && j < count; ++j) {
      Pair &pr = pairs[j];
      if (!pr.open) continue;
      Subspace &sub = pr.sub;
      if (it > 1 && sub.p == pr.projected) { // its expansions lay in its subspace already
        pr.open = false;
        continue;
      }
      PetscCall(sub.project(sub.KV, pr.projected, &pr.Kp));
      PetscCall(sub.project(sub.DV, pr.projected, &pr.Dp));
      PetscCall(sub.project(sub.MV, pr.projected, &pr.Mp));
      pr.projected = sub.p;
      largest = std::max(largest, sub.p);
      if (!continuePair(pr.Kp, pr.Dp, pr.Mp, &pr.ritz)) {
        ok = false;
        break;
      }
      const std::complex<double> l = pr.ritz.lambda, l2 = l * l;
      const Eigen::VectorXd yr = pr.ritz.y.real(), yi = pr.ritz.y.imag();
      Eigen::MatrixXd Y(sub.p, 2), Dc(sub.p, 2), Mc(sub.p, 2);
      Y.col(0) = yr, Y.col(1) = yi;
      Dc.col(0) = l.real() * yr - l.imag() * yi, Dc.col(1) = l.real() * yi + l.imag() * yr;
      Mc.col(0) = l2.real() * yr - l2.imag() * yi, Mc.col(1) = l2.real() * yi + l2.imag() * yr;
      Block KX(n, 2), R(n, 2);
      LocalBlocks::combine(sub.KV.leftCols(sub.p), Y, KX);
      R = KX;
      LocalBlocks::combine(sub.DV.leftCols(sub.p), Dc, R, true);
      LocalBlocks::combine(sub.MV.leftCols(sub.p), Mc, R, true);
      // The fitted multipliers a add K e_i a_i = c a to K x as well.
      Eigen::MatrixXd a;
      PetscCall(multipliers.fit(R, &a));
      if (a.size()) LocalBlocks::combine(multipliers.c, a, KX, true);
      Eigen::VectorXd kn, rn;
      PetscCall(blocks_.columnNorms(KX, &kn));
      PetscCall(blocks_.columnNorms(R, &rn));
      const double knorm = std::hypot(kn[0], kn[1]);
      const double residual = knorm > 0 ? std::hypot(rn[0], rn[1]) / knorm : 1.0;
      // |x|: V y with orthonormal V and |y| = 1, and the fitted multipliers.
      const double xnorm = std::sqrt(pr.ritz.y.squaredNorm() + a.squaredNorm());
      if (residual < pr.best) {
        // The best iterate so far: past the round-off floor of the residual
        // (about 1e-9 on the paper scene) further expansions are noise and
        // can make the projection worse.
        pr.best = residual;
        pr.x.resize(n, 2);
        LocalBlocks::combine(sub.V.leftCols(sub.p), Y, pr.x);
        pr.a = a;
        pr.bestLambda = l, pr.bestX = xnorm, pr.bestKx = knorm;
      }
      pr.ritz.converged = residual <= pr.limit;
      // Converged, past the round-off floor (the residual grew), or out of
      // room: this pair is finished.
      if (pr.ritz.converged || residual > pr.best || sub.p + 2 > sub.V.cols()) {
        pr.open = false;
        continue;
      }
      residuals.col(2 * (Eigen::Index)expand.size()) = R.col(0);
      residuals.col(2 * (Eigen::Index)expand.size() + 1) = R.col(1);
      expand.push_back(j);
    }
    if (!ok || expand.empty()) break;
    // The expansions: the solver applied to the open pairs' residuals (real
    // and imaginary part each), as one block; each pair takes its own two.
    const Eigen::Index e = 2 * (Eigen::Index)expand.size();
    Block expansion(n, e);
    PetscCall(blocks_.solveColumns(solver, residuals.leftCols(e), expansion, &ok));
    for (std::size_t c = 0; ok && c < expand.size(); ++c) {
      PetscCall(pairs[expand[c]].sub.append(expansion.col(2 * c)));
      PetscCall(pairs[expand[c]].sub.append(expansion.col(2 * c + 1)));
    }
  }
  // Every pair within its own tolerance, or stopped (its residual grew, or
  // no room was left) within floorFactor of its round-off floor (refined
  // meshes: roundOffFloor(), mode_refinement.hpp); the worst residual
  // reported is the worst of the pairs that missed, or of the needed ones.
  double worst = 0, missed = 0;
  bool met = !pairs.empty();
  for (const Pair &pr : pairs) {
    if (pr.exact) worst = std::max(worst, pr.best);
    if (pr.best <= pr.limit) continue;
    PetscReal nK = 0, nD = 0, nM = 0;
    PetscCall(pencilNorms->stiffness(&nK));
    PetscCall(pencilNorms->damping(&nD));
    PetscCall(pencilNorms->mass(&nM));
    const std::complex<double> l = pr.bestLambda;
    const double floor = roundOffFloor((nK + std::abs(l) * nD + std::norm(l) * nM) * pr.bestX, pr.bestKx);
    if (!(pr.best <= floorFactor * floor)) met = false, missed = std::max(missed, pr.best);
  }
  info->iterations = rounds;
  info->subspace = largest;
  info->worstResidual = pairs.empty() ? HUGE_VAL : met ? worst : missed;
  // Ascending |lambda| (as solveDampedModes); two pairs that found the same
  // mode go to the full solve.
  std::vector<int> order(pairs.size());
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = (int)j;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::abs(pairs[a].ritz.lambda) < std::abs(pairs[b].ritz.lambda);
  });
  bool distinct = true;
  for (std::size_t j = 1; j < order.size(); ++j) {
    const std::complex<double> l = pairs[order[j]].ritz.lambda, before = pairs[order[j - 1]].ritz.lambda;
    distinct = distinct && std::abs(l - before) > 1e-8 * std::abs(l);
  }
  if (ok && met && distinct) {
    PetscHandle<Vec> xr, xi;
    PetscCall(VecDuplicate(modes[0], xr.address()));
    PetscCall(VecDuplicate(modes[0], xi.address()));
    for (int j : order) {
      Pair &pr = pairs[j];
      if (multipliers.c.cols() > 0) multipliers.addMultipliers(pr.x, pr.a);
      PetscCall(blocks_.toVec(pr.x.col(0).data(), xr));
      PetscCall(blocks_.toVec(pr.x.col(1).data(), xi));
      PetscCall(appendDampedMode(assembler_, pr.ritz.lambda, xr, xi, pr.best, keepVectors, result));
      info->exact.push_back(pr.exact);
    }
    *converged = true;
  }
  PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
