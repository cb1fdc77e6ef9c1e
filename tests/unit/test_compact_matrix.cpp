// CompactMatrix (src/analysis/compact_matrix.cpp): the copy without explicit
// zeros that the tracking refinements multiply by. Its products must equal
// the source's (the same terms; only the pairing of the sums in PETSc's
// unrolled kernels may differ, so to a few ulps of the terms), it must hold
// exactly the nonzeros when made from a source, follow new values in place
// while no nonzero falls outside it and few of its entries are zero, keep
// entries that turn zero as explicit +0 (products through LocalBlocks
// bitwise those of an exact copy), and be made anew otherwise.
#include <gtest/gtest.h>

#include "boomdyn/compact_matrix.hpp"
#include "boomdyn/local_block.hpp"

#include <petscmat.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

namespace {

using boomdyn::CompactMatrix;
using boomdyn::PetscHandle;

constexpr PetscInt kRows = 41;

// A 7-band pattern on one rank whose entries with (i + j) % 3 == 0 are
// explicit zeros (as the pencil's M and D hold zeros in the Jacobian's
// pattern); `scale` changes the values, the diagonals of `zeroRows` are
// zero as well, and those of `extraRows` (rows divisible by 3, whose
// diagonal is otherwise an explicit zero) nonzero.
void fill(Mat A, double scale, const std::vector<PetscInt> &zeroRows, const std::vector<PetscInt> &extraRows = {})
{
  const auto in = [](const std::vector<PetscInt> &rows, PetscInt i) {
    return std::find(rows.begin(), rows.end(), i) != rows.end();
  };
  for (PetscInt i = 0; i < kRows; ++i)
    for (PetscInt j = std::max<PetscInt>(0, i - 3); j <= std::min<PetscInt>(kRows - 1, i + 3); ++j) {
      double v = (i + j) % 3 == 0 ? 0.0 : scale * (std::sin(0.7 * i + 1.3 * j) + (i == j ? 5.0 : 0.0));
      if (j == i && in(zeroRows, i)) v = scale < 0 ? -0.0 : 0.0; // -0 as a product of negative values
      if (j == i && in(extraRows, i)) v = scale * (2.0 + 0.1 * i);
      ASSERT_EQ(MatSetValue(A, i, j, v, INSERT_VALUES), 0);
    }
  ASSERT_EQ(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), 0);
}

void fill(Mat A, double scale, PetscInt zeroRow) { fill(A, scale, std::vector<PetscInt>{zeroRow}); }

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

  // A diagonal entry becomes zero: kept as an explicit zero, in place.
  fill(A, 0.5, 17);
  ASSERT_EQ(C.update(A), 0);
  EXPECT_EQ(C.get(), first);
  EXPECT_EQ(C.nonzeros(), nonzeros(1.0, -1));
  EXPECT_LE(productDifference(A, C.get()), 4 * eps);

  // Made from this source alone: one nonzero less.
  CompactMatrix exact;
  ASSERT_EQ(exact.update(A), 0);
  EXPECT_EQ(exact.nonzeros(), nonzeros(1.0, 17));
  EXPECT_EQ(exact.nonzeros(), nonzeros(1.0, -1) - 1);

  // All zeros: an empty copy whose products are zero.
  fill(A, 0.0, -1);
  ASSERT_EQ(C.update(A), 0);
  EXPECT_EQ(C.nonzeros(), 0);
  EXPECT_LE(productDifference(A, C.get()), 0.0);
}

