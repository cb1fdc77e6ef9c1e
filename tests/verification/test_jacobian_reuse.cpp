// Jacobian reuse (modified Newton, -boom_jacobian_reuse) gives the answer of
// full Newton to within the Newton tolerance while factoring far less often,
// and sliding joints change their track element only when they cross one
// (no chatter of contact points resting on a node).
#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/scene_reader.hpp"
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;


TEST(JacobianReuse, ExtractionMatchesFullNewtonWithFewerFactorizations)
{
  const Scene scene = shortenedExtraction(0.5);
  const DynamicHistory full = runDynamicWithOption(scene, PETSC_COMM_SELF, "-boom_jacobian_reuse", "0"),
                       reused = runDynamicWithOption(scene, PETSC_COMM_SELF, "-boom_jacobian_reuse", "1");
  ASSERT_TRUE(full.summary.completed) << full.summary.failure;
  ASSERT_TRUE(reused.summary.completed) << reused.summary.failure;
  ASSERT_EQ(full.finalState.size(), reused.finalState.size());
  const double relative = maxRelativeDifference(full.finalState, reused.finalState);
  PetscPrintf(PETSC_COMM_SELF,
              "  full Newton: %d Jacobians, %d iterations; reuse: %d Jacobians, %d iterations, %d retries; "
              "final q, v differ by %.2e relative\n",
              (int)full.newton.jacobians, (int)full.newton.iterations, (int)reused.newton.jacobians,
              (int)reused.newton.iterations, (int)reused.newton.retriesWithFreshJacobian, relative);
  // Both solve every step to the same Newton tolerance (1e-10 relative).
  EXPECT_LT(relative, 1e-7);
  EXPECT_EQ(full.newton.jacobians, full.newton.iterations);
  EXPECT_LT(reused.newton.jacobians, full.newton.jacobians / 5);
  EXPECT_EQ(full.summary.steps, reused.summary.steps);
}

TEST(JacobianReuse, ContactPointsChangeElementsOnlyWhenTheyCrossOne)
{
  const Scene scene = shortenedExtraction(0.5);
  const DynamicHistory h = runDynamicWithOption(scene, PETSC_COMM_SELF, "-boom_jacobian_reuse", "1");
  ASSERT_TRUE(h.summary.completed) << h.summary.failure;
  // Element crossings of every joint along its slack history.
  Model model(scene);
  int crossings = 0;
  for (std::size_t j = 0; j < model.slidingJoints().size(); ++j) {
    const Body &track = model.slidingJoints()[j]->track();
    const auto *beam = dynamic_cast<const AncfBeam *>(&track);
    ASSERT_NE(beam, nullptr);
    const double le = beam->elementLength();
    const double s0 = h.slacks.front()[j], s1 = h.slacks.back()[j];
    crossings += std::abs(static_cast<int>(std::floor(s1 / le + 0.5)) - static_cast<int>(std::floor(s0 / le + 0.5)));
  }
  PetscPrintf(PETSC_COMM_SELF, "  %d pattern rebuilds for about %d element crossings in %d steps\n", h.patternVersion,
              crossings, (int)h.summary.steps);
  // One rebuild per crossing (plus one per joint starting on a node); the
  // chatter this test guards against rebuilt at a third of all steps.
  EXPECT_LE(h.patternVersion, crossings + static_cast<int>(model.slidingJoints().size()));
}
