// The elastic tension-only rope end to end (docs/model.md §7), against
// closed-form references:
//  - a 10 kg body on a 1 m rope of EA = 1e4 N, released with the rope slack
//    by d = 5 cm: free fall until taut at t1 = sqrt(2 d / g), then the
//    oscillation delta(tau) = ds (1 - cos w tau) + (v1 / w) sin w tau about
//    the static stretch ds = m g / k with w = sqrt(EA / (L m)), the peak
//    stretch from energy conservation k dmax^2 / 2 = m g (d + dmax), slack
//    again when delta returns to 0 and taut again 2 v1 / g later;
//  - a pretensioned pair (a body held between two ropes): static stiffness
//    2k while both are taut, k after one went slack at F = 2 T0;
//  - EA -> large reproduces the inextensible rope (tension and position).
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double g = 9.81, m = 10.0, L0 = 1.0, EA = 1.0e4, d = 0.05;

std::string hangingScene(double dt, double tEnd)
{
  return R"(
name: hanging-mass
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: ceiling, type: rigid, length: 0.2, origin: [-0.1, 0], section: {rhoA: 1}}
  - {name: bob, type: rigid, length: 0.1, origin: [-0.05, -0.95], section: {rhoA: 100}}
constraints:
  - {type: clamp, body: ceiling, at: start}
  - {type: elastic_rope, name: rope, from: ceiling, from_at: 0.1, to: bob, to_at: 0.05, EA: 1.0e4, length: 1.0}
dynamic: {t_end: )" + std::to_string(tEnd) +
         ", dt: " + std::to_string(dt) + R"(, rho_inf: 1.0}
)";
}

// Root of f in [a, b] by bisection (f(a), f(b) of opposite sign).
template <class F> double bisect(F f, double a, double b)
{
  for (int it = 0; it < 200; ++it) {
    const double c = 0.5 * (a + b);
    ((f(c) > 0) == (f(a) > 0) ? a : b) = c;
  }
  return 0.5 * (a + b);
}

} // namespace

TEST(ElasticRopeVerification, HangingMassFallsTautensAndBounces)
{
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "thousands of steps of a 6-coordinate model: minutes on 2 ranks for nothing; the rope on "
                                 "2 ranks is RankIndependence.ElasticRopeRunMatchesSingleRank (mpi2.regression)";
  const double k = EA / L0, w = std::sqrt(k / m), ds = m * g / k;
  const double t1 = std::sqrt(2 * d / g), v1 = g * t1;
  const double dmax = (m * g + std::sqrt(m * g * m * g + 2 * k * m * g * d)) / k;
  auto delta = [&](double tau) { return ds * (1 - std::cos(w * tau)) + v1 / w * std::sin(w * tau); };
  const double tau2 = bisect(delta, M_PI / w, 2 * M_PI / w); // back to zero stretch
  const double t2 = t1 + tau2, t3 = t2 + 2 * v1 / g;
  const double dt = 1e-4;
  const DynamicHistory run = runDynamic(parseScene(hangingScene(dt, 0.45), "hanging-mass.yaml"));
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  ASSERT_EQ(run.outputs.front().size(), 3u); // tension, length, stretch
  double peak = -1, peakTension = 0;
  for (std::size_t s = 0; s < run.time.size(); ++s)
    if (run.time[s] < t2) peak = std::max(peak, run.outputs[s][2]), peakTension = std::max(peakTension, run.outputs[s][0]);
  ASSERT_EQ(run.events.size(), 3u) << "taut, slack, taut";
  const double measuredTau2 = run.events[1].t - run.events[0].t;
  PetscPrintf(PETSC_COMM_SELF,
              "  hanging mass (h = %g s): taut at %.9f s (exact %.9f, rel. %.1e); peak stretch %.7f m (exact %.7f, "
              "rel. %.1e); taut phase %.6f s (exact %.6f, rel. %.1e); slack at %.6f (exact %.6f); taut again at %.6f "
              "(exact %.6f)\n",
              dt, run.events[0].t, t1, std::abs(run.events[0].t / t1 - 1), peak, dmax, std::abs(peak / dmax - 1),
              measuredTau2, tau2, std::abs(measuredTau2 / tau2 - 1), run.events[1].t, t2, run.events[2].t, t3);
  EXPECT_EQ(run.events[0].kind, "taut");
  EXPECT_EQ(run.events[0].direction, 1);
  EXPECT_EQ(run.events[1].kind, "slack");
  EXPECT_EQ(run.events[1].direction, -1);
  EXPECT_EQ(run.events[2].kind, "taut");
  EXPECT_NEAR(run.events[0].t, t1, 1e-6 * t1);       // free fall: the interpolated crossing is exact
  EXPECT_NEAR(peak, dmax, 1e-3 * dmax);              // energy conservation at rho_inf = 1
  EXPECT_NEAR(peakTension, k * dmax, 1e-3 * k * dmax);
  EXPECT_NEAR(measuredTau2, tau2, 1e-3 * tau2);      // the frequency sqrt(EA / (L m))
  EXPECT_NEAR(run.events[2].t, t3, 1e-3 * t3);
}

