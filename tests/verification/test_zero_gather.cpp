// ZeroGather (boomdyn/gather.hpp): the gather to rank 0 that keeps its
// scatter between calls (the tracking's mode shapes, gatherShape). On any
// rank count: rank 0 receives the first `count` entries of each vector, in
// order, also when vectors of another layout (other local sizes, another
// global size) come in between, for which the kept scatter would be wrong
// and must be made anew; the other ranks receive nothing.
#include <gtest/gtest.h>

#include "boomdyn/gather.hpp"

#include <petscvec.h>

#include <vector>

namespace {

using boomdyn::PetscHandle;
using boomdyn::ZeroGather;

// A vector of `global` entries (entry i = 0.5 i - 3 + offset) with this
// rank's `local` entries (PETSC_DECIDE: PETSc's split).
PetscHandle<Vec> makeVector(PetscInt local, PetscInt global, double offset)
{
  PetscHandle<Vec> v;
  EXPECT_EQ(VecCreateMPI(PETSC_COMM_WORLD, local, global, v.address()), 0);
  PetscInt lo, hi;
  EXPECT_EQ(VecGetOwnershipRange(v, &lo, &hi), 0);
  for (PetscInt i = lo; i < hi; ++i) EXPECT_EQ(VecSetValue(v, i, 0.5 * i - 3 + offset, INSERT_VALUES), 0);
  EXPECT_EQ(VecAssemblyBegin(v), 0);
  EXPECT_EQ(VecAssemblyEnd(v), 0);
  return v;
}

void expectGathered(ZeroGather &gather, Vec v, PetscInt count, double offset, const char *what)
{
  PetscMPIInt rank;
  PetscInt n;
  ASSERT_EQ(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), 0);
  ASSERT_EQ(VecGetSize(v, &n), 0);
  std::vector<double> out{1.0, 2.0}; // replaced
  ASSERT_EQ(gather.gather(v, out, count), 0);
  if (rank != 0) {
    EXPECT_TRUE(out.empty()) << what;
    return;
  }
  const PetscInt expected = count < 0 ? n : std::min(count, n);
  ASSERT_EQ((PetscInt)out.size(), expected) << what;
  for (PetscInt i = 0; i < expected; ++i) EXPECT_EQ(out[i], 0.5 * i - 3 + offset) << what << ", entry " << i;
}

} // namespace

TEST(ZeroGather, FollowsTheLayoutOfEachVector)
{
  PetscMPIInt rank, size;
  ASSERT_EQ(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), 0);
  ASSERT_EQ(MPI_Comm_size(PETSC_COMM_WORLD, &size), 0);
  ZeroGather gather;
  PetscHandle<Vec> a = makeVector(PETSC_DECIDE, 23, 0.0), b = makeVector(PETSC_DECIDE, 23, 1.0);
  expectGathered(gather, a, -1, 0.0, "first vector");
  expectGathered(gather, b, 17, 1.0, "another vector of the same layout, first 17 entries");
  expectGathered(gather, a, 40, 0.0, "count beyond the size");
  // Another split of the same 23 entries (rank 0 holds 3 more than
  // PETSc's split, the last rank 3 fewer; on one rank the same layout).
  const PetscInt base = 23 / size + (rank < 23 % size ? 1 : 0);
  const PetscInt shifted = base + (size > 1 ? (rank == 0 ? 3 : rank == size - 1 ? -3 : 0) : 0);
  PetscHandle<Vec> c = makeVector(shifted, 23, 2.0);
  expectGathered(gather, c, -1, 2.0, "other local sizes");
  expectGathered(gather, a, -1, 0.0, "back to the first layout");
  // Another global size.
  PetscHandle<Vec> d = makeVector(PETSC_DECIDE, 31, 3.0);
  expectGathered(gather, d, 25, 3.0, "another global size");
  expectGathered(gather, b, -1, 1.0, "back again");
}
