// LocalBlocks (src/analysis/local_block.cpp), the dense blocks of the
// tracking refinements, against PETSc's own operations on the same vectors:
// block inner products and norms against VecDot/VecNorm, products with a
// matrix against MatMult, solves (both the direct factor path and the
// KSPSolve path) against KSPSolve, and the copies to and from a Vec. Written
// for any rank count.
#include <gtest/gtest.h>

#include "boomdyn/direct_solver.hpp"
#include "boomdyn/local_block.hpp"

#include <petscksp.h>

#include <cmath>
#include <vector>

namespace {

using boomdyn::LocalBlocks;
using boomdyn::PetscHandle;

constexpr PetscInt kRows = 37; // not a multiple of a rank count: uneven local sizes on 2 ranks

// A deterministic, rank-independent value for global row i of vector j.
double entry(PetscInt i, int j) { return std::sin(0.37 * (i + 1) * (j + 2)) + 0.1 * j; }

// A diagonally dominant, nonsymmetric tridiagonal matrix of kRows rows.
void makeMatrix(Mat *A)
{
  PetscInt lo, hi;
  ASSERT_EQ(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, kRows, kRows, 3, nullptr, 2, nullptr, A), 0);
  ASSERT_EQ(MatGetOwnershipRange(*A, &lo, &hi), 0);
  for (PetscInt i = lo; i < hi; ++i) {
    ASSERT_EQ(MatSetValue(*A, i, i, 4.0 + 0.01 * i, INSERT_VALUES), 0);
    if (i > 0) ASSERT_EQ(MatSetValue(*A, i, i - 1, -1.0, INSERT_VALUES), 0);
    if (i + 1 < kRows) ASSERT_EQ(MatSetValue(*A, i, i + 1, -1.5, INSERT_VALUES), 0);
  }
  ASSERT_EQ(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY), 0);
}

class LocalBlocksTest : public ::testing::Test {
protected:
  void SetUp() override
  {
    makeMatrix(A_.address());
    ASSERT_EQ(MatCreateVecs(A_, layout_.address(), nullptr), 0);
    ASSERT_EQ(blocks_.setUp(layout_), 0);
    ASSERT_TRUE(blocks_.ready());
    PetscInt lo, hi;
    ASSERT_EQ(VecGetOwnershipRange(layout_, &lo, &hi), 0);
    ASSERT_EQ(blocks_.firstRow(), lo);
    ASSERT_EQ(blocks_.localSize(), hi - lo);
    V_.resize(blocks_.localSize(), 3);
    for (PetscInt r = 0; r < blocks_.localSize(); ++r)
      for (int j = 0; j < 3; ++j) V_(r, j) = entry(lo + r, j);
  }
  // Column j of V_ as a Vec of the layout.
  PetscHandle<Vec> column(int j)
  {
    PetscHandle<Vec> v;
    EXPECT_EQ(VecDuplicate(layout_, v.address()), 0);
    EXPECT_EQ(blocks_.toVec(V_.col(j).data(), v), 0);
    return v;
  }

  PetscHandle<Mat> A_;
  PetscHandle<Vec> layout_;
  LocalBlocks blocks_;
  Eigen::MatrixXd V_;
};

TEST_F(LocalBlocksTest, InnerProductsAndNormsEqualPetscs)
{
  Eigen::MatrixXd G;
  Eigen::VectorXd norms;
  ASSERT_EQ(blocks_.inner(V_, V_.rightCols(2), &G), 0);
  ASSERT_EQ(blocks_.columnNorms(V_, &norms), 0);
  ASSERT_EQ(G.rows(), 3);
  ASSERT_EQ(G.cols(), 2);
  for (int i = 0; i < 3; ++i) {
    PetscHandle<Vec> a = column(i);
    PetscReal norm;
    ASSERT_EQ(VecNorm(a, NORM_2, &norm), 0);
    EXPECT_NEAR(norms(i), norm, 1e-13 * norm);
    for (int j = 0; j < 2; ++j) {
      PetscHandle<Vec> b = column(j + 1);
      PetscScalar dot;
      ASSERT_EQ(VecDot(b, a, &dot), 0);
      EXPECT_NEAR(G(i, j), dot, 1e-13 * norm * norm) << "G(" << i << ", " << j << ")";
    }
  }
}

