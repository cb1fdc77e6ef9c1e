// The hydraulic cylinder (docs/model.md §2.6) end to end, on a rigid block of
// mass m held up by a vertical cylinder from a ground point (the block's
// rotation locked by an angle drive, held sideways by a long horizontal
// spring), A1 = pi D^2/4, A2 = pi (D^2 - d^2)/4,
// C_i = V_i / beta_i at the initial stroke s0:
//  - closed valve, `initial: static`: the static start holds the stroke at
//    s0 with the rod pressure p2 at its given value; the piston pressure
//    must balance the load, p1 A1 - p2 A2 = m g (1e-9 relative);
//  - closed valve, started with p1 above that balance by 0.1 %: the block
//    oscillates on the oil column at omega = sqrt(k_h / m), k_h = A1^2/C1 +
//    A2^2/C2 = beta1 A1^2/V1 + beta2 A2^2/V2; the period from the zero
//    crossings of p1 - p1_eq over 7 periods, within 1e-4;
//  - flow source Q into the piston chamber (rod chamber at tank pressure),
//    viscous friction c, against the weight: the linear closed form of
//    m w' = A1 dp - c w, C1 dp' = Q - A1 w from rest at the balance
//    (w = s', dp = p1 - p1_eq): the pressure rise within 2e-4 of its steady
//    value c Q / A1^2 after the first millisecond, the slow root's rate
//    (the pressure rise time constant, ~C1 c / A1^2) fitted from the run
//    within 1e-3, the steady speed Q / A1 within 1e-5;
//  - energy balance of that run: hydraulic power in (p1 Q1 + p2 Q2) minus
//    compression power minus friction power, integrated, equals the
//    mechanical work m g dy + m w^2 / 2, to 1e-4 of the hydraulic energy in;
//  - the same run on 1 and 2 ranks (mpi2.verification): outputs agree to 1e-10;
//  - a flexible boom luffed by a closed cylinder: the luffing mode's
//    frequency from the eigen-analysis against the free oscillation, 1 %.
#include "cylinder_block.hpp"
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

using namespace boomdyn::testing::cylinder_block;
constexpr double p2 = 20e5;

// The rig of cylinder_block.hpp with the spring of 1e6 N/m.
std::string blockScene(const std::string &cylinder, const std::string &dynamic)
{
  return cylinder_block::scene(cylinder, dynamic);
}

enum { Force, P1, P2, Stroke, StrokeRate, Q1, Q2, HydraulicPower, CompressionPower, FrictionPower };

} // namespace

TEST(HydraulicCylinderVerification, StaticSplitAndOilColumnFrequency)
{
  const double p1eq = (m * g + p2 * A2) / A1;
  // The static start: p1 solved with the stroke held, p2 kept.
  const Scene held = parseScene(blockScene("valve: closed, initial_pressure_rod: 2.0e+6",
                                           "{t_end: 0.001, dt: 1.0e-4, rho_inf: 1.0, initial: static}"),
                                "cylinder-static.yaml");
  const DynamicHistory start = runDynamic(held, PETSC_COMM_SELF);
  ASSERT_TRUE(start.summary.completed) << start.summary.failure;
  const double p1Static = start.outputs.front()[P1];
  EXPECT_NEAR(p1Static / p1eq, 1.0, 1e-9);
  EXPECT_NEAR(start.outputs.front()[P2], p2, 1e-9 * p2);
  EXPECT_NEAR(start.outputs.front()[Stroke], s0, 1e-12);
  // ... and stays there (a static start is at rest).
  EXPECT_NEAR(start.outputs.back()[P1] / p1eq, 1.0, 1e-9);

  // Free oscillation from p1 0.1 % above the balance.
  const double kh = A1 * A1 / C1 + A2 * A2 / C2, omega = std::sqrt(kh / m), period = 2 * M_PI / omega;
  const std::string cyl = "valve: closed, initial_pressure_rod: 2.0e+6, initial_pressure_piston: " +
                          std::to_string(p1eq * 1.001);
  const DynamicHistory run = runDynamic(
      parseScene(blockScene(cyl, "{t_end: " + std::to_string(7.3 * period) + ", dt: 2.0e-5, rho_inf: 1.0}"),
                 "cylinder-oscillation.yaml"),
      PETSC_COMM_SELF);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  // The oscillation's centre: the mean of p1 over the run is the balance to O(amplitude^2).
  std::vector<double> crossings;
  for (std::size_t k = 1; k < run.time.size(); ++k) {
    const double a = run.outputs[k - 1][P1] - p1eq, b = run.outputs[k][P1] - p1eq;
    if (a > 0 && b <= 0) crossings.push_back(run.time[k - 1] + (run.time[k] - run.time[k - 1]) * a / (a - b));
  }
  ASSERT_GE(crossings.size(), 7u);
  const double measured = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  PetscPrintf(PETSC_COMM_SELF,
              "  closed cylinder: static p1 %.6f bar vs (m g + p2 A2)/A1 = %.6f bar; period %.8f s vs 2 pi sqrt(m/k_h) "
              "= %.8f s (k_h = %.6e N/m, rel. %.2e) over %zu crossings\n",
              p1Static / 1e5, p1eq / 1e5, measured, period, kh, std::abs(measured / period - 1), crossings.size());
  EXPECT_NEAR(measured / period, 1.0, 1e-4);
}

