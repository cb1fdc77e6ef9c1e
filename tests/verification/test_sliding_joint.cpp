// A flexible rod pushed at constant speed through a fixed sleeve: two
// sliding joints (the sleeve's two ends slide along the rod) and an
// extraction drive on the first joint's slack coordinate. The contact points
// cross many rod elements; s(t) must follow the drive exactly and the normal
// forces lambda_n(t) must show no jumps at element boundaries beyond the
// discretization level and converge under mesh refinement.
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kSpeed = 1.0, kEnd = 0.8;

Scene sleeveScene(int elements, double dt)
{
  Scene sc;
  sc.file = "sleeve.yaml";
  sc.name = "sleeve";
  sc.analysis = Scene::Analysis::Dynamic;
  sc.gravity = {0, -9.81};
  BodySpec rod;
  rod.name = "rod";
  rod.length = 2.0;
  rod.elements = elements;
  rod.origin = {-0.4, 0.0};
  rod.section = {1.0e7, 2.0e3, 5.0};
  BodySpec sleeve;
  sleeve.name = "sleeve";
  sleeve.length = 0.25;
  sleeve.elements = 1;
  sleeve.section = {1.0e9, 1.0e7, 10.0};
  sc.bodies = {rod, sleeve};
  ComponentSpec clamp("clamp", "sleeve_clamp");
  clamp.set("body", "sleeve").set("at", 0.0).set("point", Vec2d{0.0, 0.0}).set("angle", TimeFunction::constant(0.0));
  ComponentSpec rear("sliding_joint", "rear"), front("sliding_joint", "front"), drive("extraction_drive", "push");
  rear.set("body", "sleeve").set("at", 0.0).set("track", "rod");
  front.set("body", "sleeve").set("at", 0.25).set("track", "rod");
  drive.set("joint", "rear");
  // s of the rear pad grows: the rod moves backwards (-x) through the sleeve.
  drive.set("displacement", TimeFunction::ramp(0.0, kEnd, 0.0, kSpeed * kEnd));
  sc.constraints = {clamp, rear, front, drive};
  sc.dynamic.t_end = kEnd;
  sc.dynamic.dt = dt;
  sc.dynamic.rho_inf = 0.8;
  sc.output.sensors = {ComponentSpec("point_sensor", "tip").set("body", "rod").set("at", 2.0)};
  return sc;
}

} // namespace

TEST(SlidingJoint, RodPushedThroughSleeveCrossesElementsSmoothly)
{
  const Scene scene = sleeveScene(16, 1e-3);
  const Model model(scene);
  ASSERT_EQ(model.slidingJoints().size(), 2u);
  const DynamicHistory run = runDynamic(scene);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  EXPECT_EQ(run.summary.rejected, 0);
  double maxViolation = 0;
  for (double v : run.violation) maxViolation = std::max(maxViolation, v);
  PetscPrintf(PETSC_COMM_WORLD, "  sleeve, 16 elements: %d steps, max constraint violation %.2e\n",
              (int)run.summary.steps, maxViolation);
  EXPECT_LT(maxViolation, 1e-9);
}

namespace {

// Row of the normal force of a joint: constraints are clamp (3 rows), rear (2), front (2), push (1).
constexpr int kRearNormal = 4, kFrontNormal = 6;

} // namespace

