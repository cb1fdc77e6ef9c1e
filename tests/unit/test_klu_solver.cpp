// The one-rank direct solver "boomklu" (src/solvers/klu_solver.cpp) against
// PETSc's own KLU interface and against the equations it solves: the first
// factorization and its solves are bitwise PETSc's; a refactorization with a
// new matrix of the same pattern solves that matrix to round-off; a
// refactorization whose pivots became unsafe is rejected and the matrix is
// factored again with pivoting; the several-column solve gives every column
// bitwise as MatSolve; MatMatSolve and the transposed solve work; a singular
// matrix is an error, as with PETSc's interface. One rank (sequential AIJ).
#include <gtest/gtest.h>

#include "boomdyn/klu_solver.hpp"
#include "boomdyn/petsc_handle.hpp"

#include <petscksp.h>

#include <cmath>
#include <vector>

namespace {

using boomdyn::KluFactorCounts;
using boomdyn::PetscHandle;

constexpr PetscInt kRows = 29;

// A nonsymmetric saddle-point-like matrix: a banded block with a coupling
// row and column (zero diagonal there), scaled by `s` in its values so that
// two calls with different s have the same pattern and different numbers.
void fillMatrix(Mat A, double s)
{
  const PetscInt n = kRows - 1; // the last row/column is the "multiplier"
  for (PetscInt i = 0; i < n; ++i) {
    EXPECT_EQ(MatSetValue(A, i, i, 4.0 + 0.1 * i * s, INSERT_VALUES), 0);
    if (i > 0) EXPECT_EQ(MatSetValue(A, i, i - 1, -1.0 - 0.05 * s, INSERT_VALUES), 0);
    if (i + 2 < n) EXPECT_EQ(MatSetValue(A, i, i + 2, -0.7 * s, INSERT_VALUES), 0);
    if (i % 5 == 0) {
      EXPECT_EQ(MatSetValue(A, i, n, 1.0 + 0.01 * i, INSERT_VALUES), 0);
      EXPECT_EQ(MatSetValue(A, n, i, 1.0 + 0.01 * i, INSERT_VALUES), 0);
    }
  }
  EXPECT_EQ(MatSetValue(A, n, n, 0.0, INSERT_VALUES), 0);
  EXPECT_EQ(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), 0);
  EXPECT_EQ(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), 0);
}

PetscHandle<Mat> makeMatrix(double s)
{
  PetscHandle<Mat> A;
  EXPECT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, kRows, kRows, 8, nullptr, A.address()), 0);
  fillMatrix(A, s);
  return A;
}

PetscHandle<Vec> rhs(Mat A, int j)
{
  PetscHandle<Vec> b;
  PetscScalar *a;
  EXPECT_EQ(MatCreateVecs(A, nullptr, b.address()), 0);
  EXPECT_EQ(VecGetArray(b, &a), 0);
  for (PetscInt i = 0; i < kRows; ++i) a[i] = std::sin(0.31 * (i + 1) * (j + 1)) + 0.2 * j;
  EXPECT_EQ(VecRestoreArray(b, &a), 0);
  return b;
}

// A KSP with LU from the given solver type on A (set up: factored).
PetscHandle<KSP> factored(Mat A, const char *type)
{
  PetscHandle<KSP> ksp;
  PC pc;
  EXPECT_EQ(boomdyn::registerKluSolver(), 0);
  EXPECT_EQ(KSPCreate(PETSC_COMM_SELF, ksp.address()), 0);
  EXPECT_EQ(KSPSetType(ksp, KSPPREONLY), 0);
  EXPECT_EQ(KSPGetPC(ksp, &pc), 0);
  EXPECT_EQ(PCSetType(pc, PCLU), 0);
  EXPECT_EQ(PCFactorSetMatSolverType(pc, type), 0);
  EXPECT_EQ(KSPSetOperators(ksp, A, A), 0);
  EXPECT_EQ(KSPSetUp(ksp), 0);
  return ksp;
}

Mat factorOf(KSP ksp)
{
  PC pc;
  Mat F = nullptr;
  EXPECT_EQ(KSPGetPC(ksp, &pc), 0);
  EXPECT_EQ(PCFactorGetMatrix(pc, &F), 0);
  return F;
}

