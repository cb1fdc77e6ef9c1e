#include "boomdyn/local_block.hpp"

#include "boomdyn/klu_solver.hpp"
#include "boomdyn/lanes.hpp"

#include <algorithm>

namespace boomdyn {

namespace {

// The compressed rows (CSR arrays) of a sequential AIJ matrix, borrowed for
// one pass over its entries by the block product and the column read-off.
struct CompressedRows {
  Mat M = nullptr;
  PetscInt rows = 0;
  const PetscInt *ia = nullptr, *ja = nullptr;
  const PetscScalar *a = nullptr;
};

PetscErrorCode borrowRows(Mat M, PetscInt expectedRows, CompressedRows *c)
{
  PetscBool done;
  PetscFunctionBeginUser;
  c->M = M;
  PetscCall(MatGetRowIJ(M, 0, PETSC_FALSE, PETSC_FALSE, &c->rows, &c->ia, &c->ja, &done));
  PetscCheck(done && c->rows == expectedRows, PETSC_COMM_SELF, PETSC_ERR_PLIB,
             "LocalBlocks: no compressed rows of the matrix");
  PetscCall(MatSeqAIJGetArrayRead(M, &c->a));
  PetscFunctionReturn(0);
}

PetscErrorCode returnRows(CompressedRows *c)
{
  PetscBool done;
  PetscFunctionBeginUser;
  PetscCall(MatSeqAIJRestoreArrayRead(c->M, &c->a));
  PetscCall(MatRestoreRowIJ(c->M, 0, PETSC_FALSE, PETSC_FALSE, &c->rows, &c->ia, &c->ja, &done));
  PetscFunctionReturn(0);
}

// G(i, j) = A.col(i) . B.col(j) for i < rowsOf(j) (p, or j + 1 for the upper
// triangle): four columns of A per pass over a column of B, each dot product
// in four SIMD partial sums. Eigen's general product packs both operands
// first, which at the refinements' shapes (216 rows, 1-30 columns) costs
// more than the products: 1.6-3x the time of this loop (micro-benchmark
// at p x k = 28 x 6, 6 x 28, 14 x 14, 6 x 6). One column of B (k = 1) goes
// to Eigen's gemv, which is as fast.
void columnDots(const Eigen::Ref<const Eigen::MatrixXd> &A, const Eigen::Ref<const Eigen::MatrixXd> &B,
                Eigen::MatrixXd &G, bool upper)
{
  using lanes::Lanes4;
  const Eigen::Index p = A.cols(), k = B.cols(), n = A.rows();
  for (Eigen::Index j = 0; j < k; ++j) {
    const double *b = B.col(j).data();
    const Eigen::Index rows = upper ? std::min(p, j + 1) : p;
    Eigen::Index i = 0;
    for (; i + 4 <= rows; i += 4) {
      const double *a0 = A.col(i).data(), *a1 = A.col(i + 1).data(), *a2 = A.col(i + 2).data(),
                   *a3 = A.col(i + 3).data();
      Lanes4 s0 = {0, 0, 0, 0}, s1 = s0, s2 = s0, s3 = s0;
      Eigen::Index r = 0;
      for (; r + 4 <= n; r += 4) {
        const Lanes4 x = lanes::load(b + r);
        s0 += lanes::load(a0 + r) * x, s1 += lanes::load(a1 + r) * x;
        s2 += lanes::load(a2 + r) * x, s3 += lanes::load(a3 + r) * x;
      }
      double t0 = (s0[0] + s0[1]) + (s0[2] + s0[3]), t1 = (s1[0] + s1[1]) + (s1[2] + s1[3]);
      double t2 = (s2[0] + s2[1]) + (s2[2] + s2[3]), t3 = (s3[0] + s3[1]) + (s3[2] + s3[3]);
      for (; r < n; ++r) t0 += a0[r] * b[r], t1 += a1[r] * b[r], t2 += a2[r] * b[r], t3 += a3[r] * b[r];
      G(i, j) = t0, G(i + 1, j) = t1, G(i + 2, j) = t2, G(i + 3, j) = t3;
    }
    for (; i < rows; ++i) G(i, j) = A.col(i).dot(B.col(j));
  }
}

} // namespace

PetscErrorCode LocalBlocks::setUp(Vec layout)
{
  PetscInt hi;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)layout, &comm_));
  PetscCallMPI(MPI_Comm_size(comm_, &size_));
  PetscCall(VecGetOwnershipRange(layout, &lo_, &hi));
  n_ = hi - lo_;
  PetscCall(VecDuplicate(layout, x_.address()));
  PetscCall(VecDuplicate(layout, y_.address()));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::inner(const Eigen::Ref<const Eigen::MatrixXd> &A,
                                  const Eigen::Ref<const Eigen::MatrixXd> &B, Eigen::MatrixXd *G) const
{
  PetscFunctionBeginUser;
  if (B.cols() == 1) G->noalias() = A.transpose() * B; // Eigen's gemv, as fast
  else {
    G->resize(A.cols(), B.cols());
    columnDots(A, B, *G, false);
  }
  if (size_ > 1)
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, G->data(), (PetscMPIInt)G->size(), MPI_DOUBLE, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::innerSymmetric(const Eigen::Ref<const Eigen::MatrixXd> &A,
                                           const Eigen::Ref<const Eigen::MatrixXd> &B, Eigen::MatrixXd *G) const
{
  PetscFunctionBeginUser;
  G->setZero(A.cols(), B.cols());
  columnDots(A, B, *G, true);
  if (size_ > 1)
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, G->data(), (PetscMPIInt)G->size(), MPI_DOUBLE, MPI_SUM, comm_));
  G->triangularView<Eigen::StrictlyLower>() = G->transpose();
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::columnNorms(const Eigen::Ref<const Eigen::MatrixXd> &A, Eigen::VectorXd *norms) const
{
  PetscFunctionBeginUser;
  *norms = A.colwise().squaredNorm().transpose();
  if (size_ > 1)
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, norms->data(), (PetscMPIInt)norms->size(), MPI_DOUBLE, MPI_SUM, comm_));
  *norms = norms->cwiseSqrt();
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::multiply(Mat M, const double *x, double *y)
{
  PetscFunctionBeginUser;
  // PETSc only reads the input of MatMult; VecPlaceArray takes a non-const pointer.
  PetscCall(VecPlaceArray(x_, const_cast<double *>(x)));
  PetscCall(VecPlaceArray(y_, y));
  PetscCall(MatMult(M, x_, y_));
  PetscCall(VecResetArray(x_));
  PetscCall(VecResetArray(y_));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::multiply(Mat M, const Eigen::Ref<const Eigen::MatrixXd> &X, Eigen::Ref<Eigen::MatrixXd> Y)
{
  PetscBool sequential;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)M, MATSEQAIJ, &sequential));
  const Eigen::Index k = X.cols();
  if (!sequential || X.rows() != n_ || Y.rows() != n_ || Y.cols() != k) {
    for (Eigen::Index j = 0; j < k; ++j) PetscCall(multiply(M, X.col(j).data(), Y.col(j).data()));
    PetscFunctionReturn(0);
  }
  CompressedRows csr;
  PetscCall(borrowRows(M, n_, &csr));
  const PetscInt rows = csr.rows, *ia = csr.ia, *ja = csr.ja;
  const PetscScalar *a = csr.a;
  const Eigen::Index xs = X.outerStride(), ys = Y.outerStride();
  Eigen::Index j = 0;
  // Four columns per pass: the entries and their column indices are loaded
  // once for four products. The four columns are copied side by side (row
  // major) first, so that the four x values of an entry are one 32-byte row
  // and the four sums one register pair (2 x SSE2): about 3.3 instead of 4.3
  // instructions per entry and column. Each column's sum is still formed in
  // the order of the row's entries.
  for (; j + 4 <= k; j += 4) {
    rows4_.resize(n_, 4);
    rows4_ = X.middleCols(j, 4);
    for (PetscInt i = 0; i < rows; ++i) {
      Eigen::Array<double, 1, 4> s = Eigen::Array<double, 1, 4>::Zero();
      for (PetscInt e = ia[i]; e < ia[i + 1]; ++e) s += a[e] * rows4_.row(ja[e]).array();
      Y.row(i).segment<4>(j) = s.matrix();
    }
  }
  for (; j + 2 <= k; j += 2) {
    const double *x0 = X.col(j).data(), *x1 = x0 + xs;
    double *y0 = Y.col(j).data(), *y1 = y0 + ys;
    for (PetscInt i = 0; i < rows; ++i) {
      double s0 = 0, s1 = 0;
      for (PetscInt e = ia[i]; e < ia[i + 1]; ++e) s0 += a[e] * x0[ja[e]], s1 += a[e] * x1[ja[e]];
      y0[i] = s0, y1[i] = s1;
    }
  }
  for (; j < k; ++j) {
    const double *x0 = X.col(j).data();
    double *y0 = Y.col(j).data();
    for (PetscInt i = 0; i < rows; ++i) {
      double s0 = 0;
      for (PetscInt e = ia[i]; e < ia[i + 1]; ++e) s0 += a[e] * x0[ja[e]];
      y0[i] = s0;
    }
  }
  const double nonzeros = (double)ia[rows];
  PetscCall(returnRows(&csr));
  // As MatMult: 2 flops per nonzero and column (for -log_view).
  PetscCall(PetscLogFlops(2.0 * nonzeros * (double)k));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::columns(Mat M, PetscInt first, Eigen::Ref<Eigen::MatrixXd> C)
{
  PetscBool sequential;
  const Eigen::Index k = C.cols();
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)M, MATSEQAIJ, &sequential));
  if (!sequential || C.rows() != n_) {
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(n_, k);
    for (Eigen::Index i = 0; i < k; ++i)
      if (first + i - lo_ >= 0 && first + i - lo_ < n_) E(first + i - lo_, i) = 1.0;
    PetscCall(multiply(M, E, C));
    PetscFunctionReturn(0);
  }
  CompressedRows csr;
  PetscCall(borrowRows(M, n_, &csr));
  const PetscInt rows = csr.rows, *ia = csr.ia, *ja = csr.ja;
  const PetscScalar *a = csr.a;
  C.setZero();
  for (PetscInt i = 0; i < rows; ++i)
    for (PetscInt e = ia[i]; e < ia[i + 1]; ++e)
      if (ja[e] >= first && ja[e] < first + (PetscInt)k) C(i, ja[e] - first) = a[e];
  PetscCall(returnRows(&csr));
  PetscFunctionReturn(0);
}

