// Dense blocks of distributed vectors for the tracking refinements (issue 18,
// item 2; docs/performance-history.md "Tracking in dense local blocks"). At
// the paper scene's 221 unknowns a PETSc call on one Vec (VecMDot, VecMAXPY,
// VecDuplicate, ...) costs about as much as its arithmetic, and a refinement
// made several hundred of them. Here a set of vectors of one layout is the
// local rows of an Eigen column-major matrix (one column per vector): inner
// products of whole blocks are one local product and, on more than one rank,
// one MPI_Allreduce; combinations are local products (combine() for the
// tall-times-small ones); products of a block with a sequential AIJ matrix
// are one pass over its rows for four columns (multiply()), other products
// with a PETSc matrix and solves with a KSP go through two work Vecs that
// borrow a column's memory (VecPlaceArray). Works on any rank count.
#pragma once

#include "boomdyn/petsc_handle.hpp"

#include <Eigen/Dense>
#include <petscksp.h>

namespace boomdyn {

class LocalBlocks {
public:
  // The layout (and communicator) of the vectors: that of `layout`.
  PetscErrorCode setUp(Vec layout);
  bool ready() const { return x_.get() != nullptr; }
  PetscInt localSize() const { return n_; }
  PetscInt firstRow() const { return lo_; } // global index of local row 0

  // G = A^T B summed over the ranks (A, B: local rows, same row count). The
  // local part as dot products, four columns of A per pass over a column of
  // B (Eigen's general product packs both operands first: 1.6-3x slower at
  // the refinements' shapes).
  PetscErrorCode inner(const Eigen::Ref<const Eigen::MatrixXd> &A, const Eigen::Ref<const Eigen::MatrixXd> &B,
                       Eigen::MatrixXd *G) const;
  // G = A^T B summed over the ranks for a square result known to be
  // symmetric (A^T M A with M symmetric): the upper triangle computed (the
  // dot products of inner()), the lower one its mirror image.
  PetscErrorCode innerSymmetric(const Eigen::Ref<const Eigen::MatrixXd> &A,
                                const Eigen::Ref<const Eigen::MatrixXd> &B, Eigen::MatrixXd *G) const;
  // Euclidean norms of the columns of A over all ranks.
  PetscErrorCode columnNorms(const Eigen::Ref<const Eigen::MatrixXd> &A, Eigen::VectorXd *norms) const;
  // y = M x for one column (local rows of x and y).
  PetscErrorCode multiply(Mat M, const double *x, double *y);
  // Y = M X for a block of columns (local rows). For a sequential AIJ matrix
  // one pass over its compressed rows serves four columns (each row's sum in
  // the order of its entries, as MatMult without inodes): the refinements
  // multiply by matrices of 1000-2600 nonzeros about 150 times per analysis,
  // and MatMult reads the matrix once per column and costs 6-8 instructions
  // per nonzero. Otherwise (several ranks, other types) column by column.
  PetscErrorCode multiply(Mat M, const Eigen::Ref<const Eigen::MatrixXd> &X, Eigen::Ref<Eigen::MatrixXd> Y);
  // x = solve(b) with the KSP (a factorization); *ok false when it failed.
  PetscErrorCode solve(KSP ksp, const double *b, double *x, bool *ok);
  // X = solve(B) column by column with the KSP; with boomdyn's KLU factor
  // (klu_solver.hpp) all columns in one solve (one pass over L and U for
  // four columns: 6 columns at 216 unknowns in 10 instead of 22 us), each
  // column bitwise as solve() gives it. *ok false when a solve failed.
  PetscErrorCode solveColumns(KSP ksp, const Eigen::Ref<const Eigen::MatrixXd> &B, Eigen::Ref<Eigen::MatrixXd> X,
                              bool *ok);
  // C = the columns first, ..., first + C.cols() - 1 of M (local rows), i.e.
  // M times those unit vectors. For a sequential AIJ matrix read from its
  // entries (each is its product with the unit vector exactly), otherwise
  // by products with the unit vectors.
  PetscErrorCode columns(Mat M, PetscInt first, Eigen::Ref<Eigen::MatrixXd> C);
  // out = X Y, or out += X Y with `add`, for local rows X (n x p) and a small
  // Y (p x k) replicated on every rank: no communication. The refinements'
  // combinations (Ritz vectors and their products, residuals) have p of 6 to
  // 30 and k of 2 to 12, where Eigen's general product packs both operands
  // and zero-fills the result first: measured (callgrind, n = 221) 43 500
  // against 19 700 instructions at p = k = 6 and 148 000 against 131 000 at
  // p = 25, k = 10. Here each result column is a sum of axpys, four columns
  // of X per pass over it. One column (k = 1) goes to Eigen's gemv, which
  // is faster there. X and out must not overlap.
  static void combine(const Eigen::Ref<const Eigen::MatrixXd> &X, const Eigen::Ref<const Eigen::MatrixXd> &Y,
                      Eigen::Ref<Eigen::MatrixXd> out, bool add = false);
  // Copies between a column and a Vec of the layout.
  PetscErrorCode toVec(const double *x, Vec v) const;
  PetscErrorCode fromVec(Vec v, double *x) const;

private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  PetscMPIInt size_ = 1;
  PetscInt n_ = 0, lo_ = 0;
  PetscHandle<Vec> x_, y_; // work vectors without arrays of their own while in use
  Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> rows4_; // four columns side by side (multiply())
};

} // namespace boomdyn