TEST(ElasticRopeVerification, PretensionedPairStiffnessDoublesWhileBothAreTaut)
{
  // A body between an upper and a lower anchor, each rope spanning 1 m with
  // EA = 1e5 N and pretension T0 = 1000 N; a downward force F: both
  // taut up to F = 2 T0 (u = F / 2k), then only the upper one (u = T0/k +
  // (F - 2 T0)/k). No gravity; the body's rotation is held by an angle drive.
  // k = EA / L0 with L0 = l0 / (1 + T0/EA) = 1 m / 1.01 (the pretension is built into L0).
  const double T0 = 1000, k = (1e5 + T0) / 1.0;
  auto run = [&](double F) {
    const std::string text = R"(
name: rope-pair
analysis: static
gravity: [0, 0]
bodies:
  - {name: top, type: rigid, length: 0.2, origin: [-0.1, 1.0], section: {rhoA: 1}}
  - {name: floor, type: rigid, length: 0.2, origin: [-0.1, -1.0], section: {rhoA: 1}}
  - {name: bob, type: rigid, length: 0.1, origin: [-0.05, 0], section: {rhoA: 100}}
constraints:
  - {type: clamp, body: top, at: start}
  - {type: clamp, body: floor, at: start}
  - {type: angle_drive, body: bob, at: 0.05, angle: 0}
  - {type: elastic_rope, name: upper, from: top, from_at: 0.1, to: bob, to_at: 0.05, EA: 1.0e5, pretension: 1000}
  - {type: elastic_rope, name: lower, from: bob, from_at: 0.05, to: floor, to_at: 0.1, EA: 1.0e5, pretension: 1000}
loads:
  - {type: point_force, body: bob, at: 0.05, force: [0, )" +
                             std::to_string(-F) + R"(]}
static: {load_steps: 4}
output:
  sensors:
    - {name: bob, body: bob, at: 0.05}
)";
    const StaticOutcome out = runStatic(parseScene(text, "rope-pair.yaml"));
    EXPECT_TRUE(out.converged);
    return out.sensors.empty() ? 0.0 : -out.sensors[0].position.y();
  };
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // L0 = l0 / (1 + T0/EA) is built in: the pretension is exact at F = 0.
  const double loads[] = {500, 1500, 1999, 2001, 3000, 5000};
  double worst = 0;
  for (double F : loads) {
    const double u = run(F), exact = F <= 2 * T0 ? F / (2 * k) : T0 / k + (F - 2 * T0) / k;
    if (rank == 0) worst = std::max(worst, std::abs(u - exact) / exact);
  }
  // The stiffness halves at the predicted displacement u = T0 / k: secant stiffnesses on both sides.
  const double u500 = run(500), u1500 = run(1500), u3000 = run(3000), u5000 = run(5000);
  if (rank == 0) {
    PetscPrintf(PETSC_COMM_SELF, "  rope pair: worst relative error of the displacement %.2e over F = 500 ... 5000 N\n",
                worst);
    EXPECT_LT(worst, 1e-8);
    EXPECT_NEAR((1500 - 500) / (u1500 - u500), 2 * k, 1e-8 * k);
    EXPECT_NEAR((5000 - 3000) / (u5000 - u3000), k, 1e-8 * k);
  }
}

