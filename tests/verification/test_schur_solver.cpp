// The interface Schur-complement solver (-boom_schur_dd) is an exact direct
// solver: runs with it match the default solver (KLU on one rank) to the
// Newton tolerance, on one rank and, under mpi2.verification, on two, where
// the interface holds the cut of each boom, the joints' multipliers and
// slack coordinates, and the rope. And the solver alone on an assembled
// system (below).
#include "boomdyn/petsc_handle.hpp"
#include "boomdyn/scene_reader.hpp"
#include "boomdyn/schur_complement_solver.hpp"
#include "support.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

using namespace boomdyn;
using namespace boomdyn::testing;


TEST(SchurComplementSolver, ExtractionSceneMatchesDefaultSolver)
{
  const Scene scene = shortenedExtraction(0.3);
  const DynamicHistory schur = runDynamicWithOption(scene, PETSC_COMM_WORLD, "-boom_schur_dd", "1");
  const DynamicHistory reference = runDynamic(scene, PETSC_COMM_SELF);
  ASSERT_TRUE(schur.summary.completed) << schur.summary.failure;
  ASSERT_TRUE(reference.summary.completed) << reference.summary.failure;
  EXPECT_EQ(schur.summary.steps, reference.summary.steps);
  const double d = maxRelativeDifference(reference.finalState, schur.finalState);
  PetscPrintf(PETSC_COMM_WORLD, "  extraction with the Schur-complement solver vs KLU: %.3e relative\n", d);
  EXPECT_LT(d, 1e-9);
}

TEST(SchurComplementSolver, LongCantileverMatchesDefaultSolver)
{
  Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/benchmarks/scenes/long_boom.yaml");
  scene.bodies[0].elements = 400;
  scene.dynamic.t_end = 0.03;
  const DynamicHistory schur = runDynamicWithOption(scene, PETSC_COMM_WORLD, "-boom_schur_dd", "1");
  const DynamicHistory reference = runDynamic(scene, PETSC_COMM_SELF);
  ASSERT_TRUE(schur.summary.completed) << schur.summary.failure;
  ASSERT_TRUE(reference.summary.completed) << reference.summary.failure;
  // The deflection is small against the coordinates (100 m): compare the
  // tip's y (coordinate 4 N + 1 of the one beam; finalState is on every rank).
  const std::size_t tipY = 4 * static_cast<std::size_t>(scene.bodies[0].elements) + 1;
  const double ref = reference.finalState[tipY], got = schur.finalState[tipY];
  const double d = std::abs(got - ref) / std::abs(ref);
  PetscPrintf(PETSC_COMM_WORLD, "  long cantilever, tip deflection %.6e m, Schur-complement solver vs KLU: %.3e relative\n",
              ref, d);
  EXPECT_GT(std::abs(ref), 1e-5); // moving: 48 um after 30 ms
  EXPECT_LT(d, 1e-8);
}