TEST_F(LocalBlocksTest, SymmetricInnerProductIsTheUpperTriangleMirrored)
{
  // A^T (S A) with S = diag(1 + r): symmetric; the upper triangle equals the
  // full product's, the lower is its mirror image.
  const PetscInt n = blocks_.localSize(), lo = blocks_.firstRow();
  Eigen::MatrixXd SA = V_;
  for (PetscInt r = 0; r < n; ++r) SA.row(r) *= 1.0 + 0.1 * (lo + r);
  Eigen::MatrixXd G, full;
  ASSERT_EQ(blocks_.innerSymmetric(V_, SA, &G), 0);
  ASSERT_EQ(blocks_.inner(V_, SA, &full), 0);
  ASSERT_EQ(G.rows(), 3);
  ASSERT_EQ(G.cols(), 3);
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      EXPECT_NEAR(G(i, j), full(i, j), 1e-13 * full.norm()) << i << ", " << j;
      EXPECT_EQ(G(j, i), G(i, j)) << i << ", " << j;
    }
}

TEST_F(LocalBlocksTest, WideInnerProductsEqualTheColumnDots)
{
  // Blocks wide enough for the four-column passes of the dot kernel (9 and
  // 6 columns: two passes and a remainder), 37 rows (18/19 per rank on 2:
  // a remainder of the four-row SIMD steps too). Every entry against the
  // reference dot product summed over the ranks.
  const PetscInt n = blocks_.localSize(), lo = blocks_.firstRow();
  Eigen::MatrixXd A(n, 9), B(n, 6), SA(n, 9);
  for (PetscInt r = 0; r < n; ++r) {
    for (int j = 0; j < 9; ++j) A(r, j) = entry(lo + r, j), SA(r, j) = (1.0 + 0.1 * (lo + r)) * A(r, j);
    for (int j = 0; j < 6; ++j) B(r, j) = entry(lo + r, j + 4) - 0.3;
  }
  auto reference = [&](const Eigen::MatrixXd &X, const Eigen::MatrixXd &Y) {
    Eigen::MatrixXd G(X.cols(), Y.cols());
    for (Eigen::Index i = 0; i < X.cols(); ++i)
      for (Eigen::Index j = 0; j < Y.cols(); ++j) {
        double local = 0;
        for (PetscInt r = 0; r < n; ++r) local += X(r, i) * Y(r, j);
        double sum = 0;
        EXPECT_EQ(MPI_Allreduce(&local, &sum, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD), MPI_SUCCESS);
        G(i, j) = sum;
      }
    return G;
  };
  Eigen::MatrixXd G, S;
  ASSERT_EQ(blocks_.inner(A, B, &G), 0);
  ASSERT_EQ(blocks_.innerSymmetric(A, SA, &S), 0);
  const Eigen::MatrixXd g = reference(A, B), s = reference(A, SA);
  ASSERT_EQ(G.rows(), 9);
  ASSERT_EQ(G.cols(), 6);
  ASSERT_EQ(S.rows(), 9);
  ASSERT_EQ(S.cols(), 9);
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(G(i, j), g(i, j), 1e-13 * g.norm()) << i << ", " << j;
    for (int j = 0; j < 9; ++j) EXPECT_NEAR(S(i, j), s(std::min(i, j), std::max(i, j)), 1e-13 * s.norm()) << i << ", " << j;
  }
}

