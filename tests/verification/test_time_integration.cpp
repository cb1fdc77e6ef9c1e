// Generalized-alpha on constrained flexible systems: measured order of
// accuracy in h of a dynamic cantilever's tip displacement for several
// rho_inf, and energy conservation (rho_inf = 1) of a flexible pendulum
// released horizontally, with its pin violation.
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// A flexible cantilever (first bending mode 17.7 Hz, axial modes near 250 Hz)
// under a tip load ramped smoothly to P L^2/EI = 1 (large deflection).
Scene cantilever(double h, double rho)
{
  std::string s = R"(
name: order-cantilever
analysis: dynamic
bodies:
  - {name: boom, length: 1.0, elements: 4, section: {EA: 1.0e6, EI: 1.0e3, rhoA: 1.0}}
constraints:
  - {type: clamp, body: boom, at: start}
loads:
  - type: point_force
    body: boom
    at: end
    force: [0, -1000]
    scale: {type: smooth_step, t0: 0, t1: 0.05, from: 0, to: 1}
output:
  sensors:
    - {name: tip, body: boom, at: end}
)";
  s += "dynamic: {t_end: 0.1, dt: " + std::to_string(h) + ", rho_inf: " + std::to_string(rho) + "}\n";
  return parseScene(s, "order-cantilever.yaml");
}

Vec2 tipAtEnd(const DynamicHistory &h)
{
  Vec2 p = h.sensors.back()[0].position;
  MPI_Bcast(p.data(), 2, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  return p;
}

} // namespace

class TimeIntegrationOrder : public ::testing::TestWithParam<double> {};

TEST_P(TimeIntegrationOrder, IsSecondOrderInStepSize)
{
  const double rho = GetParam();
  std::vector<Vec2> tips;
  const std::vector<double> steps{1e-3, 5e-4, 2.5e-4, 1.25e-4};
  for (double h : steps) {
    const DynamicHistory run = runDynamic(cantilever(h, rho));
    ASSERT_TRUE(run.summary.completed) << run.summary.failure;
    ASSERT_EQ(run.summary.rejected, 0);
    tips.push_back(tipAtEnd(run));
  }
  // Order from successive differences (no reference solution needed).
  double order = 0;
  for (std::size_t k = 0; k + 2 < tips.size(); ++k) {
    const double d0 = (tips[k] - tips[k + 1]).norm(), d1 = (tips[k + 1] - tips[k + 2]).norm();
    order = std::log2(d0 / d1);
    PetscPrintf(PETSC_COMM_WORLD, "  rho_inf %.2f: h = %.3g -> %.3g -> %.3g: differences %.3e, %.3e, order %.3f\n", rho, steps[k],
                steps[k + 1], steps[k + 2], d0, d1, order);
  }
  EXPECT_NEAR(order, 2.0, 0.2) << "rho_inf = " << rho;
}

INSTANTIATE_TEST_SUITE_P(RhoInf, TimeIntegrationOrder, ::testing::Values(0.5, 0.8, 1.0));

TEST(FlexiblePendulum, ConservesEnergyAndKeepsPin)
{
  // 1 m pendulum, flexible in bending (first free-free bending mode ~ 11 Hz),
  // pinned at s = 0 and released horizontally under gravity; rho_inf = 1 (no
  // numerical dissipation).
  const Scene scene = parseScene(R"(
name: flexible-pendulum
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: pendulum, length: 1.0, elements: 8, section: {EA: 1.0e5, EI: 50.0, rhoA: 2.0}}
constraints:
  - {type: pin, body: pendulum, at: start}
dynamic: {t_end: 2.0, dt: 5.0e-4, rho_inf: 1.0}
output:
  sensors:
    - {name: tip, body: pendulum, at: end}
)",
                                 "flexible-pendulum.yaml");
  const DynamicHistory run = runDynamic(scene);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  // Energy scale: the potential energy released by a swing to vertical, m g L / 2.
  const double scale = 2.0 * 1.0 * 9.81 * 1.0 / 2.0;
  double drift = 0, violation = 0, lowest = 0;
  for (std::size_t k = 0; k < run.energy.size(); ++k) {
    drift = std::max(drift, std::abs(run.energy[k] - run.energy[0]) / scale);
    violation = std::max(violation, run.violation[k]);
    if (!run.sensors[k].empty()) lowest = std::min(lowest, run.sensors[k][0].position.y());
  }
  PetscPrintf(PETSC_COMM_WORLD, "  pendulum: max |E - E0| / (m g L/2) = %.3e, max pin violation %.3e m, lowest tip y = %.4f m, %d steps\n",
              drift, violation, lowest, (int)run.summary.steps);
  EXPECT_LT(drift, 1e-4);
  EXPECT_LT(violation, 1e-10);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) EXPECT_LT(lowest, -0.9) << "the pendulum must actually swing down";
}