// The solver on an assembled system, on one rank and (mpi2.verification) on
// two: a banded nonsymmetric chain with a symmetric pattern, plus two
// "multiplier" rows (zero diagonal) tying unknowns of different ranks'
// pieces, the way a clamp's multipliers (numbered last, on the last rank)
// tie the clamped node on rank 0. The preconditioner is the exact inverse:
// ||A x - b|| / ||b|| <= 1e-12, also after the values change (same pattern:
// the interior factorization is refactored and its factors extracted again).
// The interior unknowns coupled to the interface come last in the interior
// factorization (CAMD), and with a dominant diagonal pivoting keeps them there.
namespace {

constexpr PetscInt kChain = 60;

// Row i < kChain of the banded chain both systems share (bandwidth 2, a
// dominant diagonal; s changes the values, not the pattern).
void setChainRow(Mat A, PetscInt i, double s)
{
  check(MatSetValue(A, i, i, 10.0 + 0.1 * i * s, INSERT_VALUES));
  for (PetscInt k = 1; k <= 2; ++k) {
    if (i - k >= 0) check(MatSetValue(A, i, i - k, -1.0 - 0.03 * k * s + 0.01 * i, INSERT_VALUES));
    if (i + k < kChain) check(MatSetValue(A, i, i + k, -1.5 + 0.02 * k * s, INSERT_VALUES));
  }
}

void fillSystem(Mat A, double s)
{
  PetscInt start, end;
  check(MatGetOwnershipRange(A, &start, &end));
  const PetscInt n = kChain, tied[2][2] = {{1, 2 * n / 3}, {n / 2 + 3, n - 5}};
  for (PetscInt i = start; i < end; ++i) {
    if (i < n) {
      setChainRow(A, i, s);
      for (int m = 0; m < 2; ++m)
        for (PetscInt t : tied[m])
          if (t == i) check(MatSetValue(A, i, n + m, 1.0 + 0.1 * m, INSERT_VALUES));
    } else {
      const int m = static_cast<int>(i - n);
      check(MatSetValue(A, i, tied[m][0], 1.0 + 0.1 * m, INSERT_VALUES));
      check(MatSetValue(A, i, tied[m][1], -(0.5 + 0.2 * s), INSERT_VALUES));
      check(MatSetValue(A, i, i, 0.0, INSERT_VALUES));
    }
  }
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
}

double relativeResidual(KSP ksp, Mat A, double shift)
{
  PetscHandle<Vec> b, x, r;
  check(MatCreateVecs(A, x.address(), b.address()));
  check(VecDuplicate(b, r.address()));
  PetscInt start, end;
  check(VecGetOwnershipRange(b, &start, &end));
  for (PetscInt i = start; i < end; ++i) check(VecSetValue(b, i, std::sin(0.7 * i + shift) + 0.3, INSERT_VALUES));
  check(VecAssemblyBegin(b));
  check(VecAssemblyEnd(b));
  check(KSPSolve(ksp, b, x));
  check(MatMult(A, x, r));
  check(VecAXPY(r, -1.0, b));
  PetscReal rn, bn;
  check(VecNorm(r, NORM_2, &rn));
  check(VecNorm(b, NORM_2, &bn));
  return rn / bn;
}

// A KSP with the interface Schur complement for A, set up (factored).
void setUpSchurSolver(Mat A, PetscHandle<KSP> &ksp)
{
  check(KSPCreate(PETSC_COMM_WORLD, ksp.address()));
  check(useSchurComplementSolver(ksp));
  check(KSPSetOperators(ksp, A, A));
  check(KSPSetUp(ksp));
}

} // namespace

TEST(SchurComplementSolver, SolvesAssembledSystemExactlyAndOrdersCoupledUnknownsLast)
{
  PetscHandle<Mat> A;
  const PetscInt n = kChain + 2;
  check(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, n, n, 8, nullptr, 8, nullptr, A.address()));
  fillSystem(A, 0.0);
  PetscHandle<KSP> ksp;
  setUpSchurSolver(A, ksp);
  for (int round = 0; round < 3; ++round) {
    if (round > 0) { // new values, same pattern and operator: the refactorization path
      fillSystem(A, 1.0 * round);
      check(KSPSetOperators(ksp, A, A));
    }
    for (int rhs = 0; rhs < 2; ++rhs) {
      const double res = relativeResidual(ksp, A, 0.37 * rhs + round);
      PetscPrintf(PETSC_COMM_WORLD, "  assembled system, round %d, right-hand side %d: ||Ax - b|| / ||b|| = %.2e\n", round, rhs,
                  res);
      EXPECT_LE(res, 1e-12) << "round " << round << ", right-hand side " << rhs;
    }
    SchurComplementLayout layout;
    check(schurComplementLayout(ksp, &layout));
    EXPECT_GT(layout.interface, 0);
    EXPECT_GT(layout.coupled, 0);
    EXPECT_LE(layout.coupled, layout.interior);
    // J last in the row order (CAMD's constraint) and, with this dominant
    // diagonal, in the pivoted column order too.
    EXPECT_EQ(layout.firstRow, layout.interior - layout.coupled);
    EXPECT_EQ(layout.firstColumn, layout.interior - layout.coupled);
  }
}