TEST_F(LocalBlocksTest, MultiplyEqualsMatMultAndLeavesTheWorkVectorsFree)
{
  // Three products in a row: each must give its borrowed arrays back
  // (VecPlaceArray twice without VecResetArray is an error).
  Eigen::MatrixXd Y(blocks_.localSize(), 3);
  for (int j = 0; j < 3; ++j) ASSERT_EQ(blocks_.multiply(A_, V_.col(j).data(), Y.col(j).data()), 0);
  for (int j = 0; j < 3; ++j) {
    PetscHandle<Vec> x = column(j), y;
    ASSERT_EQ(VecDuplicate(layout_, y.address()), 0);
    ASSERT_EQ(MatMult(A_, x, y), 0);
    std::vector<double> expected(blocks_.localSize());
    ASSERT_EQ(blocks_.fromVec(y, expected.data()), 0);
    for (PetscInt r = 0; r < blocks_.localSize(); ++r) EXPECT_NEAR(Y(r, j), expected[r], 1e-13) << r; // same sums, maybe in another order
  }
}

TEST_F(LocalBlocksTest, BlockMultiplyEqualsMatMultColumnByColumn)
{
  // 1 to 7 columns: the passes of four, two and one column of the
  // sequential path (on several ranks: MatMult per column).
  const PetscInt n = blocks_.localSize();
  for (int k = 1; k <= 7; ++k) {
    Eigen::MatrixXd X(n, k), Y(n, k);
    for (int j = 0; j < k; ++j) X.col(j) = V_.col(j % 3) * (1.0 + 0.25 * j);
    ASSERT_EQ(blocks_.multiply(A_, X, Y), 0);
    for (int j = 0; j < k; ++j) {
      Eigen::VectorXd y(n);
      ASSERT_EQ(blocks_.multiply(A_, X.col(j).data(), y.data()), 0);
      for (PetscInt r = 0; r < n; ++r) EXPECT_NEAR(Y(r, j), y[r], 1e-13) << "k = " << k << ", column " << j;
    }
  }
}

TEST_F(LocalBlocksTest, ColumnsAreTheProductsWithUnitVectors)
{
  // Columns 5, 6, 7 of A: read off the entries on one rank, products with
  // unit vectors on several; either way bitwise M e_i.
  const PetscInt n = blocks_.localSize(), lo = blocks_.firstRow();
  Eigen::MatrixXd C(n, 3), E = Eigen::MatrixXd::Zero(n, 3), expected(n, 3);
  ASSERT_EQ(blocks_.columns(A_, 5, C), 0);
  for (int i = 0; i < 3; ++i)
    if (5 + i - lo >= 0 && 5 + i - lo < n) E(5 + i - lo, i) = 1.0;
  for (int i = 0; i < 3; ++i) ASSERT_EQ(blocks_.multiply(A_, E.col(i).data(), expected.col(i).data()), 0);
  for (int i = 0; i < 3; ++i)
    for (PetscInt r = 0; r < n; ++r) EXPECT_EQ(C(r, i), expected(r, i)) << "row " << lo + r << ", column " << 5 + i;
}

TEST_F(LocalBlocksTest, CombineEqualsEigensProduct)
{
  const PetscInt n = blocks_.localSize();
  for (int p : {1, 2, 3, 6, 9}) {
    for (int k : {1, 2, 5}) {
      Eigen::MatrixXd X(n, p), Y(p, k), out(n, k), sum(n, k);
      for (int j = 0; j < p; ++j) X.col(j) = V_.col(j % 3) * (1.0 + 0.5 * j);
      for (int j = 0; j < p; ++j)
        for (int c = 0; c < k; ++c) Y(j, c) = std::cos(1.3 * j + 0.7 * c);
      LocalBlocks::combine(X, Y, out);
      const Eigen::MatrixXd expected = X * Y;
      EXPECT_LE((out - expected).norm(), 1e-14 * (1.0 + expected.norm())) << "p = " << p << ", k = " << k;
      sum = expected;
      LocalBlocks::combine(X, Y, sum, true);
      EXPECT_LE((sum - 2.0 * expected).norm(), 1e-14 * (1.0 + expected.norm())) << "add, p = " << p << ", k = " << k;
    }
  }
}

