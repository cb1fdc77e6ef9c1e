// The paper's three-boom telescope (inputs/paper_extraction_single_calibration.yaml): rope
// kinematics, and extraction across track elements.
#include "support.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

Scene paperScene()
{
  std::ifstream in(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/paper_extraction_single_calibration.yaml");
  std::stringstream text;
  text << in.rdbuf();
  return parseScene(text.str(), "paper_extraction_single_calibration.yaml");
}

// Slack coordinates: j1, j2, j3, j4 in scene order.
constexpr int J2 = 1, J4 = 3;

} // namespace

TEST(Telescope, RopeMakesBoomThreeExtendAsBoomTwo)
{
  // Rigid booms without gravity and load stay collinear and keep their
  // lengths: the rope spans are exact differences of material coordinates, so
  // boom 3's extension in boom 2 must equal boom 2's in boom 1. (Flexible
  // booms stretch axially under the extraction's inertia forces, which moves
  // material points by up to a fraction of a millimetre.)
  Scene scene = paperScene();
  scene.gravity = {0, 0};
  scene.forces.clear();
  scene.dynamic.t_end = 2.0;
  for (auto &c : scene.constraints)
    if (c.type == "extraction_drive") c.set("displacement", TimeFunction::smoothStep(0.0, 2.0, 0.0, 1.0));
  for (auto &b : scene.bodies) b.type = BodySpec::Type::Rigid;
  scene.dynamic.dt = 2e-3;
  const DynamicHistory run = runDynamic(scene);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  double worst = 0;
  for (const auto &s : run.slacks)
    worst = std::max(worst, std::abs((s[J4] - run.slacks[0][J4]) - (s[J2] - run.slacks[0][J2])));
  PetscPrintf(PETSC_COMM_WORLD, "  rope: extension of boom 2 in boom 1 %.6f m, of boom 3 in boom 2 %.6f m, max difference %.2e m\n",
              run.slacks.back()[J2] - run.slacks[0][J2], run.slacks.back()[J4] - run.slacks[0][J4], worst);
  EXPECT_NEAR(run.slacks.back()[J2] - run.slacks[0][J2], 1.0, 1e-12);
  EXPECT_LT(worst, 1e-9);
}

TEST(Telescope, LoadedExtractionRunsWithSmallViolation)
{
  // The paper scene, shortened: 0.6 m of extraction in 1 s from rest with the
  // tip load and gravity, 8 elements per boom; contact points cross elements.
  Scene scene = paperScene();
  for (auto &b : scene.bodies) b.elements = 8;
  for (auto &c : scene.constraints)
    if (c.type == "extraction_drive") c.set("displacement", TimeFunction::smoothStep(0.0, 1.0, 0.0, 0.6));
  scene.dynamic.t_end = 1.0;
  const DynamicHistory run = runDynamic(scene);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  double violation = 0;
  for (double v : run.violation) violation = std::max(violation, v);
  PetscPrintf(PETSC_COMM_WORLD, "  loaded extraction: %d steps, %d rejected, max violation %.2e, slack j2 %.4f -> %.4f m\n",
              (int)run.summary.steps, (int)run.summary.rejected, violation, run.slacks[0][J2], run.slacks.back()[J2]);
  EXPECT_LT(violation, 1e-9);
  EXPECT_NEAR(run.slacks.back()[J2] - run.slacks[0][J2], 0.6, 1e-9);
}
