// Newton's start of a time step (-boom_acceleration_predictor, docs/model.md
// §4.2): q_n + h v_n + h^2/2 a_n when that predicted the previous step better
// than q_n + h v_n. It must save work in smooth motion, give the same answer
// to the Newton tolerance, and never cut a step that q_n + h v_n solves (a
// failed solve from it is redone from q_n + h v_n).
#include "boomdyn/scene_reader.hpp"
#include "support.hpp"

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

struct PredictorPair {
  DynamicHistory withAcceleration, velocityOnly;
};

PredictorPair runBoth(const Scene &scene)
{
  PredictorPair p;
  p.withAcceleration = runDynamic(scene, PETSC_COMM_SELF, 0, true, true);
  p.velocityOnly = runDynamic(scene, PETSC_COMM_SELF, 0, true, false);
  return p;
}

void report(const char *what, const PredictorPair &p, double relative)
{
  PetscPrintf(PETSC_COMM_SELF,
              "  %s: with acceleration %d steps (%d rejected), %d iterations, %d Jacobians; q + h v only %d steps (%d "
              "rejected), %d iterations, %d Jacobians; final q, v differ by %.2e relative\n",
              what, (int)p.withAcceleration.summary.steps, (int)p.withAcceleration.summary.rejected,
              (int)p.withAcceleration.newton.iterations, (int)p.withAcceleration.newton.jacobians,
              (int)p.velocityOnly.summary.steps, (int)p.velocityOnly.summary.rejected,
              (int)p.velocityOnly.newton.iterations, (int)p.velocityOnly.newton.jacobians, relative);
}

} // namespace

TEST(NewtonPredictor, SmoothExtractionBuildsFewerJacobiansForTheSameAnswer)
{
  const PredictorPair p = runBoth(shortenedExtraction(0.5));
  ASSERT_TRUE(p.withAcceleration.summary.completed) << p.withAcceleration.summary.failure;
  ASSERT_TRUE(p.velocityOnly.summary.completed) << p.velocityOnly.summary.failure;
  const double relative = maxRelativeDifference(p.withAcceleration.finalState, p.velocityOnly.finalState);
  report("extraction, 0.5 s", p, relative);
  EXPECT_EQ(p.withAcceleration.summary.steps, p.velocityOnly.summary.steps);
  // Both solve every step to the same Newton tolerance (as JacobianReuse's
  // comparison of modified and full Newton).
  EXPECT_LT(relative, 1e-7);
  // With a start nearer the solution the kept matrix contracts well enough
  // more often, so fewer Jacobians are built (measured 62 against 134). The
  // iterations: about the same in this first half second (2923 against
  // 2865); over the whole paper scene they drop too (34 928 -> 29 907
  // residuals, 963 -> 753 factorizations, docs/performance.md).
  EXPECT_LT(p.withAcceleration.newton.jacobians, 0.75 * p.velocityOnly.newton.jacobians);
  EXPECT_LT(p.withAcceleration.newton.iterations, 1.05 * p.velocityOnly.newton.iterations);
}

TEST(NewtonPredictor, StepLoadAtALargeStepIsNotCutMoreOften)
{
  // The 10 kN step load on the cantilever at h = 50 ms: the accelerations of
  // the first steps are the stiff modes' transients. Without the fallback to
  // q + h v the acceleration predictor cut these steps down to 0.1 ms.
  Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/cantilever_dynamic.yaml");
  scene.dynamic.dt = 0.05;
  scene.dynamic.t_end = 0.5;
  const PredictorPair p = runBoth(scene);
  ASSERT_TRUE(p.withAcceleration.summary.completed) << p.withAcceleration.summary.failure;
  ASSERT_TRUE(p.velocityOnly.summary.completed) << p.velocityOnly.summary.failure;
  const double relative = maxRelativeDifference(p.withAcceleration.finalState, p.velocityOnly.finalState);
  report("cantilever, h = 50 ms, step load", p, relative);
  EXPECT_LE(p.withAcceleration.summary.rejected, p.velocityOnly.summary.rejected);
  EXPECT_LE(p.withAcceleration.summary.steps, p.velocityOnly.summary.steps);
  EXPECT_LT(relative, 1e-7);
}
