// A mesh so fine that the Newton iteration matrix M/(beta h^2) + K is
// ill-conditioned in double precision (issue 6, item 3): the model estimates
// (omega_max h)^2 beta from the element data and warns, naming the scene,
// the body, the element length, the largest usable element count at this h
// and the largest usable h at this mesh. inputs/cantilever_dynamic.yaml at
// h = 1e-3 s: 2048 elements run, 8192 do not (the full runs are in
// scripts/extreme_cases.py; docs/extreme-cases.md).
#include "extreme_support.hpp"

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

Scene cantilever(int elements, double h)
{
  Scene scene = inputScene("cantilever_dynamic.yaml");
  scene.bodies[0].elements = elements;
  scene.dynamic.dt = h;
  scene.dynamic.dt_min = std::min(scene.dynamic.dt_min, h);
  return scene;
}

} // namespace

TEST(IllConditionedMesh, EstimateAndWarningForTheFineCantilever)
{
  for (int n : {16, 512, 2048, 4096, 8192}) {
    const Model::Conditioning k = Model(cantilever(n, 1e-3)).iterationConditioning().at(0);
    PetscPrintf(PETSC_COMM_WORLD, "  %5d elements (l = %.3e m), h = 1e-3 s: omega_max = %.3e rad/s, (omega_max h)^2 beta = %.2e, "
                "largest usable: %d elements at this h, h <= %.2e s at this mesh\n",
                n, k.elementLength, k.omegaMax, k.estimate, k.maxElements, k.maxStep);
  }
  // 2048 elements at h = 1e-3 s run (measured), so no warning there.
  EXPECT_TRUE(Model(cantilever(2048, 1e-3)).conditioningWarnings().empty());
  EXPECT_TRUE(Model(cantilever(16, 1e-3)).conditioningWarnings().empty());
  const std::vector<std::string> w = Model(cantilever(8192, 1e-3)).conditioningWarnings();
  ASSERT_EQ(w.size(), 1u);
  PetscPrintf(PETSC_COMM_WORLD, "  warning: %s\n", w[0].c_str());
  for (const char *part : {"cantilever_dynamic.yaml", "body 'boom'", "8192 elements of 0.000244 m", "h = 0.001 s",
                           "ill-conditioned", "Use at most ", "h <= "})
    EXPECT_NE(w[0].find(part), std::string::npos) << "missing '" << part << "' in: " << w[0];
  const Model::Conditioning k = Model(cantilever(8192, 1e-3)).iterationConditioning().at(0);
  EXPECT_GT(k.maxElements, 2048);
  EXPECT_LT(k.maxElements, 4096);
  EXPECT_LT(k.maxStep, 1e-3);
  // The advice is consistent: at the suggested mesh or step the warning goes away.
  EXPECT_TRUE(Model(cantilever(k.maxElements, 1e-3)).conditioningWarnings().empty());
  EXPECT_TRUE(Model(cantilever(8192, 0.99 * k.maxStep)).conditioningWarnings().empty());
  // Statics and modal analyses have no time step: no estimate.
  Scene statics = inputScene("cantilever_static.yaml");
  statics.bodies[0].elements = 8192;
  EXPECT_TRUE(Model(statics).conditioningWarnings().empty());
}

TEST(IllConditionedMesh, TwoThousandElementsRunAtOneMillisecond)
{
  // The largest measured mesh that works at h = 1e-3 s: a few steps complete
  // with finite results and the tip moving the right way.
  Scene scene = cantilever(2048, 1e-3);
  scene.dynamic.t_end = 5e-3;
  const DynamicHistory run = runDynamic(scene);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  EXPECT_TRUE(allFinite(run));
  PetscPrintf(PETSC_COMM_WORLD, "  2048 elements, h = 1e-3 s: %d steps, %d rejected, %.2f Newton/step\n", (int)run.summary.steps,
              (int)run.summary.rejected, (double)run.summary.newtonIterations / run.summary.steps);
  if (rank() == 0) EXPECT_LT(run.sensors.back()[0].position.y(), 0.0);
}