namespace {

constexpr double Q = 1e-5, c = 2e6;

std::string flowSourceCylinder()
{
  return "valve: flow_source, flow: 1.0e-5, friction_viscous: 2.0e+6, tank_pressure: 0, initial_pressure_rod: 0";
}

Scene flowScene(double tEnd, double dt)
{
  return parseScene(blockScene(flowSourceCylinder(),
                               "{t_end: " + std::to_string(tEnd) + ", dt: " + std::to_string(dt) +
                                   ", rho_inf: 1.0, initial: static}"),
                    "cylinder-flow.yaml");
}

} // namespace

TEST(HydraulicCylinderVerification, FlowSourceRiseSpeedAndEnergyBalance)
{
  const double tEnd = 0.8;
  const DynamicHistory run = runDynamic(flowScene(tEnd, 1e-5), PETSC_COMM_SELF);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  const double p1eq = m * g / A1; // p2 = tank = 0
  // Closed form: x = [w, dp], x' = M x + b, x(0) = 0, with the roots of
  // lambda^2 + (c/m) lambda + A1^2/(m C1) = 0 (overdamped).
  const double a = c / m, k = A1 * A1 / (m * C1), disc = std::sqrt(a * a / 4 - k);
  const double l1 = -a / 2 + disc, l2 = -a / 2 - disc; // slow, fast
  const double dpSteady = c * Q / (A1 * A1), wSteady = Q / A1;
  // dp(t) = dp_ss + B1 e^{l1 t} + B2 e^{l2 t}, dp(0) = 0, dp'(0) = Q / C1.
  const double B2 = (Q / C1 + l1 * dpSteady) / (l2 - l1), B1 = -dpSteady - B2;
  double worst = 0;
  for (std::size_t s = 0; s < run.time.size(); ++s) {
    const double t = run.time[s];
    if (t < 1e-3) continue;
    const double ref = dpSteady + B1 * std::exp(l1 * t) + B2 * std::exp(l2 * t);
    worst = std::max(worst, std::abs(run.outputs[s][P1] - p1eq - ref) / dpSteady);
  }
  // The slow root from the run: the log slope of dp_ss - dp between 0.1 and 0.2 s.
  auto at = [&](double t) {
    std::size_t s = 0;
    while (run.time[s] < t - 1e-9) ++s;
    return dpSteady - (run.outputs[s][P1] - p1eq);
  };
  const double fitted = std::log(at(0.2) / at(0.1)) / 0.1;
  const double speed = run.outputs.back()[StrokeRate];

  // Energy: trapezoidal sums of the powers against the block's mechanical energy.
  double hydraulic = 0, compression = 0, friction = 0;
  for (std::size_t s = 1; s < run.time.size(); ++s) {
    const double h = run.time[s] - run.time[s - 1];
    hydraulic += 0.5 * h * (run.outputs[s][HydraulicPower] + run.outputs[s - 1][HydraulicPower]);
    compression += 0.5 * h * (run.outputs[s][CompressionPower] + run.outputs[s - 1][CompressionPower]);
    friction += 0.5 * h * (run.outputs[s][FrictionPower] + run.outputs[s - 1][FrictionPower]);
  }
  const double lift = run.outputs.back()[Stroke] - run.outputs.front()[Stroke];
  const double mechanical = m * g * lift + 0.5 * m * speed * speed;
  const double imbalance = hydraulic - compression - friction - mechanical;
  PetscPrintf(PETSC_COMM_SELF,
              "  flow source: pressure rise vs closed form worst %.2e of c Q/A1^2 = %.4f bar; slow root %.6f 1/s vs "
              "%.6f 1/s (rel. %.2e; C1 c/A1^2 = %.5f s); speed %.8e m/s vs Q/A1 = %.8e (rel. %.2e)\n"
              "  energy: hydraulic in %.6f J, compression %.6f J, friction %.6f J, mechanical %.6f J: imbalance %.3e J "
              "(%.2e of the hydraulic energy)\n",
              worst, dpSteady / 1e5, fitted, l1, std::abs(fitted / l1 - 1), C1 * c / (A1 * A1), speed, wSteady,
              std::abs(speed / wSteady - 1), hydraulic, compression, friction, mechanical, imbalance,
              std::abs(imbalance) / hydraulic);
  EXPECT_LT(worst, 2e-4);
  EXPECT_NEAR(fitted / l1, 1.0, 1e-3);
  EXPECT_NEAR(speed / wSteady, 1.0, 1e-5);
  EXPECT_LT(std::abs(imbalance), 1e-4 * hydraulic);
}

