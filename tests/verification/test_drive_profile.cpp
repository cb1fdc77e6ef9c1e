// The accel-limited drive profile in a run: inputs/sleeve_push.yaml pushes a
// rod through a sleeve at 1 m/s with a ramp (the rate jumps from 0 to 1 m/s
// at t = 0 and back at 0.8 s); the same push with an accel-limited move at
// the same speed (accel 5 m/s^2, unlimited jerk) needs a drive force
// m a = 50 N instead of the impulse of the jump. The slack coordinate
// follows the profile exactly.
#include "boomdyn/scene_reader.hpp"
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// Row of the drive's multiplier: clamp (3 rows), rear (2), front (2), push (1).
constexpr int kPushRow = 7;

Scene sleevePush(const TimeFunction &displacement, double tEnd)
{
  Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/sleeve_push.yaml");
  for (ComponentSpec &c : scene.constraints)
    if (c.name == "push") c.set("displacement", displacement);
  scene.dynamic.t_end = tEnd;
  return scene;
}

double peakDriveForce(const DynamicHistory &h)
{
  double peak = 0;
  for (const auto &row : h.multipliers) peak = std::max(peak, std::abs(row[kPushRow]));
  return peak;
}

} // namespace

TEST(DriveProfile, AccelLimitedPushCutsThePeakAxialForce)
{
  const double speed = 1.0, distance = 0.8, accel = 5.0;
  const TimeFunction ramp = TimeFunction::ramp(0.0, distance / speed, 0.0, distance);
  const TimeFunction move = TimeFunction::accelLimited(0.0, 0.0, distance, speed, accel);
  const double tEnd = move.endTime() + 0.05;
  const DynamicHistory withRamp = runDynamic(sleevePush(ramp, tEnd), PETSC_COMM_SELF);
  const DynamicHistory withMove = runDynamic(sleevePush(move, tEnd), PETSC_COMM_SELF);
  ASSERT_TRUE(withRamp.summary.completed) << withRamp.summary.failure;
  ASSERT_TRUE(withMove.summary.completed) << withMove.summary.failure;
  const double peakRamp = peakDriveForce(withRamp), peakMove = peakDriveForce(withMove);
  // The rod (10 kg) pushed at 5 m/s^2 needs 50 N; the elastic rod adds its axial vibration.
  const double rodMass = 2.0 * 5.0;
  PetscPrintf(PETSC_COMM_SELF, "  sleeve push: peak drive force %.1f N with the ramp, %.2f N accel-limited (m a = %.1f N), ratio %.1f\n",
              peakRamp, peakMove, rodMass * accel, peakRamp / peakMove);
  EXPECT_GT(peakRamp, 10.0 * peakMove);
  EXPECT_LT(peakMove, 2.0 * rodMass * accel);
  // The contact coordinate follows the move (position-level constraint).
  double worst = 0;
  for (std::size_t k = 0; k < withMove.time.size(); ++k)
    worst = std::max(worst, std::abs(withMove.slacks[k][0] - withMove.slacks[0][0] - move.value(withMove.time[k])));
  PetscPrintf(PETSC_COMM_SELF, "  slack coordinate vs the move: max difference %.2e m\n", worst);
  EXPECT_LT(worst, 1e-10);
}
