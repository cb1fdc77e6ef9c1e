#include "boomdyn/mode_refinement.hpp"

#include "boomdyn/direct_solver.hpp"
#include "boomdyn/log_events.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace boomdyn {

PetscErrorCode ModeRefiner::prepare(double t, Vec q, Vec lambda, double target, bool *factored)
{
  PetscFunctionBeginUser;
  factored_ = false;
  if (!A_ || pattern_ != assembler_.patternVersion()) {
    // A contact point changed element: new matrices, and the solver forgets
    // its symbolic factorization (docs/petsc-notes.md trap 1).
    PetscCall(assembler_.createMatrix(A_.address()));
    PetscCall(assembler_.createMatrix(B_.address()));
    S_.reset(); // made from A below: a matrix made by createMatrix() is not assembled yet
    if (!ksp_) {
      PetscCall(KSPCreate(assembler_.comm(), ksp_.address()));
      PetscCall(KSPSetOptionsPrefix(ksp_, "modal_st_"));
      PetscCall(useDirectSolver(ksp_));
      PetscCall(KSPSetFromOptions(ksp_));
    } else {
      PetscCall(KSPReset(ksp_));
    }
    pattern_ = assembler_.patternVersion();
  }
  PetscCall(assemblePencil(assembler_, t, q, lambda, A_, B_));
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
  std::vector<PetscHandle<Vec>> W(m), AW(m), BW(m);
  PetscHandle<Vec> rhs, r;
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
  PetscCall(VecDuplicate(basis[0], rhs.address()));
  PetscCall(VecDuplicate(basis[0], r.address()));
  for (int j = 0; j < m; ++j) {
    PetscCall(VecDuplicate(basis[0], W[j].address()));
    PetscCall(VecDuplicate(basis[0], AW[j].address()));
    PetscCall(VecDuplicate(basis[0], BW[j].address()));
  }
  std::vector<Vec> w(m), aw(m), bw(m);
  for (int j = 0; j < m; ++j) w[j] = W[j], aw[j] = AW[j], bw[j] = BW[j];
  std::vector<PetscScalar> dots(m), coef(m);
  Eigen::MatrixXd GA(m, m), GB(m, m);
  for (int it = 1; it <= maxIterations; ++it) {
    for (int j = 0; j < m; ++j) {
      KSPConvergedReason kr;
      PetscCall(MatMult(B_, basis[j], rhs));
      PetscCall(KSPSolve(ksp_, rhs, W[j]));
      PetscCall(KSPGetConvergedReason(ksp_, &kr));
      if (kr < 0) {
        PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
        PetscFunctionReturn(0);
      }
      PetscCall(MatMult(A_, W[j], AW[j]));
      PetscCall(MatMult(B_, W[j], BW[j]));
    }
    // Projected pencil (W^T A W, W^T B W), symmetrized against round-off.
    for (int j = 0; j < m; ++j) {
      PetscCall(VecMDot(AW[j], m, w.data(), dots.data()));
      for (int i = 0; i < m; ++i) GA(i, j) = dots[i];
      PetscCall(VecMDot(BW[j], m, w.data(), dots.data()));
      for (int i = 0; i < m; ++i) GB(i, j) = dots[i];
    }
    GA = 0.5 * (GA + GA.transpose()).eval();
    GB = 0.5 * (GB + GB.transpose()).eval();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> rr(GA, GB);
    if (rr.info() != Eigen::Success) break; // W lost B-rank: let the full solve decide
    const Eigen::VectorXd theta = rr.eigenvalues(); // ascending
    const Eigen::MatrixXd Y = rr.eigenvectors();    // Y^T GB Y = 1
    // The modes must be finite and non-negative (docs/model.md §5): anything
    // else goes to the full solve, which filters and reports.
    if (!theta.allFinite() || theta[0] < -1e-8 * std::abs(theta[m - 1])) break;
    double worst = 0;
    for (int k = 0; k < m; ++k) {
      for (int j = 0; j < m; ++j) coef[j] = Y(j, k);
      PetscCall(VecSet(basis[k], 0.0));
      PetscCall(VecMAXPY(basis[k], m, coef.data(), w.data()));
      if (k >= count) continue;
      // r = A x - theta B x = sum_j Y_jk (A w_j - theta B w_j)
      PetscReal rn, an;
      PetscCall(VecSet(rhs, 0.0));
      PetscCall(VecMAXPY(rhs, m, coef.data(), aw.data()));
      PetscCall(VecNorm(rhs, NORM_2, &an));
      for (int j = 0; j < m; ++j) coef[j] = -theta[k] * Y(j, k);
      PetscCall(VecCopy(rhs, r));
      PetscCall(VecMAXPY(r, m, coef.data(), bw.data()));
      PetscCall(VecNorm(r, NORM_2, &rn));
      worst = std::max(worst, an > 0 ? rn / an : 1.0);
    }
    const double before = out->worstResidual;
    out->iterations = it;
    out->worstResidual = worst;
    if (worst <= tolerance) {
      out->omega2.assign(theta.data(), theta.data() + count);
      *converged = true;
      break;
    }
    // Stagnation at a round-off floor (a low mode of a stiff pencil): no use
    // iterating on. Below floorTolerance the pairs are accepted, above it
    // the full solve decides.
    if (it > 2 && worst > 0.5 * before) {
      if (worst <= floorTolerance) {
        out->omega2.assign(theta.data(), theta.data() + count);
        *converged = true;
      }
      break;
    }
  }
  PetscCall(PetscLogEventEnd(logEvents().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
