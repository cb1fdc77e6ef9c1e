// The winch on the elastic rope (docs/model.md §7.1) end to end: a 10 kg
// body hangs at rest on a 1 m rope (EA = 1e5 N, pretensioned with its
// weight) from a fixed ceiling; the winch hoists at v = 0.2 m/s from
// t0 = 0.1 s to t1 = 0.6 s (a ramp of the paid-out length: the winch speed
// jumps at both ends, two breakpoints of the integrator).
//  - The energy balance with the winch power closes: E(t) - E(0) = W_winch
//    (rho_inf = 1, no damping), to 1e-3 of W_winch.
//  - Massless-rope limit of a speed jump: the body's response to the
//    sudden hoisting is u(tau) = v (tau - sin(w tau)/w) (w^2 = k/m, k =
//    EA/L0), so the tension T = m g + v sqrt(k m) sin(w tau) peaks at
//    m g + v sqrt(k m) a quarter period after the jump (the lift-off formula
//    with the ground replaced by the body's own equilibrium), to 2 % (the
//    peak of the first half period; k = EA/L0(t) of the paid-out rope
//    there; later peaks grow with k as the rope gets shorter).
//  - Steps land on both breakpoints (the events of the restart are exact).
#include "support.hpp"

#include "boomdyn/design_numbers.hpp"

#include <cmath>
#include <map>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double g = 9.81, m = 10.0, EA = 1.0e5, v = 0.2, t0 = 0.1, t1 = 0.6;

std::string winchScene(double dt, double tEnd)
{
  return R"(
name: winch-hoist
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: ceiling, type: rigid, length: 0.2, origin: [-0.1, 0], section: {rhoA: 1}}
  - {name: bob, type: rigid, length: 0.1, origin: [-0.05, -1.0], section: {rhoA: 100}}
constraints:
  - {type: clamp, body: ceiling, at: start}
  - {type: angle_drive, body: bob, at: 0.05, angle: 0}
  - {type: elastic_rope, name: hoist, from: ceiling, from_at: 0.1, to: bob, to_at: 0.05, EA: 1.0e5,
     pretension: 98.1, winch: {type: ramp, t0: 0.1, t1: 0.6, from: 0, to: -0.1}}
dynamic: {t_end: )" + std::to_string(tEnd) +
         ", dt: " + std::to_string(dt) + R"(, rho_inf: 1.0}
)";
}

} // namespace

TEST(WinchVerification, HoistingJumpAndEnergyBalance)
{
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "thousands of steps of a 6-coordinate model; 2 ranks: mpi2 winch run";
  const double dt = 1e-4;
  const DynamicHistory run = runDynamic(parseScene(winchScene(dt, 0.75), "winch-hoist.yaml"));
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  ASSERT_TRUE(run.outcome.hasEnergyBalance);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  ASSERT_EQ(run.outputs.front().size(), 5u); // tension, length, stretch, payout, winch_power
  const double L0 = 1.0 / (1 + m * g / EA), w = std::sqrt(EA / L0 / m), tPeak = t0 + 0.5 * M_PI / w;
  const double k = EA / (L0 - v * (tPeak - t0)), peakRef = m * g + v * std::sqrt(k * m);
  double peak = 0;
  bool landed0 = false, landed1 = false;
  for (std::size_t s = 0; s < run.time.size(); ++s) {
    if (run.time[s] < t0 + M_PI / w) peak = std::max(peak, run.outputs[s][0]);
    landed0 = landed0 || std::abs(run.time[s] - t0) < 1e-12;
    landed1 = landed1 || std::abs(run.time[s] - t1) < 1e-12;
  }
  const double Wwinch = run.outcome.inputWork, excess = run.outcome.energyExcess;
  const double lift = m * g * 0.1; // the potential energy the winch gives the body (kinetic ~0 at the end)
  PetscPrintf(PETSC_COMM_SELF,
              "  winch: peak tension %.3f N vs m g + v sqrt(k m) = %.3f N (rel. %.2e); payout at the end %.6f m; "
              "winch work %.6f J (m g dh = %.6f J, + the oscillation left by the two jumps), energy excess %.3e J "
              "(%.2e of the work)\n",
              peak, peakRef, std::abs(peak / peakRef - 1), run.outputs.back()[3], Wwinch, lift, excess,
              std::abs(excess) / Wwinch);
  EXPECT_TRUE(landed0 && landed1) << "steps land on the winch's speed jumps";
  EXPECT_NEAR(run.outputs.back()[3], -0.1, 1e-12);
  EXPECT_NEAR(peak, peakRef, 0.02 * peakRef);
  // The oscillation each speed jump leaves has the energy m v^2 / 2: at most 4x that remains.
  EXPECT_GT(Wwinch, lift);
  EXPECT_LT(Wwinch, lift + 4 * 0.5 * m * v * v);
  EXPECT_LT(std::abs(excess), 1e-3 * Wwinch);
}