TEST(HydraulicCylinderVerification, OneAndTwoRanksAgree)
{
  // Full Newton, as tests/regression/test_rank_independence.cpp: with the
  // Jacobian kept between iterations the order of summation on 2 ranks can
  // flip a refresh decision and move the result at the Newton tolerance
  // (7e-8 measured here), which says nothing about the parallel code.
  const Scene scene = flowScene(0.05, 1e-4);
  const DynamicHistory one = runDynamicWithOption(scene, PETSC_COMM_SELF, "-boom_jacobian_reuse", "0"),
                       all = runDynamicWithOption(scene, PETSC_COMM_WORLD, "-boom_jacobian_reuse", "0");
  ASSERT_TRUE(one.summary.completed && all.summary.completed);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return; // outputs on rank 0 of the run's communicator
  ASSERT_EQ(one.outputs.size(), all.outputs.size());
  // Each channel relative to its largest magnitude over the run (flows and
  // powers pass through zero).
  std::vector<double> scale(one.outputs.front().size(), 0.0);
  for (const auto &row : one.outputs)
    for (std::size_t k = 0; k < row.size(); ++k) scale[k] = std::max(scale[k], std::abs(row[k]));
  double worst = 0;
  for (std::size_t s = 0; s < one.outputs.size(); ++s)
    for (std::size_t k = 0; k < one.outputs[s].size(); ++k)
      if (scale[k] > 0) worst = std::max(worst, std::abs(one.outputs[s][k] - all.outputs[s][k]) / scale[k]);
  PetscPrintf(PETSC_COMM_SELF, "  cylinder: 1 rank vs the world communicator: largest relative output difference %.2e\n",
              worst);
  EXPECT_LT(worst, 1e-10);
}

namespace {

// A flexible boom (steel box, EI ten times the elevation_drive boom's)
// pinned at its foot, a 200 kg tip mass, luffed by a closed cylinder from
// a ground point to 0.8 m along the boom with 5 l of hose on each side; a
// downward tip force of 2 kN ramps off from t = 0.01 s over ramp seconds.
std::string luffedBoom(double ramp, double tEnd)
{
  return R"(
name: cylinder-boom
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: boom, length: 2.0, elements: 8, section: {E: 2.1e11, rho: 7850, A: 4.056e-3, I: 2.3586272e-4}}
constraints:
  - {type: pin, body: boom, at: start, point: [0, 0]}
  - {type: hydraulic_cylinder, name: luff, body: boom, at: 0.8, base_point: [0.3, -0.6], piston_diameter: 0.1,
     rod_diameter: 0.056, stroke: 0.4, closed_length: 0.6, dead_volume_piston: 2.0e-4, hose_volume_piston: 5.0e-3,
     dead_volume_rod: 1.5e-4, hose_volume_rod: 5.0e-3, bulk_modulus_hose: 7.0e+8, valve: closed,
     initial_pressure_rod: 1.0e+6}
loads:
  - {type: point_force, body: boom, at: end, force: [0, -2000], scale: {type: ramp, t0: 0.01, t1: )" +
         std::to_string(0.01 + ramp) + R"(, from: 1, to: 0}}
masses:
  - {body: boom, at: end, mass: 200}
dynamic: {t_end: )" + std::to_string(tEnd) +
         R"(, dt: 1.0e-4, rho_inf: 0.9, initial: static}
)";
}

} // namespace

