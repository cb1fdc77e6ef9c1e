// PencilNorms and roundOffFloor (src/analysis/mode_refinement.cpp): the
// scales of the tracking refinements' round-off floors. The norms are the
// infinity norms (largest absolute row sum) of the matrices given to set(),
// taken when first asked for; set() forgets the values taken before, so a
// new pencil never gets the last one's norms.
#include <gtest/gtest.h>

#include "boomdyn/mode_refinement.hpp"
#include "boomdyn/petsc_handle.hpp"

#include <petscmat.h>

#include <cfloat>

namespace {

using boomdyn::PencilNorms;
using boomdyn::PetscHandle;

// A 3 x 3 matrix with rows (s, -2s, 0), (0, 0, 0), (-s, 0, 0.5s): infinity
// norm 3|s| (the first row's absolute sum).
PetscErrorCode makeMatrix(double s, Mat *A)
{
  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, 3, 3, 2, nullptr, A));
  PetscCall(MatSetValue(*A, 0, 0, s, INSERT_VALUES));
  PetscCall(MatSetValue(*A, 0, 1, -2 * s, INSERT_VALUES));
  PetscCall(MatSetValue(*A, 2, 0, -s, INSERT_VALUES));
  PetscCall(MatSetValue(*A, 2, 2, 0.5 * s, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

TEST(PencilNorms, AreTheInfinityNormsOfTheMatricesLastSet)
{
  PetscHandle<Mat> K, M, D, K2;
  ASSERT_EQ(makeMatrix(2.0, K.address()), 0);
  ASSERT_EQ(makeMatrix(-0.25, M.address()), 0);
  ASSERT_EQ(makeMatrix(4.0, D.address()), 0);
  ASSERT_EQ(makeMatrix(10.0, K2.address()), 0);
  PencilNorms norms;
  norms.set(K, M, D);
  PetscReal k = -1, m = -1, d = -1;
  ASSERT_EQ(norms.stiffness(&k), 0);
  ASSERT_EQ(norms.mass(&m), 0);
  ASSERT_EQ(norms.damping(&d), 0);
  EXPECT_DOUBLE_EQ(k, 6.0);
  EXPECT_DOUBLE_EQ(m, 0.75);
  EXPECT_DOUBLE_EQ(d, 12.0);
  // A new pencil: its norms, not the kept ones; no damping matrix: 0.
  norms.set(K2, M, nullptr);
  ASSERT_EQ(norms.stiffness(&k), 0);
  ASSERT_EQ(norms.damping(&d), 0);
  EXPECT_DOUBLE_EQ(k, 30.0);
  EXPECT_EQ(d, 0.0);
}

TEST(PencilNorms, RoundOffFloorIsOneUnitRoundOffOfTheScale)
{
  EXPECT_DOUBLE_EQ(boomdyn::roundOffFloor(1e10, 1e4), DBL_EPSILON * 1e6);
  EXPECT_EQ(boomdyn::roundOffFloor(1.0, 0.0), 0.0); // |A x| = 0: no floor
}

} // namespace