// Quick release: a payload (rigid body 40 kg + point masses 40 kg and
// Delta m = 20 kg on its axis, m = 100 kg) hangs at rest on an elastic rope
// (EA = 1e6 N, 2 m, pretensioned with its weight); at t = 0.1 s Delta m is
// released. The remaining mass m - Delta m starts at rest with the rope
// force m g: it oscillates about (m - Delta m) g with the amplitude Delta m g,
// so the smallest rope force is (m - 2 Delta m) g (no damping, rho_inf = 1),
// to 2 %; the event 'release' is written at 0.1 s and the step lands there.
TEST(WinchVerification, QuickReleaseSmallestRopeForce)
{
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "a 6-coordinate model: 2 ranks are tested by the mpi2 winch run";
  const double mTotal = 100.0, dm = 20.0;
  const DynamicHistory run = runDynamic(parseScene(R"(
name: quick-release
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: ceiling, type: rigid, length: 0.2, origin: [-0.1, 0], section: {rhoA: 1}}
  - {name: payload, type: rigid, length: 0.4, origin: [-0.2, -2.0], section: {rhoA: 100}}
constraints:
  - {type: clamp, body: ceiling, at: start}
  - {type: elastic_rope, name: hoist, from: ceiling, from_at: 0.1, to: payload, to_at: 0.2, EA: 1.0e6,
     pretension: 981}
masses:
  - {name: ballast, body: payload, at: 0.2, mass: 40}
  - {name: part, body: payload, at: 0.2, mass: 20, release_at: 0.1}
dynamic: {t_end: 0.3, dt: 1.0e-4, rho_inf: 1.0}
)",
                                                   "quick-release.yaml"));
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  double before = 1e300, after = 1e300, beforeMax = 0;
  bool landed = false;
  for (std::size_t s = 0; s < run.time.size(); ++s) {
    if (run.time[s] < 0.1 - 1e-12) before = std::min(before, run.outputs[s][0]), beforeMax = std::max(beforeMax, run.outputs[s][0]);
    else if (run.time[s] > 0.1 + 1e-12) after = std::min(after, run.outputs[s][0]);
    landed = landed || std::abs(run.time[s] - 0.1) < 1e-12;
  }
  const double ref = (mTotal - 2 * dm) * g;
  PetscPrintf(PETSC_COMM_SELF,
              "  quick release: rope force before %.4f ... %.4f N (m g = %.4f N); smallest after %.4f N vs "
              "(m - 2 dm) g = %.4f N (rel. %.2e); energy excess %.2e J of %.3e J involved\n",
              before, beforeMax, mTotal * g, after, ref, std::abs(after / ref - 1), run.outcome.energyExcess,
              run.outcome.energyInvolved);
  EXPECT_TRUE(landed);
  EXPECT_NEAR(before, mTotal * g, 1e-6 * mTotal * g); // at rest before the release
  EXPECT_NEAR(after, ref, 0.02 * ref);
  ASSERT_EQ(run.events.size(), 1u);
  EXPECT_EQ(run.events[0].kind, "release");
  EXPECT_DOUBLE_EQ(run.events[0].t, 0.1);
  EXPECT_LT(std::abs(run.outcome.energyExcess), 1e-6 * run.outcome.energyInvolved); // the released energy is counted
}

