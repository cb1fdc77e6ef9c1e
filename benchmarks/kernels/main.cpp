// Google Benchmark main for the kernel and assembly micro-benchmarks: PETSc
// is initialized once around benchmark::RunSpecifiedBenchmarks so that the
// assembly benchmarks can build Vec/Mat objects. --benchmark_* flags are
// consumed by Google Benchmark before PETSc sees the command line.
#include <benchmark/benchmark.h>
#include <petscsys.h>

namespace boomdyn::bench {
void releaseAssemblyFixtures(); // assembly.cpp: PETSc objects must go before PetscFinalize
}

int main(int argc, char **argv)
{
  benchmark::Initialize(&argc, argv);
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  boomdyn::bench::releaseAssemblyFixtures();
  PetscCall(PetscFinalize());
  return 0;
}