// Steps that do not divide t_end exactly: the run ends on t_end, and no step
// is a rounding sliver (a 1e-12 s last step gave MN multipliers before).
TEST(TimeStepping, EndsOnTEndWithoutSliverSteps)
{
  // 7 s as in the paper scenes: thousands of steps accumulate the rounding.
  for (double h : {5e-4, 1e-3 / 3.0, 7e-4, 4e-3}) {
    Scene scene = cantilever(h, 0.8);
    scene.dynamic.dt = h; // exactly, not through std::to_string
    scene.dynamic.t_end = 7.0;
    const DynamicHistory run = runDynamic(scene, PETSC_COMM_SELF);
    ASSERT_TRUE(run.summary.completed) << run.summary.failure;
    EXPECT_NEAR(run.time.back(), scene.dynamic.t_end, 1e-12) << "h = " << h;
    for (std::size_t k = 1; k < run.time.size(); ++k)
      EXPECT_GT(run.time[k] - run.time[k - 1], 1e-3 * h) << "step " << k << " of h = " << h;
    EXPECT_EQ(run.summary.steps, static_cast<PetscInt>(std::ceil(scene.dynamic.t_end / h - 1e-6))) << "h = " << h;
  }
}

// A drive's kink just beyond a step's end: the step is stretched (by at most
// 1 %) to land on it instead of leaving a sliver. The clamp angle ramps to
// t1 = 6.0005 ms with h = 1 ms, so the step from 5 ms would end 0.5 us short
// of the kink and the landing step would be 5e-4 h long (forces of order
// m/(5e-4 h)^2, and a Newton failure there was blamed on dt_min).
TEST(TimeStepping, LandsOnAKinkWithoutASliverStep)
{
  const double h = 1e-3, kink = 6.0005e-3;
  Scene scene = parseScene(R"(
name: kink-sliver
analysis: dynamic
bodies:
  - {name: boom, length: 1.0, elements: 4, section: {EA: 1.0e6, EI: 1.0e3, rhoA: 1.0}}
constraints:
  - type: clamp
    body: boom
    at: start
    angle: {type: ramp, t0: 0, t1: 0.0060005, from: 0, to: 1}
dynamic: {t_end: 0.012, dt: 1.0e-3, rho_inf: 0.8}
output:
  sensors:
    - {name: tip, body: boom, at: end}
)",
                           "kink-sliver.yaml");
  const DynamicHistory run = runDynamic(scene, PETSC_COMM_SELF);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  bool landed = false;
  for (std::size_t k = 1; k < run.time.size(); ++k) {
    const double step = run.time[k] - run.time[k - 1];
    EXPECT_GT(step, 0.5 * h) << "step " << k << " ends at t = " << run.time[k] << " s";
    EXPECT_LE(step, 1.01 * h * (1 + 1e-12)) << "step " << k;
    landed = landed || std::abs(run.time[k] - kink) < 1e-15;
  }
  EXPECT_TRUE(landed) << "a step ends on the kink at " << kink << " s";
  EXPECT_NEAR(run.time.back(), scene.dynamic.t_end, 1e-12);
}

// Adaptive steps (-boom_adaptive_tol): the error of the tip at t = 0.1 s
// against a fine fixed-step reference falls with the tolerance, and the
// controller takes fewer steps where the motion is smooth.
TEST(AdaptiveSteps, ErrorFollowsTheTolerance)
{
  Scene fine = cantilever(1e-3, 0.8);
  fine.dynamic.dt = 1e-5;
  const Vec2 reference = tipAtEnd(runDynamic(fine, PETSC_COMM_WORLD));
  double previous = 1e300;
  std::vector<double> errors;
  for (double tol : {1e-5, 1e-6, 1e-7, 1e-8}) {
    Scene scene = cantilever(1e-3, 0.8); // dt = 1e-3 is the largest step allowed
    const DynamicHistory run = runDynamic(scene, PETSC_COMM_WORLD, tol);
    ASSERT_TRUE(run.summary.completed) << run.summary.failure;
    const double error = (tipAtEnd(run) - reference).norm();
    double hmin = 1e300, hmax = 0;
    for (std::size_t k = 1; k < run.time.size(); ++k) {
      hmin = std::min(hmin, run.time[k] - run.time[k - 1]);
      hmax = std::max(hmax, run.time[k] - run.time[k - 1]);
    }
    PetscPrintf(PETSC_COMM_WORLD, "  tol %.0e: %d steps (h %.2e ... %.2e), %d rejected, tip error %.3e m\n", tol,
                (int)run.summary.steps, hmin, hmax, (int)run.summary.rejected, error);
    EXPECT_LE(hmax, 1e-3 * (1 + 1e-9));
    EXPECT_LT(error, previous) << "tol " << tol;
    previous = error;
    errors.push_back(error);
  }
  EXPECT_LT(errors.back(), errors.front() / 30); // three decades of tolerance
}
