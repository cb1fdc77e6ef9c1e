// A rigid block on a rigid track on a fixed incline, no friction: two sliding
// joints hold the block on the track, gravity pulls it down the slope, and
// its contact coordinate follows s(t) = s0 - g sin(theta) t^2 / 2.
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

TEST(RigidIncline, FrictionlessSlideFollowsConstantAcceleration)
{
  const double theta = 30.0 * M_PI / 180.0, g = 9.81, s0 = 3.0;
  const std::string text = R"(
name: rigid-incline
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: ramp, type: rigid, length: 4.0, angle: 30, section: {rhoA: 50}}
  - {name: block, type: rigid, length: 0.5, origin: [2.598076211353316, 1.5], angle: 30, section: {rhoA: 20}}
constraints:
  - {type: clamp, body: ramp, at: start}
  - {type: sliding_joint, name: rear, body: block, at: start, track: ramp}
  - {type: sliding_joint, name: front, body: block, at: end, track: ramp}
dynamic: {t_end: 0.6, dt: 1.0e-2, rho_inf: 0.8}
)";
  const DynamicHistory run = runDynamic(parseScene(text, "rigid-incline.yaml"));
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  double worst = 0;
  for (std::size_t k = 1; k < run.time.size(); ++k) {
    const double t = run.time[k], travel = 0.5 * g * std::sin(theta) * t * t;
    const double err = std::abs((s0 - run.slacks[k][0]) - travel) / travel;
    worst = std::max(worst, err);
  }
  PetscPrintf(PETSC_COMM_WORLD, "  rigid incline: s(0.6) = %.12f m (exact %.12f), worst relative error of the travel %.2e\n",
              run.slacks.back()[0], s0 - 0.5 * g * std::sin(theta) * 0.36, worst);
  EXPECT_LT(worst, 1e-8);
  EXPECT_NEAR(run.slacks.back()[1] - run.slacks.back()[0], 0.5, 1e-12) << "the block keeps its length on the track";
}