TEST(ElasticRopeVerification, StiffRopeReproducesTheInextensibleRope)
{
  // A pendulum: a 10 kg body swings on a rope from a ceiling over a pulley
  // (rope: ceiling start -> pulley at the ceiling's middle -> body), once
  // with the inextensible `rope`, once with an `elastic_rope` of EA = 1e9 N
  // (static stretch ~1e-7 m; its axial mode at ~1.5 kHz is damped by
  // rho_inf = 0.5 within a few steps of 1 ms).
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "thousands of steps of a 6-coordinate model: minutes on 2 ranks for nothing; the rope on "
                                 "2 ranks is RankIndependence.ElasticRopeRunMatchesSingleRank (mpi2.regression)";
  auto scene = [](const std::string &rope) {
    return parseScene(R"(
name: rope-pendulum
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: ceiling, type: rigid, length: 0.4, origin: [-0.2, 0], section: {rhoA: 1}}
  - {name: bob, type: rigid, length: 0.1, origin: [0.45, -0.8], section: {rhoA: 100}}
constraints:
  - {type: clamp, body: ceiling, at: start}
  - {)" + rope + R"(, name: rope, from: ceiling, from_at: 0.0, pulley: ceiling, pulley_at: 0.2, to: bob, to_at: 0.05}
dynamic: {t_end: 1.0, dt: 1.0e-3, rho_inf: 0.5}
output:
  sensors:
    - {name: bob, body: bob, at: 0.05}
)",
                      "rope-pendulum.yaml");
  };
  // Full Newton: a rope 1e9 N stiff turns the Newton tolerance's error in the
  // positions into tension errors; with the default Jacobian reuse the two
  // differ by 1.2e-4 m and 3.4e-4 of the tension (docs/defaults.md).
  // The stiff rope's tension, EA times the stretch of the step's positions,
  // is the penalty form of the step's own index-3 multiplier, so the two
  // integrations agree to the stretch when the inextensible rope reports
  // that multiplier (the default, -boom_consistent_multipliers 0). Its other
  // report, the multiplier of the acceleration-level equations at the step's state,
  // differs from both by the index-3 multiplier's time-step error, checked
  // separately below.
  PetscOptionsSetValue(nullptr, "-boom_jacobian_reuse", "0");
  SimulationOptions stepMultipliers = testOptions(), consistent = testOptions();
  stepMultipliers.consistentMultipliers = false;
  consistent.consistentMultipliers = true;
  const DynamicHistory rigid = runDynamicWith(scene("type: rope"), PETSC_COMM_WORLD, stepMultipliers);
  const DynamicHistory reported = runDynamicWith(scene("type: rope"), PETSC_COMM_WORLD, consistent);
  const DynamicHistory elastic = runDynamicWith(scene("type: elastic_rope, EA: 1.0e9"), PETSC_COMM_WORLD, testOptions());
  PetscOptionsClearValue(nullptr, "-boom_jacobian_reuse");
  ASSERT_TRUE(rigid.summary.completed && reported.summary.completed && elastic.summary.completed);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  ASSERT_EQ(rigid.time.size(), elastic.time.size());
  ASSERT_EQ(reported.time.size(), elastic.time.size());
  double position = 0, tension = 0, reportedTension = 0, maxTension = 0;
  for (std::size_t s = 0; s < rigid.time.size(); ++s) {
    position = std::max(position, (rigid.sensors[s][0].position - elastic.sensors[s][0].position).norm());
    maxTension = std::max(maxTension, rigid.outputs[s][0]);
    if (rigid.time[s] < 0.05) continue;
    tension = std::max(tension, std::abs(rigid.outputs[s][0] - elastic.outputs[s][0]));
    reportedTension = std::max(reportedTension, std::abs(reported.outputs[s][0] - elastic.outputs[s][0]));
  }
  PetscPrintf(PETSC_COMM_SELF,
              "  EA = 1e9 vs inextensible rope: max position difference %.2e m, max tension difference after 0.05 s "
              "%.2e N against the step's multiplier, %.2e N against the reported one (max tension %.1f N)\n",
              position, tension, reportedTension, maxTension);
  EXPECT_LT(position, 1e-6);
  EXPECT_LT(tension, 1e-6 * maxTension); // measured 9e-8 relative
  // The index-3 multiplier's error at h = 1 ms on a pendulum of omega ~ 3.5
  // rad/s is of order (omega h)^2 ~ 1e-5 of the tension.
  EXPECT_LT(reportedTension, 1e-5 * maxTension); // measured 2.0e-6 relative
}
