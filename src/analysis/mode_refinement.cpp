#include "boomdyn/mode_refinement.hpp"

#include "boomdyn/direct_solver.hpp"
#include "boomdyn/log_events.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace boomdyn {

double roundOffFloor(double scale, double norm)
{
  return norm > 0 ? DBL_EPSILON * scale / norm : 0.0;
}

void PencilNorms::set(Mat K, Mat M, Mat D)
{
  mats_[0] = K, mats_[1] = M, mats_[2] = D;
  values_[0] = values_[1] = values_[2] = -1;
}

PetscErrorCode PencilNorms::get(int which, PetscReal *v)
{
  PetscFunctionBeginUser;
  if (values_[which] < 0) {
    values_[which] = 0;
    if (mats_[which]) PetscCall(MatNorm(mats_[which], NORM_INFINITY, &values_[which]));
  }
  *v = values_[which];
  PetscFunctionReturn(0);
}

PetscErrorCode ModeRefiner::prepare(double t, Vec q, Vec lambda, double target, bool *factored)
{
  PetscFunctionBeginUser;
  factored_ = false;
  if (!A_ || pattern_ != assembler_.patternVersion()) {
    // A contact point changed element: new matrices, and the solver forgets
    // its symbolic factorization (docs/petsc-notes.md trap 1).
    PetscCall(assembler_.createMatrix(A_.address()));
    PetscCall(assembler_.createMatrix(B_.address()));
    D_.reset();
    S_.reset(); // made from A below: a matrix made by createMatrix() is not assembled yet
    if (!ksp_) {
      PetscCall(KSPCreate(assembler_.comm(), ksp_.address()));
      PetscCall(KSPSetOptionsPrefix(ksp_, "modal_st_"));
      PetscCall(useAnalysisDirectSolver(ksp_));
      PetscCall(KSPSetFromOptions(ksp_));
    } else {
      PetscCall(KSPReset(ksp_));
    }
    pattern_ = assembler_.patternVersion();
  }
  if (withDamping && !D_) PetscCall(assembler_.createMatrix(D_.address()));
  // The state vector's layout is that of x, whatever the pattern: made once.
  if (!state_) PetscCall(assembler_.createVector(state_.address()));
  PetscCall(assemblePencil(assembler_, t, q, lambda, A_, B_, &sigma_, withDamping ? D_.get() : nullptr, state_));
  PetscCall(Ac_.update(A_));
  PetscCall(Bc_.update(B_));
  if (withDamping) PetscCall(Dc_.update(D_));
  // The scales of the round-off floors of the refinements' residuals.
  norms_.set(Ac_.get(), Bc_.get(), withDamping ? Dc_.get() : nullptr);
  // A, B and S share one exact pattern (Assembler::createMatrix): the copy and
  // the update keep S's nonzero state, so the factorization below is numeric only.
  if (!S_) PetscCall(MatDuplicate(A_, MAT_COPY_VALUES, S_.address()));
  else PetscCall(MatCopy(A_, S_, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(S_, -target, B_, SAME_NONZERO_PATTERN));
  PetscCall(KSPSetOperators(ksp_, S_, S_));
  PetscCall(KSPSetUp(ksp_));
  PC pc;
  PCFailedReason reason;
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(PCGetFailedReason(pc, &reason));
  *factored = factored_ = reason == PC_NOERROR;
  PetscFunctionReturn(0);
}

PetscErrorCode ModeRefiner::refine(double t, Vec q, Vec lambda, double target, int count,
                                   std::vector<PetscHandle<Vec>> &basis, RefinedModes *out, bool *converged)
{
  const int m = static_cast<int>(basis.size());
  bool factored;
  PetscFunctionBeginUser;
  *converged = false;
  *out = RefinedModes{};
  if (m < count) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(logEvents().eigen, 0, 0, 0, 0));
  PetscCall(prepare(t, q, lambda, target, &factored));
  if (!factored) {
    PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  // The vectors as dense local blocks (local_block.hpp): one column each.
  if (!blocks_.ready()) PetscCall(blocks_.setUp(basis[0]));
  const PetscInt n = blocks_.localSize();
  Eigen::MatrixXd V(n, m), AV(n, m), BV(n, m), W(n, m), AW(n, m), BW(n, m), R(n, count);
  for (int j = 0; j < m; ++j) PetscCall(blocks_.fromVec(basis[j], V.col(j).data()));
  PetscCall(blocks_.multiply(Bc_.get(), V, BV));
  Eigen::MatrixXd GA, GB;
  Eigen::VectorXd an, rn, xn;
  bool solved = true;
  // Leading wanted Ritz vectors that met the tolerance ("soft locking"):
  // they enter the next subspace as they are, with their products, instead
  // of through a solve and two products. The lowest modes converge first
  // (the shift is below them), so the locked ones are mostly a prefix; the
  // others and the guard vectors iterate as before, and every reported pair
  // is tested again at each iteration.
  int locked = 0;
  double previousExcess = 0;
  std::vector<double> previous(count, HUGE_VAL); // each pair's residual at the last iteration
  for (int it = 1; it <= maxIterations; ++it) {
    W.leftCols(locked) = V.leftCols(locked);
    AW.leftCols(locked) = AV.leftCols(locked);
    BW.leftCols(locked) = BV.leftCols(locked);
    PetscCall(blocks_.solveColumns(ksp_, BV.rightCols(m - locked), W.rightCols(m - locked), &solved));
    if (!solved) break;
    // The products as blocks: one pass over each matrix for four columns.
    PetscCall(blocks_.multiply(Ac_.get(), W.rightCols(m - locked), AW.rightCols(m - locked)));
    PetscCall(blocks_.multiply(Bc_.get(), W.rightCols(m - locked), BW.rightCols(m - locked)));
    // Projected pencil (W^T A W, W^T B W): symmetric, the upper triangles
    // computed and mirrored (LocalBlocks::innerSymmetric).
    PetscCall(blocks_.innerSymmetric(W, AW, &GA));
    PetscCall(blocks_.innerSymmetric(W, BW, &GB));
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> rr(GA, GB);
    if (rr.info() != Eigen::Success) break; // W lost B-rank: let the full solve decide
    const Eigen::VectorXd theta = rr.eigenvalues(); // ascending
    const Eigen::MatrixXd Y = rr.eigenvectors();    // Y^T GB Y = 1
    // The modes must be finite and non-negative (docs/model.md §5): anything
    // else goes to the full solve, which filters and reports.
    if (!theta.allFinite() || theta[0] < -1e-8 * std::abs(theta[m - 1])) break;
    // Tall times small (LocalBlocks::combine: cheaper than Eigen's general product here).
    LocalBlocks::combine(W, Y, V);
    LocalBlocks::combine(BW, Y, BV); // B V for the next iteration without products with B
    LocalBlocks::combine(AW, Y, AV); // A V likewise, for the residuals and locked vectors
    // r = A x - theta B x for the wanted pairs, from A V and B V.
    R.noalias() = AV.leftCols(count) - BV.leftCols(count) * theta.head(count).asDiagonal();
    PetscCall(blocks_.columnNorms(AV.leftCols(count), &an));
    PetscCall(blocks_.columnNorms(R, &rn));
    PetscCall(blocks_.columnNorms(V.leftCols(count), &xn));
    // A pair is done at `tolerance`, or where its residual stopped falling
    // (by half in an iteration) within floorFactor of its round-off floor
    // (refined meshes: roundOffFloor()). Progress is measured by the largest
    // residual of the pairs not done (`excess`, relative to the tolerance),
    // so that a pair resting at its floor does not hide the others' progress.
    double worst = 0, excess = 0;
    std::vector<double> limit(count); // residual at which each pair counts as done (locking)
    for (int k = 0; k < count; ++k) {
      const double r = an[k] > 0 ? rn[k] / an[k] : 1.0;
      bool resting = false;
      if (r > tolerance && r > 0.5 * previous[k]) { // stopped falling above the tolerance: at its floor?
        PetscReal normA = 0, normB = 0;
        PetscCall(norms_.stiffness(&normA));
        PetscCall(norms_.mass(&normB));
        resting = r <= floorFactor * roundOffFloor((normA + std::abs(theta[k]) * normB) * xn[k], an[k]);
      }
      previous[k] = r;
      limit[k] = resting ? std::max(r, tolerance) : tolerance;
      worst = std::max(worst, r);
      if (r > limit[k]) excess = std::max(excess, r / tolerance);
    }
    locked = 0;
    while (locked < count && an[locked] > 0 && rn[locked] <= limit[locked] * an[locked]) ++locked;
    const double before = previousExcess;
    previousExcess = excess;
    out->iterations = it;
    out->worstResidual = worst;
    if (excess == 0.0) {
      out->omega2.assign(theta.data(), theta.data() + count);
      *converged = true;
      break;
    }
    // Stagnation of a pair above both its tolerance and its floor: no use
    // iterating on, the full solve decides.
    if (it > 2 && excess > 0.5 * before) break;
  }
  for (int j = 0; j < m; ++j) PetscCall(blocks_.toVec(V.col(j).data(), basis[j]));
  PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