// Lift-off: a 10 kg payload rests on the ground (ground_contact, k_g =
// 1e9 N/m, no damping, at its static compression) under a just-taut rope of
// EA = 1e5 N and 1 m; at t0 = 0.05 s the winch starts hoisting at v = 0.2 m/s
// (a speed jump). Massless-rope limit: the rope force grows as k v tau
// until it carries the weight (lift-off at tau1 = m g / (k v), event
// lift_off; the exact time with the ground spring is derived below), then
// T = m g + v sqrt(k m) sin(w tau'), w^2 = k/m: the peak
// rope force m g + v sqrt(k m) (k = EA/L0 of the paid-out rope at the
// peak), to 2 %. h = 2e-5 s resolves the ground's 1e4 rad/s (w h = 0.2).
TEST(WinchVerification, LiftOffPeakRopeForce)
{
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "a 6-coordinate model: 2 ranks are tested by the mpi2 winch run";
  const double kg = 1e9, y0 = -1.0 - m * g / kg; // the payload's axis at its static compression
  char text[1600];
  std::snprintf(text, sizeof text, R"(
name: lift-off
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: ceiling, type: rigid, length: 0.2, origin: [-0.1, 0], section: {rhoA: 1}}
  - {name: payload, type: rigid, length: 0.1, origin: [-0.05, %.17g], section: {rhoA: 100}}
constraints:
  - {type: clamp, body: ceiling, at: start}
  - {type: angle_drive, body: payload, at: 0.05, angle: 0}
  - {type: elastic_rope, name: hoist, from: ceiling, from_at: 0.1, to: payload, to_at: 0.05, EA: 1.0e5,
     length: %.17g, winch: {type: ramp, t0: 0.05, t1: 1.05, from: 0, to: -0.2}}
  - {type: ground_contact, name: ground, body: payload, at: 0.05, level: -1.0, stiffness: 1.0e9}
dynamic: {t_end: 0.1, dt: 2.0e-5, rho_inf: 1.0}
)",
                y0, -y0);
  const Scene scene = parseScene(text, "lift-off.yaml");
  const DynamicHistory run = runDynamic(scene);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  const double L0 = -y0, k0 = EA / L0, t0 = 0.05, tau1 = m * g / (k0 * v), w = std::sqrt(k0 / m);
  // On the ground the payload is a mass between the ground spring k_g and
  // the rope stretched at the rate v: y = k v (tau / K - sin(W tau) / (K W)),
  // K = k + k_g, W^2 = K / m (rise above the rest position), so the ground
  // force m g - k_g y reaches zero a little before tau1 (its oscillation of
  // amplitude k_g k v / (K^2 W) ~ 2 N from the speed jump): the lift-off time.
  const double K = k0 + kg, W = std::sqrt(K / m);
  double lo = 0.5 * tau1, hi = 1.5 * tau1;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double y = k0 * v * (mid / K - std::sin(W * mid) / (K * W));
    ((m * g - kg * y > 0) ? lo : hi) = mid;
  }
  const double liftRef = t0 + 0.5 * (lo + hi);
  const double tPeak = t0 + tau1 + 0.5 * M_PI / w, k = EA / (L0 - v * (tPeak - t0));
  const double peakRef = m * g + v * std::sqrt(k * m);
  double peak = 0, groundBefore = 0;
  for (std::size_t s = 0; s < run.time.size(); ++s) {
    peak = std::max(peak, run.outputs[s][0]);
    if (run.time[s] < t0) groundBefore = std::max(groundBefore, std::abs(run.outputs[s][5] - m * g));
  }
  double liftOff = -1;
  for (const TypeEvent &e : run.events)
    if (e.kind == "lift_off" && liftOff < 0) liftOff = e.t;
  PetscPrintf(PETSC_COMM_SELF,
              "  lift-off: at %.7f s (two springs: %.7f s; rigid ground: %.7f s); peak rope force %.3f N vs "
              "m g + v sqrt(k m) = %.3f N (rel. %.2e); ground force at rest within %.1e N of m g\n",
              liftOff, liftRef, t0 + tau1, peak, peakRef, std::abs(peak / peakRef - 1), groundBefore);
  EXPECT_LT(groundBefore, 1e-6 * m * g);
  EXPECT_NEAR(liftOff, liftRef, 2e-3 * tau1);
  EXPECT_NEAR(peak, peakRef, 0.02 * peakRef);

  // The design numbers of the run (docs/output.md "Design numbers"): the rope
  // carries nothing at t = 0, so its dynamic factor is relative to the
  // weight of the load it lifts, m g (EN 13001-2's phi_2):
  // phi_2 = peak / (m g) = 1 + v sqrt(k m) / (m g), within the same 2 %.
  const Model model(scene);
  DesignNumbers design(model);
  for (std::size_t s = 0; s < run.time.size(); ++s) design.update(run.time[s], run.outputs[s], run.multipliers[s]);
  std::map<std::string, double> d;
  for (const auto &[name, value] : design.attributes()) d[name] = value;
  const std::string p = "design.elastic_rope.hoist.";
  ASSERT_TRUE(d.count(p + "load_weight_N"));
  const double phi2 = 1 + v * std::sqrt(k * m) / (m * g);
  PetscPrintf(PETSC_COMM_SELF, "%s  phi_2 = %.5f vs 1 + v sqrt(k m) / (m g) = %.5f (rel. %.2e)\n", design.report().c_str(),
              d.at(p + "dynamic_factor"), phi2, std::abs(d.at(p + "dynamic_factor") / phi2 - 1));
  EXPECT_LT(std::abs(d.at(p + "static_tension_N")), 1e-6 * m * g); // slack start
  EXPECT_DOUBLE_EQ(d.at(p + "load_weight_N"), m * g);
  EXPECT_DOUBLE_EQ(d.at(p + "dynamic_factor"), peak / (m * g));
  EXPECT_NEAR(d.at(p + "dynamic_factor"), phi2, 0.02 * phi2);
}

