// The interface Schur-complement solver (-boom_schur_dd) is an exact direct
// solver: runs with it match the default solver (KLU on one rank) to the
// Newton tolerance, on one rank and, under mpi2.verification, on two, where
// the interface holds the cut of each boom, the joints' multipliers and
// slack coordinates, and the rope.
#include "boomdyn/scene_reader.hpp"
#include "support.hpp"

#include <cmath>

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