void LocalBlocks::combine(const Eigen::Ref<const Eigen::MatrixXd> &X, const Eigen::Ref<const Eigen::MatrixXd> &Y,
                          Eigen::Ref<Eigen::MatrixXd> out, bool add)
{
  const Eigen::Index p = X.cols(), k = Y.cols();
  if (k == 1 || p == 0) {
    if (!add) out.noalias() = X * Y;
    else out.noalias() += X * Y;
    return;
  }
  for (Eigen::Index c = 0; c < k; ++c) {
    auto o = out.col(c);
    Eigen::Index j = 0;
    if (!add) { // the first terms written, not added to zeros
      if (p >= 2) {
        o = X.col(0) * Y(0, c) + X.col(1) * Y(1, c);
        j = 2;
      } else {
        o = X.col(0) * Y(0, c);
        j = 1;
      }
    }
    for (; j + 4 <= p; j += 4)
      o += X.col(j) * Y(j, c) + X.col(j + 1) * Y(j + 1, c) + X.col(j + 2) * Y(j + 2, c) + X.col(j + 3) * Y(j + 3, c);
    for (; j < p; ++j) o += X.col(j) * Y(j, c);
  }
}

namespace {

// The factor of a shift-and-invert solver that is a factorization applied
// once (useDirectSolver: preonly + LU), or nullptr for anything else set
// from the options (which goes through KSPSolve); *ok false when that
// factorization failed.
PetscErrorCode directFactor(KSP ksp, Mat *factor, bool *ok)
{
  PC pc;
  PetscBool preonly, lu;
  PetscFunctionBeginUser;
  *factor = nullptr;
  *ok = true;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu));
  if (!preonly || !lu) PetscFunctionReturn(0);
  PCFailedReason failed;
  PetscCall(PCGetFailedReason(pc, &failed));
  *ok = failed == PC_NOERROR;
  if (*ok) PetscCall(PCFactorGetMatrix(pc, factor));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode LocalBlocks::solve(KSP ksp, const double *b, double *x, bool *ok)
{
  Mat factor;
  PetscFunctionBeginUser;
  PetscCall(VecPlaceArray(x_, const_cast<double *>(b)));
  PetscCall(VecPlaceArray(y_, x));
  // The factorization's triangular solves directly, without KSPSolve's
  // overhead (a third of a solve at 221 unknowns).
  PetscCall(directFactor(ksp, &factor, ok));
  if (factor) PetscCall(MatSolve(factor, x_, y_));
  else if (*ok) {
    KSPConvergedReason reason;
    PetscCall(KSPSolve(ksp, x_, y_));
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    *ok = reason >= 0;
  }
  PetscCall(VecResetArray(x_));
  PetscCall(VecResetArray(y_));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::solveColumns(KSP ksp, const Eigen::Ref<const Eigen::MatrixXd> &B,
                                         Eigen::Ref<Eigen::MatrixXd> X, bool *ok)
{
  Mat factor = nullptr;
  PetscBool done = PETSC_FALSE;
  PetscFunctionBeginUser;
  *ok = true;
  if (X.cols() == 0) PetscFunctionReturn(0);
  PetscCall(directFactor(ksp, &factor, ok));
  if (!*ok) PetscFunctionReturn(0);
  if (factor) {
    X = B;
    PetscCall(kluSolveColumns(factor, X.cols(), X.outerStride(), X.data(), &done));
  }
  for (Eigen::Index j = 0; j < X.cols() && !done && *ok; ++j) PetscCall(solve(ksp, B.col(j).data(), X.col(j).data(), ok));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::toVec(const double *x, Vec v) const
{
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayWrite(v, &a));
  std::copy(x, x + n_, a);
  PetscCall(VecRestoreArrayWrite(v, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalBlocks::fromVec(Vec v, double *x) const
{
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(v, &a));
  std::copy(a, a + n_, x);
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