// Both paths of solve(): the factor applied directly (preonly + LU, MUMPS on
// several ranks) and KSPSolve (GMRES), against KSPSolve on a Vec.
void checkSolve(Mat A, Vec layout, LocalBlocks &blocks, const Eigen::MatrixXd &V, bool direct)
{
  PetscHandle<KSP> ksp;
  PC pc;
  PetscMPIInt size;
  ASSERT_EQ(MPI_Comm_size(PETSC_COMM_WORLD, &size), 0);
  ASSERT_EQ(KSPCreate(PETSC_COMM_WORLD, ksp.address()), 0);
  ASSERT_EQ(KSPSetOperators(ksp, A, A), 0);
  ASSERT_EQ(KSPGetPC(ksp, &pc), 0);
  if (direct) {
    ASSERT_EQ(KSPSetType(ksp, KSPPREONLY), 0);
    ASSERT_EQ(PCSetType(pc, PCLU), 0);
    if (size > 1) ASSERT_EQ(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), 0);
  } else {
    ASSERT_EQ(KSPSetType(ksp, KSPGMRES), 0);
    ASSERT_EQ(PCSetType(pc, PCJACOBI), 0);
    ASSERT_EQ(KSPSetTolerances(ksp, 1e-13, 1e-50, PETSC_DEFAULT, 200), 0);
  }
  ASSERT_EQ(KSPSetUp(ksp), 0);
  for (int j = 0; j < 3; ++j) {
    std::vector<double> x(blocks.localSize()), expected(blocks.localSize());
    bool ok = false;
    ASSERT_EQ(blocks.solve(ksp, V.col(j).data(), x.data(), &ok), 0);
    EXPECT_TRUE(ok);
    PetscHandle<Vec> b, y;
    ASSERT_EQ(VecDuplicate(layout, b.address()), 0);
    ASSERT_EQ(VecDuplicate(layout, y.address()), 0);
    ASSERT_EQ(blocks.toVec(V.col(j).data(), b), 0);
    ASSERT_EQ(KSPSolve(ksp, b, y), 0);
    ASSERT_EQ(blocks.fromVec(y, expected.data()), 0);
    // The direct path is the same triangular solves (to round-off); GMRES
    // from a zero start makes the same iterations.
    for (PetscInt r = 0; r < blocks.localSize(); ++r) EXPECT_NEAR(x[r], expected[r], 1e-12) << r;
    // And it solves the system: A x = b to round-off.
    PetscHandle<Vec> xv, residual;
    ASSERT_EQ(VecDuplicate(layout, xv.address()), 0);
    ASSERT_EQ(VecDuplicate(layout, residual.address()), 0);
    ASSERT_EQ(blocks.toVec(x.data(), xv), 0);
    ASSERT_EQ(MatMult(A, xv, residual), 0);
    ASSERT_EQ(VecAXPY(residual, -1.0, b), 0);
    PetscReal rnorm, bnorm;
    ASSERT_EQ(VecNorm(residual, NORM_2, &rnorm), 0);
    ASSERT_EQ(VecNorm(b, NORM_2, &bnorm), 0);
    EXPECT_LT(rnorm, 1e-11 * bnorm);
  }
}

TEST_F(LocalBlocksTest, DirectSolveEqualsKspSolve) { checkSolve(A_, layout_, blocks_, V_, true); }

TEST_F(LocalBlocksTest, IterativeSolveEqualsKspSolve) { checkSolve(A_, layout_, blocks_, V_, false); }