// ||A x - b|| / (||A|| ||x|| + ||b||)
double backwardError(Mat A, Vec x, Vec b)
{
  PetscHandle<Vec> r;
  PetscReal rn, an, xn, bn;
  EXPECT_EQ(VecDuplicate(b, r.address()), 0);
  EXPECT_EQ(MatMult(A, x, r), 0);
  EXPECT_EQ(VecAXPY(r, -1.0, b), 0);
  EXPECT_EQ(VecNorm(r, NORM_2, &rn), 0);
  EXPECT_EQ(MatNorm(A, NORM_FROBENIUS, &an), 0);
  EXPECT_EQ(VecNorm(x, NORM_2, &xn), 0);
  EXPECT_EQ(VecNorm(b, NORM_2, &bn), 0);
  return rn / (an * xn + bn);
}

bool bitwiseEqual(Vec x, Vec y)
{
  const PetscScalar *a, *b;
  PetscInt n;
  EXPECT_EQ(VecGetLocalSize(x, &n), 0);
  EXPECT_EQ(VecGetArrayRead(x, &a), 0);
  EXPECT_EQ(VecGetArrayRead(y, &b), 0);
  bool equal = true;
  for (PetscInt i = 0; i < n; ++i) equal = equal && a[i] == b[i];
  EXPECT_EQ(VecRestoreArrayRead(x, &a), 0);
  EXPECT_EQ(VecRestoreArrayRead(y, &b), 0);
  return equal;
}

TEST(KluSolver, FirstFactorizationSolvesBitwiseAsPetscsKlu)
{
  PetscHandle<Mat> A = makeMatrix(1.0);
  PetscHandle<KSP> ours = factored(A, boomdyn::MATSOLVERBOOMKLU), petscs = factored(A, MATSOLVERKLU);
  PetscHandle<Vec> b = rhs(A, 0), x, y;
  ASSERT_EQ(VecDuplicate(b, x.address()), 0);
  ASSERT_EQ(VecDuplicate(b, y.address()), 0);
  ASSERT_EQ(KSPSolve(ours, b, x), 0);
  ASSERT_EQ(KSPSolve(petscs, b, y), 0);
  EXPECT_TRUE(bitwiseEqual(x, y));
  EXPECT_LT(backwardError(A, x, b), 1e-15);
  ASSERT_EQ(KSPSolveTranspose(ours, b, x), 0);
  ASSERT_EQ(KSPSolveTranspose(petscs, b, y), 0);
  EXPECT_TRUE(bitwiseEqual(x, y));
}

TEST(KluSolver, RefactorizationSolvesTheNewMatrix)
{
  PetscHandle<Mat> A = makeMatrix(1.0);
  PetscHandle<KSP> ksp = factored(A, boomdyn::MATSOLVERBOOMKLU);
  fillMatrix(A, 1.3); // same pattern, new values
  ASSERT_EQ(KSPSetOperators(ksp, A, A), 0);
  ASSERT_EQ(KSPSetUp(ksp), 0);
  KluFactorCounts counts;
  PetscBool isKlu;
  ASSERT_EQ(boomdyn::kluFactorCounts(factorOf(ksp), &counts, &isKlu), 0);
  ASSERT_TRUE(isKlu);
  EXPECT_EQ(counts.full, 1);
  EXPECT_EQ(counts.refactors, 1); // the new values went through klu_refactor
  EXPECT_EQ(counts.rejected, 0);
  PetscHandle<Vec> b = rhs(A, 1), x, y;
  ASSERT_EQ(VecDuplicate(b, x.address()), 0);
  ASSERT_EQ(VecDuplicate(b, y.address()), 0);
  ASSERT_EQ(KSPSolve(ksp, b, x), 0);
  EXPECT_LT(backwardError(A, x, b), 1e-15);
  // Against a fresh factorization of the new matrix by PETSc's KLU.
  PetscHandle<KSP> fresh = factored(A, MATSOLVERKLU);
  ASSERT_EQ(KSPSolve(fresh, b, y), 0);
  PetscReal d, yn;
  ASSERT_EQ(VecAXPY(y, -1.0, x), 0);
  ASSERT_EQ(VecNorm(y, NORM_2, &d), 0);
  ASSERT_EQ(VecNorm(x, NORM_2, &yn), 0);
  EXPECT_LT(d, 1e-13 * yn);
}