namespace {

// Y = M X through LocalBlocks (the refinements' products) for columns with
// entries of both signs, zeros and -0 among them.
Eigen::MatrixXd blockProduct(Mat M)
{
  PetscHandle<Vec> layout;
  EXPECT_EQ(MatCreateVecs(M, layout.address(), nullptr), 0);
  boomdyn::LocalBlocks blocks;
  EXPECT_EQ(blocks.setUp(layout), 0);
  Eigen::MatrixXd X(kRows, 7), Y(kRows, 7);
  for (PetscInt i = 0; i < kRows; ++i)
    for (int j = 0; j < 7; ++j) X(i, j) = (i + j) % 5 == 0 ? ((i + j) % 2 ? -0.0 : 0.0) : std::cos(0.3 * i * (j + 1)) - 0.2;
  EXPECT_EQ(blocks.multiply(M, X, Y), 0);
  return Y;
}

// The columns 8..13 read off M (LocalBlocks::columns): row 10's diagonal among them.
Eigen::MatrixXd blockColumns(Mat M)
{
  PetscHandle<Vec> layout;
  EXPECT_EQ(MatCreateVecs(M, layout.address(), nullptr), 0);
  boomdyn::LocalBlocks blocks;
  EXPECT_EQ(blocks.setUp(layout), 0);
  Eigen::MatrixXd C(kRows, 6);
  EXPECT_EQ(blocks.columns(M, 8, C), 0);
  return C;
}

bool bitwiseEqual(const Eigen::MatrixXd &a, const Eigen::MatrixXd &b)
{
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

} // namespace

TEST(CompactMatrix, KeepsEntriesThatTurnZeroWithBitwiseTheProductsOfAnExactCopy)
{
  PetscHandle<Mat> A;
  ASSERT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, kRows, kRows, 7, nullptr, A.address()), 0);
  CompactMatrix C;
  // The copy against one made from the source alone (without explicit
  // zeros): bitwise the same block products and columns.
  const auto expectExactProducts = [&](const char *when) {
    CompactMatrix exact;
    ASSERT_EQ(exact.update(A), 0);
    EXPECT_TRUE(bitwiseEqual(blockProduct(C.get()), blockProduct(exact.get()))) << when;
    EXPECT_TRUE(bitwiseEqual(blockColumns(C.get()), blockColumns(exact.get()))) << when;
    EXPECT_GE(C.nonzeros(), exact.nonzeros()) << when;
  };
  fill(A, 1.0, {});
  ASSERT_EQ(C.update(A), 0);
  const Mat first = C.get();
  const PetscInt all = C.nonzeros();
  expectExactProducts("made");

  // Two diagonals turn zero, then one of them nonzero again and another
  // zero (negative values: -0 products): the same copy throughout.
  fill(A, -1.5, {10, 20});
  ASSERT_EQ(C.update(A), 0);
  EXPECT_EQ(C.get(), first);
  EXPECT_EQ(C.nonzeros(), all);
  expectExactProducts("two zeros");
  fill(A, 0.75, {20, 25});
  ASSERT_EQ(C.update(A), 0);
  EXPECT_EQ(C.get(), first);
  expectExactProducts("zeros moved");

  // A nonzero where the copy has no entry: made anew with it and the
  // previous positions (the two zeros stay).
  fill(A, 0.75, {20, 25}, {9});
  ASSERT_EQ(C.update(A), 0);
  EXPECT_EQ(C.nonzeros(), all + 1); // (a new matrix, maybe at the old one's address)
  expectExactProducts("new position");

  // More zeros than a sixteenth of the entries: made anew from the
  // nonzeros alone.
  std::vector<PetscInt> many;
  for (PetscInt i = 1; i < kRows; i += 3) many.push_back(i); // diagonals that are nonzero in the pattern
  ASSERT_GT((PetscInt)many.size(), all / 16);
  fill(A, 2.0, many);
  ASSERT_EQ(C.update(A), 0);
  CompactMatrix exact;
  ASSERT_EQ(exact.update(A), 0);
  EXPECT_EQ(C.nonzeros(), exact.nonzeros());
  expectExactProducts("many zeros");
}

// A new source matrix in place of a destroyed one (the tracking's pencil
// after a contact point changed element): PETSc may give it the same
// address, and made and assembled the same way it has the same nonzero state
// and entry count, but another pattern. The copy must follow the new matrix,
// not keep the old one's positions (before: the copy held the old pattern,
// its products were wrong, and on refined meshes every later refinement
// failed and fell back to the full solve).
TEST(CompactMatrix, FollowsANewSourceAtTheAddressOfADestroyedOne)
{
  const double eps = std::numeric_limits<double>::epsilon();
  // A band without zeros, its columns shifted cyclically by `shift`: as
  // many entries per row for every shift, at other positions.
  const auto make = [](PetscInt shift, Mat *M) {
    ASSERT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, kRows, kRows, 7, nullptr, M), 0);
    for (PetscInt i = 0; i < kRows; ++i)
      for (PetscInt j = std::max<PetscInt>(0, i - 3); j <= std::min<PetscInt>(kRows - 1, i + 3); ++j)
        ASSERT_EQ(MatSetValue(*M, i, (j + shift) % kRows, std::sin(0.7 * i + 1.3 * j) + (i == j ? 5.0 : 0.0),
                              INSERT_VALUES),
                  0);
    ASSERT_EQ(MatAssemblyBegin(*M, MAT_FINAL_ASSEMBLY), 0);
    ASSERT_EQ(MatAssemblyEnd(*M, MAT_FINAL_ASSEMBLY), 0);
  };
  CompactMatrix C;
  std::uintptr_t before;
  {
    Mat A;
    make(0, &A);
    ASSERT_EQ(C.update(A), 0);
    before = reinterpret_cast<std::uintptr_t>(A);
    ASSERT_EQ(MatDestroy(&A), 0);
  }
  PetscHandle<Mat> B;
  make(5, B.address());
  if (reinterpret_cast<std::uintptr_t>(B.get()) != before)
    std::printf("  note: the new matrix did not get the old one's address; the copy is checked all the same\n");
  ASSERT_EQ(C.update(B), 0);
  EXPECT_LE(productDifference(B, C.get()), 4 * eps);
}
