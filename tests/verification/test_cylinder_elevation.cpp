// The cylinder-driven elevation scenes (inputs/paper_elevation_{35,70}_cylinder.yaml,
// inputs/hoist_luffing_cylinder.yaml; issue 38): boom 1 luffed by a hydraulic cylinder on a feed-forward valve
// command instead of the prescribed quintic angle of paper_elevation_{35,70}.
// The angle of boom 1's chord from the pin to the rod end (sensor
// boom1_rod_end) follows the prescribed angle within 2 % of the final angle
// at every step and ends within 2 % of it (measured 0.39 %, 0.37 % and, with
// the payload swinging, 0.74 %; the issue asks for a few percent).
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

double prescribed(double t, double finalDeg)
{
  if (t <= 1.0) return 0.0;
  if (t >= 6.73) return finalDeg;
  const double x = (t - 1.0) / 5.73;
  return finalDeg * x * x * x * (10 - 15 * x + 6 * x * x);
}

void checkElevation(const std::string &stem, double finalDeg)
{
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "7000 steps of the paper scene; its 2-rank behaviour is the solver's own";
  const std::string file = std::string(BOOMDYN_SOURCE_DIR) + "/inputs/" + stem + ".yaml";
  const Scene scene = readSceneFile(file);
  int sensor = -1;
  for (std::size_t i = 0; i < scene.output.sensors.size(); ++i)
    if (scene.output.sensors[i].name == "boom1_rod_end") sensor = static_cast<int>(i);
  ASSERT_GE(sensor, 0);
  const DynamicHistory run = runDynamic(scene, PETSC_COMM_SELF);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  double worst = 0, worstAt = 0, last = 0;
  for (std::size_t s = 0; s < run.time.size(); ++s) {
    const Vec2 &p = run.sensors[s][sensor].position;
    const double angle = std::atan2(p[1], p[0]) * 180 / M_PI;
    const double error = std::abs(angle - prescribed(run.time[s], finalDeg));
    if (error > worst) worst = error, worstAt = run.time[s];
    last = angle;
  }
  PetscPrintf(PETSC_COMM_SELF,
              "  %s: cylinder elevation to %g deg: largest deviation from the prescribed angle %.3f deg (%.2f %% of %g deg) at "
              "t = %.3f s; final %.3f deg\n",
              stem.c_str(), finalDeg, worst, 100 * worst / finalDeg, finalDeg, worstAt, last);
  EXPECT_LT(worst, 0.02 * finalDeg);
  EXPECT_NEAR(last, finalDeg, 0.02 * finalDeg);
}

} // namespace

TEST(CylinderElevation, FollowsTheAngleProfileTo35Degrees) { checkElevation("paper_elevation_35_cylinder", 35); }
TEST(CylinderElevation, FollowsTheAngleProfileTo70Degrees) { checkElevation("paper_elevation_70_cylinder", 70); }
// With the 1 t payload swinging on the hoist rope during luffing and extraction.
TEST(CylinderElevation, HoistLuffingFollowsTheAngleProfile) { checkElevation("hoist_luffing_cylinder", 35); }