TEST(KluSolver, UnsafePivotsAreFactoredAgain)
{
  // 2 x 2 blocks: [[a, 1], [1, 1]]. With a = 2 partial pivoting keeps the
  // diagonal; with a = 1e-14 that pivot order gives a growth of 1e14 and is
  // rejected, the full factorization swaps the rows.
  PetscHandle<Mat> A;
  ASSERT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 2, nullptr, A.address()), 0);
  const auto fill = [&](double a) {
    const PetscInt rows[] = {0, 1};
    const PetscScalar v[] = {a, 1.0, 1.0, 1.0};
    ASSERT_EQ(MatSetValues(A, 2, rows, 2, rows, v, INSERT_VALUES), 0);
    ASSERT_EQ(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), 0);
    ASSERT_EQ(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), 0);
  };
  fill(2.0);
  PetscHandle<KSP> ksp = factored(A, boomdyn::MATSOLVERBOOMKLU);
  fill(1e-14);
  ASSERT_EQ(KSPSetOperators(ksp, A, A), 0);
  ASSERT_EQ(KSPSetUp(ksp), 0);
  KluFactorCounts counts;
  PetscBool isKlu;
  ASSERT_EQ(boomdyn::kluFactorCounts(factorOf(ksp), &counts, &isKlu), 0);
  EXPECT_EQ(counts.full, 2);
  EXPECT_EQ(counts.refactors, 0);
  EXPECT_EQ(counts.rejected, 1);
  PetscHandle<Vec> b, x;
  ASSERT_EQ(MatCreateVecs(A, x.address(), b.address()), 0);
  ASSERT_EQ(VecSetValue(b, 0, 1.0, INSERT_VALUES), 0);
  ASSERT_EQ(VecSetValue(b, 1, 3.0, INSERT_VALUES), 0);
  ASSERT_EQ(VecAssemblyBegin(b), 0);
  ASSERT_EQ(VecAssemblyEnd(b), 0);
  ASSERT_EQ(KSPSolve(ksp, b, x), 0);
  EXPECT_LT(backwardError(A, x, b), 1e-15);
}

