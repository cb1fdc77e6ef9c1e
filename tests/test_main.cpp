// GoogleTest main for every test executable: PETSc is initialized once per
// process so that tests may create Vec/Mat/SNES objects. Started like the
// boomdyn program (SingletonStart) when run without mpiexec.
#include <gtest/gtest.h>
#include <petscsys.h>

#include "boomdyn/singleton_start.hpp"

int main(int argc, char **argv)
{
  const boomdyn::SingletonStart singleton; // as boomdyn: fast start, a private session directory
  ::testing::InitGoogleTest(&argc, argv);
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) {
    // Only rank 0 reports; the others still run every test collectively.
    auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int result = RUN_ALL_TESTS();
  // A test failing on any rank fails the run on every rank.
  int global = 0;
  MPI_Allreduce(&result, &global, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  PetscCall(PetscFinalize());
  return global;
}
