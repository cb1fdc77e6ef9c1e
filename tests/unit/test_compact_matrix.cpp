// CompactMatrix (src/analysis/compact_matrix.cpp): the copy without explicit
// zeros that the tracking refinements multiply by. Its products must equal
// the source's (the same terms; only the pairing of the sums in PETSc's
// unrolled kernels may differ, so to a few ulps of the terms), it must hold
// exactly the nonzeros, follow new values in place while the zero pattern
// holds, and be made anew when an entry becomes zero or nonzero.
#include <gtest/gtest.h>

#include "boomdyn/compact_matrix.hpp"

#include <petscmat.h>

#include <cmath>
#include <limits>

namespace {

using boomdyn::CompactMatrix;
using boomdyn::PetscHandle;

constexpr PetscInt kRows = 41;

// A 7-band pattern on one rank whose entries with (i + j) % 3 == 0 are
// explicit zeros (as the pencil's M and D hold zeros in the Jacobian's
// pattern); `scale` changes the values, `zeroRow` >= 0 zeroes that row's
// diagonal as well.
void fill(Mat A, double scale, PetscInt zeroRow)
{
  for (PetscInt i = 0; i < kRows; ++i)
    for (PetscInt j = std::max<PetscInt>(0, i - 3); j <= std::min<PetscInt>(kRows - 1, i + 3); ++j) {
      double v = (i + j) % 3 == 0 ? 0.0 : scale * (std::sin(0.7 * i + 1.3 * j) + (i == j ? 5.0 : 0.0));
      if (i == zeroRow && j == i) v = 0.0;
      ASSERT_EQ(MatSetValue(A, i, j, v, INSERT_VALUES), 0);
    }
  ASSERT_EQ(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), 0);
}

PetscInt nonzeros(double scale, PetscInt zeroRow)
{
  PetscInt count = 0;
  for (PetscInt i = 0; i < kRows; ++i)
    for (PetscInt j = std::max<PetscInt>(0, i - 3); j <= std::min<PetscInt>(kRows - 1, i + 3); ++j)
      count += (i + j) % 3 != 0 && !(i == zeroRow && j == i) && scale != 0.0;
  return count;
}

// max_i |(A x - C x)_i| / sum_j |A_ij x_j|
double productDifference(Mat A, Mat C)
{
  PetscHandle<Vec> x, y, z;
  EXPECT_EQ(MatCreateVecs(A, x.address(), y.address()), 0);
  EXPECT_EQ(VecDuplicate(y, z.address()), 0);
  for (PetscInt i = 0; i < kRows; ++i) EXPECT_EQ(VecSetValue(x, i, std::cos(0.3 * i) - 0.2, INSERT_VALUES), 0);
  EXPECT_EQ(VecAssemblyBegin(x), 0);
  EXPECT_EQ(VecAssemblyEnd(x), 0);
  EXPECT_EQ(MatMult(A, x, y), 0);
  EXPECT_EQ(MatMult(C, x, z), 0);
  const PetscScalar *ya, *za, *xa;
  EXPECT_EQ(VecGetArrayRead(y, &ya), 0);
  EXPECT_EQ(VecGetArrayRead(z, &za), 0);
  EXPECT_EQ(VecGetArrayRead(x, &xa), 0);
  double worst = 0;
  for (PetscInt i = 0; i < kRows; ++i) {
    PetscInt n;
    const PetscInt *cols;
    const PetscScalar *vals;
    EXPECT_EQ(MatGetRow(A, i, &n, &cols, &vals), 0);
    double terms = 0;
    for (PetscInt k = 0; k < n; ++k) terms += std::abs(vals[k] * xa[cols[k]]);
    EXPECT_EQ(MatRestoreRow(A, i, &n, &cols, &vals), 0);
    if (terms > 0) worst = std::max(worst, std::abs(ya[i] - za[i]) / terms);
    else EXPECT_EQ(za[i], 0.0);
  }
  EXPECT_EQ(VecRestoreArrayRead(x, &xa), 0);
  EXPECT_EQ(VecRestoreArrayRead(z, &za), 0);
  EXPECT_EQ(VecRestoreArrayRead(y, &ya), 0);
  return worst;
}

} // namespace

TEST(CompactMatrix, HoldsTheNonzerosAndMultipliesLikeTheSource)
{
  PetscHandle<Mat> A;
  ASSERT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, kRows, kRows, 7, nullptr, A.address()), 0);
  fill(A, 1.0, -1);
  CompactMatrix C;
  ASSERT_EQ(C.update(A), 0);
  ASSERT_NE(C.get(), A.get());
  EXPECT_EQ(C.nonzeros(), nonzeros(1.0, -1));
  EXPECT_LT(C.nonzeros(), 7 * kRows * 3 / 4); // a third of the band is zeros
  const double eps = std::numeric_limits<double>::epsilon();
  EXPECT_LE(productDifference(A, C.get()), 4 * eps);

  // New values, the same zeros: the same copy, updated in place.
  const Mat first = C.get();
  fill(A, -2.5, -1);
  ASSERT_EQ(C.update(A), 0);
  EXPECT_EQ(C.get(), first);
  EXPECT_EQ(C.nonzeros(), nonzeros(1.0, -1));
  EXPECT_LE(productDifference(A, C.get()), 4 * eps);

  // A diagonal entry becomes zero: a new pattern, one nonzero less.
  fill(A, 0.5, 17);
  ASSERT_EQ(C.update(A), 0);
  EXPECT_EQ(C.nonzeros(), nonzeros(1.0, 17));
  EXPECT_EQ(C.nonzeros(), nonzeros(1.0, -1) - 1);
  EXPECT_LE(productDifference(A, C.get()), 4 * eps);

  // All zeros: an empty copy whose products are zero.
  fill(A, 0.0, -1);
  ASSERT_EQ(C.update(A), 0);
  EXPECT_EQ(C.nonzeros(), 0);
  EXPECT_LE(productDifference(A, C.get()), 0.0);
}