// solveColumns() with the default direct solver (useDirectSolver: boomdyn's
// KLU on one rank, one solve for all columns; MUMPS on several, column by
// column) gives each column bitwise as solve() does.
TEST_F(LocalBlocksTest, SolveColumnsEqualsSolveColumnByColumn)
{
  PetscHandle<KSP> ksp;
  ASSERT_EQ(KSPCreate(PETSC_COMM_WORLD, ksp.address()), 0);
  ASSERT_EQ(KSPSetOperators(ksp, A_, A_), 0);
  ASSERT_EQ(boomdyn::useDirectSolver(ksp), 0);
  ASSERT_EQ(KSPSetUp(ksp), 0);
  const Eigen::Index n = blocks_.localSize();
  Eigen::MatrixXd X(n, 3), expected(n, 3);
  bool ok = false;
  ASSERT_EQ(blocks_.solveColumns(ksp, V_, X, &ok), 0);
  EXPECT_TRUE(ok);
  for (int j = 0; j < 3; ++j) {
    ASSERT_EQ(blocks_.solve(ksp, V_.col(j).data(), expected.col(j).data(), &ok), 0);
    EXPECT_TRUE(ok);
  }
  for (Eigen::Index r = 0; r < n; ++r)
    for (int j = 0; j < 3; ++j) EXPECT_EQ(X(r, j), expected(r, j)) << r << ", " << j;
  // A block of some columns of a wider matrix (outer stride > rows).
  Eigen::MatrixXd wide = Eigen::MatrixXd::Zero(n, 5);
  ASSERT_EQ(blocks_.solveColumns(ksp, V_.rightCols(2), wide.middleCols(1, 2), &ok), 0);
  EXPECT_TRUE(ok);
  EXPECT_TRUE(wide.middleCols(1, 2) == expected.rightCols(2));
  EXPECT_TRUE(wide.col(0).isZero(0) && wide.rightCols(2).isZero(0));
}

TEST_F(LocalBlocksTest, FailedFactorizationIsReportedNotSolved)
{
  // A zero row: LU meets a zero pivot; solve() must say so (ok false)
  // instead of applying a failed factor.
  PetscHandle<Mat> S;
  ASSERT_EQ(MatDuplicate(A_, MAT_COPY_VALUES, S.address()), 0);
  const PetscInt row = kRows / 2;
  PetscInt lo, hi;
  ASSERT_EQ(MatGetOwnershipRange(S, &lo, &hi), 0);
  if (row >= lo && row < hi) // zero values, same pattern (MatZeroRows would drop the diagonal entry)
    for (PetscInt c = row - 1; c <= row + 1; ++c) ASSERT_EQ(MatSetValue(S, row, c, 0.0, INSERT_VALUES), 0);
  ASSERT_EQ(MatAssemblyBegin(S, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(MatAssemblyEnd(S, MAT_FINAL_ASSEMBLY), 0);
  PetscHandle<KSP> ksp;
  PC pc;
  PetscMPIInt size;
  ASSERT_EQ(MPI_Comm_size(PETSC_COMM_WORLD, &size), 0);
  if (size > 1) GTEST_SKIP() << "PETSc's own LU (one rank) reports the zero pivot as a PC failure";
  ASSERT_EQ(KSPCreate(PETSC_COMM_WORLD, ksp.address()), 0);
  ASSERT_EQ(KSPSetOperators(ksp, S, S), 0);
  ASSERT_EQ(KSPSetType(ksp, KSPPREONLY), 0);
  ASSERT_EQ(KSPGetPC(ksp, &pc), 0);
  ASSERT_EQ(PCSetType(pc, PCLU), 0);
  ASSERT_EQ(KSPSetErrorIfNotConverged(ksp, PETSC_FALSE), 0);
  ASSERT_EQ(KSPSetUp(ksp), 0);
  std::vector<double> x(blocks_.localSize(), 7.0);
  bool ok = true;
  ASSERT_EQ(blocks_.solve(ksp, V_.col(0).data(), x.data(), &ok), 0);
  EXPECT_FALSE(ok);
}

} // namespace