// The luffing mode of a boom held by a closed cylinder: the lowest
// eigenfrequency at the static equilibrium (pressures linearized as closed
// chambers, docs/model.md §2.6) against the period of the free oscillation
// after the tip force is ramped off, from the downward zero crossings of
// the piston pressure about its mean (an offset of the mean does not move
// the spacing of crossings of one direction), within 1 %. The ramp lasts one
// period of the second mode, whose residual vibration it then cancels.
TEST(HydraulicCylinderVerification, LuffingModeFromEigenAnalysisAndFreeOscillation)
{
  const Scene probe = parseScene(luffedBoom(0.01, 0.1), "cylinder-boom.yaml");
  const ModalResult modes = modesAtStaticEquilibrium(probe, 2, PETSC_COMM_SELF);
  ASSERT_EQ(modes.frequencyHz.size(), 2u);
  const double f1 = modes.frequencyHz[0], f2 = modes.frequencyHz[1];
  const DynamicHistory run =
      runDynamic(parseScene(luffedBoom(1.0 / f2, 0.01 + 1.0 / f2 + 12.5 / f1), "cylinder-boom.yaml"), PETSC_COMM_SELF);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  const double released = 0.01 + 1.0 / f2;
  double mean = 0;
  int count = 0;
  for (std::size_t s = 0; s < run.time.size(); ++s)
    if (run.time[s] > released) mean += run.outputs[s][P1], ++count;
  mean /= count;
  std::vector<double> crossings;
  for (std::size_t k = 1; k < run.time.size(); ++k) {
    if (run.time[k - 1] < released) continue;
    const double a = run.outputs[k - 1][P1] - mean, b = run.outputs[k][P1] - mean;
    if (a > 0 && b <= 0) crossings.push_back(run.time[k - 1] + (run.time[k] - run.time[k - 1]) * a / (a - b));
  }
  ASSERT_GE(crossings.size(), 10u);
  const double measured = (crossings.size() - 1) / (crossings.back() - crossings.front());
  PetscPrintf(PETSC_COMM_SELF,
              "  luffed boom: eigen-analysis f1 = %.5f Hz (f2 = %.4f Hz); free oscillation %.5f Hz over %zu crossings "
              "(rel. %.2e)\n",
              f1, f2, measured, crossings.size(), std::abs(measured / f1 - 1));
  EXPECT_NEAR(measured / f1, 1.0, 0.01);
}

// The proportional valve end to end: the block lifted by the spool held at
// u = 0.5 from supply 100 bar with viscous friction c = 2e5 N s/m reaches
// the steady speed w where the valve's flows match the chambers'
// (square-root law above the laminar limit on both edges):
//   A1 w = Cv u sqrt(ps - p1),  A2 w = Cv u sqrt(p2 - pt),  p1 A1 - p2 A2 - c w = m g,
// i.e. p1 = ps - (A1 w/(Cv u))^2, p2 = pt + (A2 w/(Cv u))^2 and one equation
// in w, solved here by bisection. Speed and both pressures within 1e-6 at
// 4 s: the level both pressures rise to together is set through the
// valve's flow gain, with a time constant of about 0.15 s (measured: 2 %
// short of it at 0.3 s); the spool lag (tau = 4.5 ms) is in the run.
TEST(HydraulicCylinderVerification, ProportionalValveSteadyLift)
{
  const double ps = 100e5, pt = 1e5, u = 0.5, cv = 2e5, Cv = 1e-4 / std::sqrt(35e5);
  const std::string cyl = "valve: proportional, command: 0.5, spool_time_constant: 4.5e-3, rated_flow: 1.0e-4, "
                          "rated_pressure_drop: 3.5e+6, supply_pressure: 1.0e+7, tank_pressure: 1.0e+5, "
                          "friction_viscous: 2.0e+5, initial_pressure_rod: 1.0e+5";
  const DynamicHistory run = runDynamic(
      parseScene(blockScene(cyl, "{t_end: 4.0, dt: 1.0e-3, rho_inf: 0.9, initial: static}"), "cylinder-valve.yaml"),
      PETSC_COMM_SELF);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  auto imbalance = [&](double w) {
    const double a = A1 * w / (Cv * u), b = A2 * w / (Cv * u);
    return (ps - a * a) * A1 - (pt + b * b) * A2 - cv * w - m * g;
  };
  double lo = 0, hi = Cv * u * std::sqrt(ps) / A1; // imbalance(lo) > 0 > imbalance(hi)
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (imbalance(mid) > 0 ? lo : hi) = mid;
  }
  const double w = 0.5 * (lo + hi), a = A1 * w / (Cv * u), b = A2 * w / (Cv * u);
  const double p1 = ps - a * a, p2r = pt + b * b;
  const std::vector<double> &last = run.outputs.back();
  PetscPrintf(PETSC_COMM_SELF,
              "  valve lift: speed %.8e m/s vs %.8e (rel. %.2e); p1 %.6f bar vs %.6f; p2 %.6f bar vs %.6f; spool %.6f\n",
              last[StrokeRate], w, std::abs(last[StrokeRate] / w - 1), last[P1] / 1e5, p1 / 1e5, last[P2] / 1e5,
              p2r / 1e5, last.back());
  ASSERT_GT(ps - p1, 2e5); // both edges above the laminar limit: the square-root law applies
  ASSERT_GT(p2r - pt, 2e5);
  EXPECT_NEAR(last[StrokeRate] / w, 1.0, 1e-6);
  EXPECT_NEAR(last[P1] / p1, 1.0, 1e-6);
  EXPECT_NEAR(last[P2] / p2r, 1.0, 1e-6);
  EXPECT_NEAR(last[Q1], A1 * w, 1e-6 * A1 * w);
  EXPECT_NEAR(last.back(), u, 1e-9); // the spool settled on its command
}