// The list form `pulleys: [{body, at}, ...]`: the same two sheaves as
// pulley/pulley2 give the same run bit for bit; three sheaves span the sum of
// the four straight segments (derived here from the points).
TEST(WinchVerification, SheaveListMatchesPulleyKeysAndTakesAnyNumber)
{
  auto scene = [](const std::string &sheaves) {
    return parseScene(R"(
name: sheaves
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: ceiling, type: rigid, length: 2.0, origin: [0, 0], section: {rhoA: 1}}
  - {name: bob, type: rigid, length: 0.1, origin: [1.95, -1.0], section: {rhoA: 100}}
constraints:
  - {type: clamp, body: ceiling, at: start}
  - {type: elastic_rope, name: hoist, from: ceiling, from_at: 0.0, )" + sheaves +
                          R"(, to: bob, to_at: 0.05, EA: 1.0e5, pretension: 50,
     winch: {type: ramp, t0: 0.01, t1: 1.01, from: 0, to: -0.1}}
dynamic: {t_end: 0.02, dt: 1.0e-3, rho_inf: 0.9}
)",
                      "sheaves.yaml");
  };
  const DynamicHistory keys = runDynamic(scene("pulley: ceiling, pulley_at: 0.5, pulley2: ceiling, pulley2_at: 2.0"));
  const DynamicHistory list = runDynamic(scene("pulleys: [{body: ceiling, at: 0.5}, {body: ceiling, at: 2.0}]"));
  const DynamicHistory three =
      runDynamic(scene("pulleys: [{body: ceiling, at: 0.5}, {body: ceiling, at: 1.2}, {body: ceiling, at: 2.0}]"));
  ASSERT_TRUE(keys.summary.completed && list.summary.completed && three.summary.completed);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  ASSERT_EQ(keys.outputs.size(), list.outputs.size());
  for (std::size_t s = 0; s < keys.outputs.size(); ++s) EXPECT_EQ(keys.outputs[s], list.outputs[s]);
  // Ceiling points at x = 0, 0.5, 1.2, 2.0 (y = 0), the bob's attachment at (2.0, -1.0).
  EXPECT_NEAR(three.outputs.front()[1], 0.5 + 0.7 + 0.8 + 1.0, 1e-12);
  EXPECT_NEAR(keys.outputs.front()[1], 0.5 + 1.5 + 1.0, 1e-12);
}