// A cantilever's clamp, numbered the way boomdyn numbers it: the chain's
// unknowns first, a cross-rank "rope" multiplier row (tying unknown 5 to
// unknown kChain - 10), then the clamp's three multiplier rows last, on the
// last rank, with columns only at the clamped unknowns 0..2 (rank 0's) and
// themselves (stored zeros). On several ranks rank 0 adopts the clamp rows
// into its interior (with 0..2, which then couple to no other rank), the
// rope row stays on the interface; the preconditioner is still the exact
// inverse, before and after refactorizations with new values.
namespace {

constexpr PetscInt kRope = kChain, kClamp = kChain + 1, kClampedSize = kChain + 4;

void fillClampedSystem(Mat A, double s)
{
  PetscInt start, end;
  check(MatGetOwnershipRange(A, &start, &end));
  const PetscInt n = kChain, tied[2] = {5, n - 10};
  for (PetscInt i = start; i < end; ++i) {
    if (i < n) {
      setChainRow(A, i, s);
      if (i == tied[0] || i == tied[1]) check(MatSetValue(A, i, kRope, i == tied[0] ? 1.0 : -0.7, INSERT_VALUES));
      if (i < 3)
        for (PetscInt m = 0; m < 3; ++m) check(MatSetValue(A, i, kClamp + m, (m == i ? 1.0 : 0.2 * (m + 1)) * (1.0 + 0.1 * s), INSERT_VALUES));
    } else if (i == kRope) {
      check(MatSetValue(A, i, tied[0], 1.0, INSERT_VALUES));
      check(MatSetValue(A, i, tied[1], -(0.7 + 0.2 * s), INSERT_VALUES));
      check(MatSetValue(A, i, i, 0.0, INSERT_VALUES));
    } else {
      const PetscInt m = i - kClamp;
      for (PetscInt c = 0; c < 3; ++c) check(MatSetValue(A, i, c, (m == c ? 2.0 : -0.3 * (c + 1)) * (1.0 + 0.05 * s), INSERT_VALUES));
      for (PetscInt c = 0; c < 3; ++c) check(MatSetValue(A, i, kClamp + c, 0.0, INSERT_VALUES));
    }
  }
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
}

} // namespace

TEST(SchurComplementSolver, AdoptsClampRowsIntoTheClampedRanksInterior)
{
  PetscHandle<Mat> A;
  check(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, kClampedSize, kClampedSize, 10, nullptr, 10, nullptr,
                     A.address()));
  fillClampedSystem(A, 0.0);
  PetscHandle<KSP> ksp;
  setUpSchurSolver(A, ksp);
  PetscMPIInt size, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (int round = 0; round < 3; ++round) {
    if (round > 0) {
      fillClampedSystem(A, 1.0 * round);
      check(KSPSetOperators(ksp, A, A));
    }
    for (int rhs = 0; rhs < 2; ++rhs) {
      const double res = relativeResidual(ksp, A, 0.41 * rhs + round);
      PetscPrintf(PETSC_COMM_WORLD, "  clamped system, round %d, right-hand side %d: ||Ax - b|| / ||b|| = %.2e\n", round, rhs, res);
      EXPECT_LE(res, 1e-12) << "round " << round << ", right-hand side " << rhs;
    }
    SchurComplementLayout layout;
    check(schurComplementLayout(ksp, &layout));
    const auto onInterface = [&](PetscInt g) {
      return std::find(layout.interfaceRows.begin(), layout.interfaceRows.end(), g) != layout.interfaceRows.end();
    };
    if (size == 1) {
      EXPECT_TRUE(layout.adoptedRows.empty());
      EXPECT_EQ(layout.given, 0);
    } else if (rank == 0) {
      EXPECT_EQ(layout.adoptedRows, (std::vector<PetscInt>{kClamp, kClamp + 1, kClamp + 2}));
      EXPECT_EQ(layout.given, 0);
      for (PetscInt g = 0; g < 3; ++g) EXPECT_FALSE(onInterface(g)) << "clamped unknown " << g;
      EXPECT_TRUE(onInterface(5)); // the rope's end stays coupled to the last rank
      // The interior holds the adopted rows; the interface is the cut and the rope's end.
      EXPECT_EQ(layout.interface, 3);
    } else {
      EXPECT_TRUE(layout.adoptedRows.empty());
      EXPECT_EQ(layout.given, rank == size - 1 ? 3 : 0);
      for (PetscInt g = kClamp; g < kClamp + 3; ++g) EXPECT_FALSE(onInterface(g));
      if (rank == size - 1) EXPECT_TRUE(onInterface(kRope));
    }
  }
}
