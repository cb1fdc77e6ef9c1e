// The test helpers of tests/support.hpp fail when they must: a failed PETSc
// call stops the test, and states that cannot be compared are a failure,
// not a difference of 0.
#include "support.hpp"

#include <gtest/gtest-spi.h>

#include <cmath>

using namespace boomdyn::testing;

TEST(TestSupport, CheckPassesSuccess) { EXPECT_NO_THROW(check(0)); }

TEST(TestSupport, CheckStopsOnPetscError)
{
  EXPECT_THROW(check(PETSC_ERR_ARG_OUTOFRANGE), PetscCallFailed);
}

TEST(TestSupport, MaxRelativeDifferenceOfEqualStatesIsZero)
{
  EXPECT_EQ(maxRelativeDifference({1.0, -2.0, 3.0}, {1.0, -2.0, 3.0}), 0.0);
}

TEST(TestSupport, MaxRelativeDifferenceIsScaledByTheLargestEntry)
{
  // |diff| max 0.5 at index 1, max |a| = 4.
  EXPECT_DOUBLE_EQ(maxRelativeDifference({1.0, 4.0}, {1.25, 3.5}), 0.125);
}

TEST(TestSupport, MaxRelativeDifferenceFailsOnSizeMismatch)
{
  static double d; // EXPECT_NONFATAL_FAILURE's statement cannot use non-static locals
  EXPECT_NONFATAL_FAILURE(d = maxRelativeDifference({1.0, 2.0}, {1.0, 2.0, 3.0}), "different sizes (2 and 3)");
  EXPECT_TRUE(std::isinf(d));
}

TEST(TestSupport, MaxRelativeDifferenceFailsOnEmptyStates)
{
  static double d; // EXPECT_NONFATAL_FAILURE's statement cannot use non-static locals
  EXPECT_NONFATAL_FAILURE(d = maxRelativeDifference({}, {}), "empty states");
  EXPECT_TRUE(std::isinf(d));
}

TEST(TestSupport, MaxRelativeDifferenceFailsOnNaN)
{
  static double d; // EXPECT_NONFATAL_FAILURE's statement cannot use non-static locals
  EXPECT_NONFATAL_FAILURE(d = maxRelativeDifference({1.0, 2.0}, {1.0, std::nan("")}), "NaN at index 1");
  EXPECT_TRUE(std::isinf(d));
}