TEST(KluSolver, SeveralColumnsSolveBitwiseAsMatSolve)
{
  PetscHandle<Mat> A = makeMatrix(1.0);
  PetscHandle<KSP> ksp = factored(A, boomdyn::MATSOLVERBOOMKLU);
  Mat F = factorOf(ksp);
  constexpr int k = 7; // not a multiple of KLU's four columns per pass
  constexpr PetscInt ld = kRows + 3;
  std::vector<double> X(ld * k, -1.0);
  std::vector<PetscHandle<Vec>> b, x(k);
  for (int j = 0; j < k; ++j) {
    b.push_back(rhs(A, j));
    const PetscScalar *a;
    ASSERT_EQ(VecGetArrayRead(b[j], &a), 0);
    std::copy(a, a + kRows, X.begin() + j * ld);
    ASSERT_EQ(VecRestoreArrayRead(b[j], &a), 0);
    ASSERT_EQ(VecDuplicate(b[j], x[j].address()), 0);
    ASSERT_EQ(MatSolve(F, b[j], x[j]), 0);
  }
  PetscBool done;
  ASSERT_EQ(boomdyn::kluSolveColumns(F, k, ld, X.data(), &done), 0);
  ASSERT_TRUE(done);
  for (int j = 0; j < k; ++j) {
    const PetscScalar *a;
    ASSERT_EQ(VecGetArrayRead(x[j], &a), 0);
    for (PetscInt i = 0; i < kRows; ++i) EXPECT_EQ(X[j * ld + i], a[i]) << "column " << j << " row " << i;
    ASSERT_EQ(VecRestoreArrayRead(x[j], &a), 0);
    EXPECT_EQ(X[j * ld + kRows], -1.0); // the padding rows are not touched
  }
  // The same through MatMatSolve with dense blocks.
  PetscHandle<Mat> B, Y;
  ASSERT_EQ(MatCreateSeqDense(PETSC_COMM_SELF, kRows, k, nullptr, B.address()), 0);
  ASSERT_EQ(MatCreateSeqDense(PETSC_COMM_SELF, kRows, k, nullptr, Y.address()), 0);
  for (int j = 0; j < k; ++j) {
    const PetscScalar *a;
    ASSERT_EQ(VecGetArrayRead(b[j], &a), 0);
    for (PetscInt i = 0; i < kRows; ++i) ASSERT_EQ(MatSetValue(B, i, j, a[i], INSERT_VALUES), 0);
    ASSERT_EQ(VecRestoreArrayRead(b[j], &a), 0);
  }
  ASSERT_EQ(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(MatMatSolve(F, B, Y), 0);
  const PetscScalar *y;
  ASSERT_EQ(MatDenseGetArrayRead(Y, &y), 0);
  for (int j = 0; j < k; ++j)
    for (PetscInt i = 0; i < kRows; ++i) EXPECT_EQ(y[j * kRows + i], X[j * ld + i]);
  ASSERT_EQ(MatDenseRestoreArrayRead(Y, &y), 0);
}

// Each column of kluSolveColumns on x equal, bitwise, to MatSolve (KLU's own
// solve) of that column with the same factor.
void expectColumnsAsMatSolve(Mat A, Mat F, int k)
{
  const PetscInt ld = kRows + 1;
  std::vector<double> X(ld * k, -1.0);
  for (int j = 0; j < k; ++j) {
    PetscHandle<Vec> b = rhs(A, j);
    const PetscScalar *a;
    ASSERT_EQ(VecGetArrayRead(b, &a), 0);
    std::copy(a, a + kRows, X.begin() + j * ld);
    ASSERT_EQ(VecRestoreArrayRead(b, &a), 0);
  }
  PetscBool done;
  ASSERT_EQ(boomdyn::kluSolveColumns(F, k, ld, X.data(), &done), 0);
  ASSERT_TRUE(done);
  for (int j = 0; j < k; ++j) {
    PetscHandle<Vec> b = rhs(A, j), x;
    ASSERT_EQ(VecDuplicate(b, x.address()), 0);
    ASSERT_EQ(MatSolve(F, b, x), 0);
    const PetscScalar *y;
    ASSERT_EQ(VecGetArrayRead(x, &y), 0);
    for (PetscInt i = 0; i < kRows; ++i) EXPECT_EQ(X[j * ld + i], y[i]) << k << " columns: column " << j << " row " << i;
    ASSERT_EQ(VecRestoreArrayRead(x, &y), 0);
    EXPECT_EQ(X[j * ld + kRows], -1.0) << "padding row of column " << j;
  }
}

// The several-column solve runs on factors extracted from KLU's (eight
// columns per pass, padded): for every column count from 2 to 17 (one,
// two and three passes, full and padded), on a matrix whose block
// triangular form has several blocks and off-diagonal entries (KLU's
// transposed solve then subtracts them block by block), and again after a
// refactorization with new values (the extracted factors are refreshed),
// every column is bitwise KLU's own solve.
TEST(KluSolver, SeveralColumnsBitwiseWithBlocksAndAfterRefactorization)
{
  // Reducible: rows/columns 0..9 depend on 10..28 but not the other way
  // round, and 10..28 is fillMatrix's coupled system shifted.
  const auto fill = [](Mat A, double s) {
    for (PetscInt i = 0; i < kRows; ++i) {
      EXPECT_EQ(MatSetValue(A, i, i, 3.0 + 0.2 * i * s, INSERT_VALUES), 0);
      if (i >= 11) EXPECT_EQ(MatSetValue(A, i, i - 1, -1.0 - 0.1 * s, INSERT_VALUES), 0);
      if (i >= 10 && i + 1 < kRows) EXPECT_EQ(MatSetValue(A, i, i + 1, -0.5 * s, INSERT_VALUES), 0);
      if (i < 10) {
        EXPECT_EQ(MatSetValue(A, i, 10 + 2 * i, 0.7 + 0.01 * i * s, INSERT_VALUES), 0); // off-diagonal block
        if (i > 0 && i % 3 != 0) EXPECT_EQ(MatSetValue(A, i, i - 1, 0.3 * s, INSERT_VALUES), 0);
      }
    }
    EXPECT_EQ(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), 0);
    EXPECT_EQ(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), 0);
  };
  PetscHandle<Mat> A;
  ASSERT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, kRows, kRows, 6, nullptr, A.address()), 0);
  fill(A, 1.0);
  PetscHandle<KSP> ksp = factored(A, boomdyn::MATSOLVERBOOMKLU);
  Mat F = factorOf(ksp);
  KluFactorCounts counts;
  PetscBool isKlu;
  ASSERT_EQ(boomdyn::kluFactorCounts(F, &counts, &isKlu), 0);
  ASSERT_GT(counts.offDiagonal, 0); // several blocks, coupled
  for (int k = 2; k <= 17; ++k) expectColumnsAsMatSolve(A, F, k);
  fill(A, 1.7);
  ASSERT_EQ(KSPSetOperators(ksp, A, A), 0);
  ASSERT_EQ(KSPSetUp(ksp), 0);
  ASSERT_EQ(boomdyn::kluFactorCounts(F, &counts, &isKlu), 0);
  EXPECT_EQ(counts.refactors, 1);
  for (int k : {2, 8, 9}) expectColumnsAsMatSolve(A, F, k);
  // The solves are of the new matrix (not of factors kept from the first).
  PetscHandle<Vec> b = rhs(A, 3), x;
  ASSERT_EQ(VecDuplicate(b, x.address()), 0);
  std::vector<double> X(2 * kRows);
  const PetscScalar *a;
  ASSERT_EQ(VecGetArrayRead(b, &a), 0);
  std::copy(a, a + kRows, X.begin());
  std::copy(a, a + kRows, X.begin() + kRows);
  ASSERT_EQ(VecRestoreArrayRead(b, &a), 0);
  PetscBool done;
  ASSERT_EQ(boomdyn::kluSolveColumns(F, 2, kRows, X.data(), &done), 0);
  PetscScalar *xa;
  ASSERT_EQ(VecGetArray(x, &xa), 0);
  std::copy(X.begin(), X.begin() + kRows, xa);
  ASSERT_EQ(VecRestoreArray(x, &xa), 0);
  EXPECT_LT(backwardError(A, x, b), 1e-15);
}