// Payload pendulum: a payload (rigid body 40 kg + two point masses of 30 kg
// at +-0.15 m from its centre) hangs on a stiff rope (EA = 1e9 N) from a
// fixed sheave, attached at its centre of mass: the rope force has no
// moment about the centre, so the swing is that of a pendulum of the
// rope's (stretched) length l whatever the payload's rotational inertia:
// period 2 pi sqrt(l / g) (1 + theta0^2 / 16) for the amplitude theta0 =
// 3 deg; measured from the zero crossings of the hook's x over two
// periods, within 1e-3. rho_inf = 0.5 damps the rope's axial mode (1.3 kHz)
// in a few steps and leaves the 0.22 Hz swing alone (omega h = 1.4e-3).
TEST(WinchVerification, PayloadPendulumPeriod)
{
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "thousands of steps of a 6-coordinate model: 2 ranks are tested by the mpi2 hoist run";
  const double L = 5.0, theta0 = 3.0 * M_PI / 180, mass = 100.0, EAstiff = 1e9;
  const double hx = L * std::sin(theta0), hy = -L * std::cos(theta0);
  char text[1600];
  std::snprintf(text, sizeof text, R"(
name: payload-pendulum
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: boom, type: rigid, length: 0.4, origin: [-0.4, 0], section: {rhoA: 1}}
  - {name: payload, type: rigid, length: 0.4, origin: [%.17g, %.17g], section: {rhoA: 100}}
constraints:
  - {type: clamp, body: boom, at: start}
  - {type: elastic_rope, name: hoist, from: boom, from_at: 0.0, pulleys: [{body: boom, at: end}], to: payload,
     to_at: 0.2, EA: 1.0e9, pretension: %.17g}
masses:
  - {body: payload, at: 0.05, mass: 30}
  - {body: payload, at: 0.35, mass: 30}
dynamic: {t_end: 9.2, dt: 1.0e-3, rho_inf: 0.5}
output:
  sensors:
    - {name: hook, body: payload, at: 0.2}
)",
                hx - 0.2, hy, mass * g * std::cos(theta0));
  const DynamicHistory run = runDynamic(parseScene(text, "payload-pendulum.yaml"));
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  std::vector<double> crossings;
  for (std::size_t s = 1; s < run.time.size(); ++s) {
    const double a = run.sensors[s - 1][0].position.x(), b = run.sensors[s][0].position.x();
    if ((a > 0) != (b > 0)) crossings.push_back(run.time[s - 1] + (run.time[s] - run.time[s - 1]) * a / (a - b));
  }
  ASSERT_GE(crossings.size(), 4u);
  const double measured = 2 * (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double l = L * (1 + mass * g / EAstiff); // the stretched length (static, to 1e-9)
  const double exact = 2 * M_PI * std::sqrt(l / g) * (1 + theta0 * theta0 / 16);
  PetscPrintf(PETSC_COMM_SELF, "  payload pendulum: period %.6f s from %zu zero crossings vs %.6f s (rel. %.2e)\n",
              measured, crossings.size(), exact, std::abs(measured / exact - 1));
  EXPECT_NEAR(measured, exact, 1e-3 * exact);
}