TEST(SlidingJoint, SlackFollowsDriveAndNormalForceHasNoJumps)
{
  const int elements = 16;
  const DynamicHistory run = runDynamic(sleeveScene(elements, 1e-3));
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  const double l = 2.0 / elements;
  double driveError = 0;
  for (std::size_t k = 0; k < run.time.size(); ++k)
    driveError = std::max(driveError, std::abs(run.slacks[k][0] - (0.4 + kSpeed * run.time[k])));
  EXPECT_LT(driveError, 1e-10) << "the rear slack coordinate must follow the drive";
  // The front pad (0.25 m ahead) moves with it: s_front - s_rear stays near 0.25 m.
  EXPECT_NEAR(run.slacks.back()[1] - run.slacks.back()[0], 0.25, 1e-3);

  // Jumps: at a step where a contact point crosses an element boundary, the
  // change of lambda_n must be of the size of the changes around it.
  int crossings = 0;
  double worst = 0;
  for (int joint = 0; joint < 2; ++joint) {
    const int row = joint == 0 ? kRearNormal : kFrontNormal;
    for (std::size_t k = 2; k + 2 < run.time.size(); ++k) {
      if (std::floor(run.slacks[k][joint] / l) == std::floor(run.slacks[k + 1][joint] / l)) continue;
      ++crossings;
      auto inc = [&](std::size_t i) { return std::abs(run.multipliers[i + 1][row] - run.multipliers[i][row]); };
      const double around = std::max({inc(k - 2), inc(k - 1), inc(k + 1), inc(k + 2)});
      worst = std::max(worst, inc(k) / around);
    }
  }
  PetscPrintf(PETSC_COMM_WORLD,
              "  sleeve: drive error %.2e m, %d element crossings, worst lambda_n increment at a crossing / "
              "largest neighbouring increment = %.2f\n",
              driveError, crossings, worst);
  EXPECT_GE(crossings, 10);
  EXPECT_LT(worst, 2.0);
}

TEST(SlidingJoint, NormalForceConvergesUnderMeshRefinement)
{
  // lambda_n(t) of the front pad for 8, 16, 32 elements against 64; h fixed.
  const std::vector<int> meshes{8, 16, 32, 64};
  std::vector<std::vector<double>> forces;
  for (int n : meshes) {
    const DynamicHistory run = runDynamic(sleeveScene(n, 1e-3));
    ASSERT_TRUE(run.summary.completed) << run.summary.failure;
    std::vector<double> f;
    for (const auto &m : run.multipliers) f.push_back(m[kFrontNormal]);
    forces.push_back(f);
  }
  std::vector<double> errors;
  for (std::size_t i = 0; i + 1 < meshes.size(); ++i) {
    double e = 0, scale = 0;
    for (std::size_t k = 0; k < forces[i].size(); ++k) {
      e = std::max(e, std::abs(forces[i][k] - forces.back()[k]));
      scale = std::max(scale, std::abs(forces.back()[k]));
    }
    errors.push_back(e / scale);
    PetscPrintf(PETSC_COMM_WORLD, "  sleeve, %2d elements: max |lambda_n - lambda_n(64)| / max |lambda_n(64)| = %.3e%s\n",
                meshes[i], errors.back(),
                i ? (", rate " + std::to_string(std::log2(errors[i - 1] / errors[i]))).c_str() : "");
  }
  EXPECT_LT(errors[2], errors[1]);
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_GT(std::log2(errors[1] / errors[2]), 1.0) << "at least first-order convergence of lambda_n";
}

TEST(SlidingJoint, SliderLeavingItsTrackStopsTheRunWithAMessage)
{
  // Push 2 m/s for 1 s: the front pad (starting at s = 0.65 m) reaches the
  // rod's end (s = 2 m) near t = 0.68 s.
  Scene scene = sleeveScene(16, 2e-3);
  scene.constraints.back().set("displacement", TimeFunction::ramp(0.0, 1.0, 0.0, 2.0));
  scene.dynamic.t_end = 1.0;
  const DynamicHistory run = runDynamic(scene);
  EXPECT_FALSE(run.summary.completed);
  const std::string &msg = run.summary.failure;
  PetscPrintf(PETSC_COMM_WORLD, "  message: %s\n", msg.c_str());
  EXPECT_NE(msg.find("sliding joint 'front' left its track 'rod'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("t = 0.6"), std::string::npos) << msg;
  EXPECT_NE(msg.find("s = 2.0"), std::string::npos) << msg;
  EXPECT_NEAR(run.time.back(), 0.675, 0.01) << "the run stops at the last step that kept the slider on the track";
}
