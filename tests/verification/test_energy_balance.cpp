// Energy balance E(t) - E(0) = W_in - dissipation: the input power of
// driven constraints (lambda . C_t) and of loads that vary in time (-s' F . r)
// against analytic work, the balance closing on conservative runs, and the
// check that stops runs which create energy (boomdyn: -boom_energy_tolerance).
#include "boomdyn/energy_balance.hpp"
#include "boomdyn/scene_reader.hpp"
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// Trapezoidal integral of the input power over the recorded steps.
std::vector<double> inputWork(const DynamicHistory &h)
{
  std::vector<double> w(h.time.size(), 0.0);
  for (std::size_t k = 1; k < h.time.size(); ++k)
    w[k] = w[k - 1] + 0.5 * (h.inputPower[k] + h.inputPower[k - 1]) * (h.time[k] - h.time[k - 1]);
  return w;
}

} // namespace

TEST(EnergyBalance, ElevationDriveWorkIsTheLiftingWork)
{
  // inputs/elevation_drive.yaml: a 2 m steel boom (rhoA = 31.84 kg/m) raised
  // from 0 to 35 degrees by its clamp angle, at rest at both ends. The drive
  // does the work of lifting the centre of mass: m g (L/2) sin 35 deg (the
  // boom is stiff: its sag changes this by ~1e-5).
  Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/elevation_drive.yaml");
  const DynamicHistory h = runDynamic(scene, PETSC_COMM_SELF);
  ASSERT_TRUE(h.summary.completed) << h.summary.failure;
  const double rhoA = 7850 * 4.056e-3, L = 2.0;
  const double exact = rhoA * L * 9.81 * 0.5 * L * std::sin(35.0 * M_PI / 180.0);
  const std::vector<double> w = inputWork(h);
  const double excess = h.energy.back() - h.energy.front() - w.back();
  PetscPrintf(PETSC_COMM_SELF, "  drive work %.6f J, m g L/2 sin 35 = %.6f J (%.2e relative), excess %.2e J\n", w.back(),
              exact, std::abs(w.back() - exact) / exact, excess);
  EXPECT_LT(std::abs(w.back() - exact), 1e-3 * exact);
  EXPECT_LT(std::abs(excess), 1e-3 * exact); // the scheme dissipates little of a slow motion
}

TEST(EnergyBalance, RampedLoadBalanceClosesWithoutDissipation)
{
  // A flexible cantilever under a tip load ramped smoothly to P L^2/EI = 1,
  // rho_inf = 1 (no numerical dissipation): E - E0 - W_in stays at the
  // integration error, far below the energy involved.
  const Scene scene = parseScene(R"(
name: ramped
analysis: dynamic
bodies:
  - {name: boom, length: 1.0, elements: 8, section: {EA: 1.0e6, EI: 1.0e3, rhoA: 1.0}}
constraints:
  - {type: clamp, body: boom, at: start}
loads:
  - {type: point_force, body: boom, at: end, force: [0, -1000], scale: {type: smooth_step, t0: 0, t1: 0.05, from: 0, to: 1}}
dynamic: {t_end: 0.2, dt: 2.5e-4, rho_inf: 1.0}
)", "ramped.yaml");
  const DynamicHistory h = runDynamic(scene, PETSC_COMM_SELF);
  ASSERT_TRUE(h.summary.completed) << h.summary.failure;
  const std::vector<double> w = inputWork(h);
  double involved = 0, worst = 0;
  for (std::size_t k = 0; k < h.time.size(); ++k) {
    involved = std::max(involved, h.energyParts[k].kinetic + h.energyParts[k].strain);
    worst = std::max(worst, std::abs(h.energy[k] - h.energy[0] - w[k]));
  }
  PetscPrintf(PETSC_COMM_SELF, "  ramped load: input work %.4f J, worst |E - E0 - W| %.2e J of %.4f J involved\n", w.back(),
              worst, involved);
  // W_in = -integral s' F . r dt: the dead load's potential -s F . r falls as
  // the tip moves down, so it is negative here, and far from zero.
  EXPECT_GT(std::abs(w.back()), 0.1 * involved);
  EXPECT_LT(worst, 1e-3 * involved);
}

TEST(EnergyBalance, CheckFlagsCreatedEnergyOnly)
{
  EnergyBalance balance(0.05);
  EnergyParts e;
  e.potential = 1e6; // a large constant offset (gravity) must not matter
  e.inputPower = 10.0;
  EXPECT_TRUE(balance.update(0.0, 0.0, e).empty());
  // The first step is the baseline: whatever it does (here: 1000 J from
  // nowhere, an overshoot) is not checked.
  e.kinetic = 1000.0;
  EXPECT_TRUE(balance.update(0.5, 0.5, e).empty());
  // A drive puts in 10 W for 1 s; the system stores 9 J more (1 J dissipated).
  e.kinetic = 1004.5, e.strain = 4.5;
  EXPECT_TRUE(balance.update(1.5, 1.0, e).empty()) << balance.excess();
  EXPECT_NEAR(balance.inputWork(), 10.0, 1e-12);
  EXPECT_NEAR(balance.excess(), -1.0, 1e-9);
  // Energy from nowhere: 400 J more while the drive puts in 5 J (the
  // energy involved is about 1000 J: 40 % of it).
  e.inputPower = 0.0;
  e.kinetic = 1404.5;
  const std::string message = balance.update(2.5, 1.0, e);
  EXPECT_NE(message.find("energy balance violated at t = 2.5 s"), std::string::npos) << message;
  EXPECT_NE(message.find("rho_inf"), std::string::npos) << message;
  // Off: never a message.
  EnergyBalance off(0.0);
  (void)off.update(0.0, 0.0, EnergyParts{});
  (void)off.update(1.0, 1.0, EnergyParts{});
  e.kinetic = 1e9;
  EXPECT_TRUE(off.update(2.0, 1.0, e).empty());
}

TEST(EnergyBalance, DissipatedWorkClosesTheBalance)
{
  // A vibration losing 2 J to material damping in one step of 1 s: E falls
  // by 2 J, the step's damping work is 2 J, the excess E - E0 - W_in + W_diss is 0.
  EnergyBalance balance(0.05);
  EnergyParts e;
  e.kinetic = 10.0;
  EXPECT_TRUE(balance.update(0.0, 0.0, e).empty());
  EXPECT_TRUE(balance.update(0.1, 0.1, e, 5.0).empty()); // baseline: its damping work is not counted
  e.kinetic = 8.0;
  EXPECT_TRUE(balance.update(1.1, 1.0, e, 2.0).empty());
  EXPECT_NEAR(balance.dissipatedWork(), 2.0, 1e-12);
  EXPECT_NEAR(balance.excess(), 0.0, 1e-12);
  // Energy the damping forces fed in (negative damping work, as
  // generalized-alpha with rho_inf < 1 does in overdamped modes after a
  // step load) is accounted, not flagged: E rises by 3 J, the damping did -3 J.
  e.kinetic = 11.0;
  EXPECT_TRUE(balance.update(2.1, 1.0, e, -3.0).empty()) << balance.excess();
  EXPECT_NEAR(balance.excess(), 0.0, 1e-12);
  // But energy from nowhere is flagged even while the damping dissipates:
  // E rises by 5 J while the damping removes 1 J.
  e.kinetic = 16.0;
  const std::string message = balance.update(3.1, 1.0, e, 1.0);
  EXPECT_NE(message.find("energy balance violated at t = 3.1 s"), std::string::npos) << message;
  EXPECT_NEAR(balance.excess(), 6.0, 1e-12);
}