TEST(KluSolver, OtherFactorsAreLeftToTheCaller)
{
  PetscHandle<Mat> A = makeMatrix(1.0);
  PetscHandle<KSP> ksp = factored(A, MATSOLVERKLU);
  std::vector<double> X(kRows, 1.0);
  PetscBool done = PETSC_TRUE;
  ASSERT_EQ(boomdyn::kluSolveColumns(factorOf(ksp), 1, kRows, X.data(), &done), 0);
  EXPECT_FALSE(done);
  EXPECT_EQ(X[0], 1.0);
}

TEST(KluSolver, SingularMatrixIsAnError)
{
  PetscHandle<Mat> A;
  ASSERT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, 3, 3, 3, nullptr, A.address()), 0);
  for (PetscInt i = 0; i < 3; ++i)
    for (PetscInt j = 0; j < 3; ++j) ASSERT_EQ(MatSetValue(A, i, j, 1.0 + i, INSERT_VALUES), 0); // rank 1
  ASSERT_EQ(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(boomdyn::registerKluSolver(), 0);
  PetscHandle<KSP> ksp;
  PC pc;
  ASSERT_EQ(KSPCreate(PETSC_COMM_SELF, ksp.address()), 0);
  ASSERT_EQ(KSPSetType(ksp, KSPPREONLY), 0);
  ASSERT_EQ(KSPGetPC(ksp, &pc), 0);
  ASSERT_EQ(PCSetType(pc, PCLU), 0);
  ASSERT_EQ(PCFactorSetMatSolverType(pc, boomdyn::MATSOLVERBOOMKLU), 0);
  ASSERT_EQ(KSPSetOperators(ksp, A, A), 0);
  ASSERT_EQ(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), 0);
  const PetscErrorCode ierr = KSPSetUp(ksp);
  ASSERT_EQ(PetscPopErrorHandler(), 0);
  EXPECT_EQ(ierr, PETSC_ERR_LIB);
}

} // namespace
