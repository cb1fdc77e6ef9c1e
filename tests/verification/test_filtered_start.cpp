// The filtered start of generalized-alpha (-boom_filtered_start, docs/model.md
// §4.3) against the closed form of the first step for one mode: a 1 kg rigid
// bar on a zero-length spring to ground (omega^2 = k/m), a force F switched
// on at t = 0, one step of h = 1 ms. From rest with qdd_0 = F/m and a_0 =
// s F/m the recursion of §4.2 gives
//   a_1 = (F/m - alpha_m a_0 - (1 - alpha_f) (omega h)^2 (1/2 - beta) a_0)
//         / ((1 - alpha_m) + (1 - alpha_f) beta (omega h)^2),
//   q_1 = h^2 ((1/2 - beta) a_0 + beta a_1),   v_1 = h ((1 - gamma) a_0 + gamma a_1),
// with s = 1 unfiltered and s = 1/(1 + mu theta (omega h)^2) filtered,
// mu = (1 - gamma/(2 beta))^2, theta = beta (1 - alpha_f)/(1 - alpha_m).
#include "support.hpp"

#include "boomdyn/generalized_alpha.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kMass = 1.0, kForce = 100.0, kStep = 1e-3;

struct FirstStep {
  double q, v;
};

FirstStep closedForm(double omegaH, bool filtered)
{
  const AlphaParameters p = AlphaParameters::fromRhoInf(0.8);
  const double c = 1.0 - p.gamma / (2.0 * p.beta), mu = c * c;
  const double theta = p.beta * (1.0 - p.alpha_f) / (1.0 - p.alpha_m);
  const double w2 = omegaH * omegaH, qdd0 = kForce / kMass;
  const double a0 = filtered ? qdd0 / (1.0 + mu * theta * w2) : qdd0;
  const double a1 = (qdd0 - p.alpha_m * a0 - (1.0 - p.alpha_f) * w2 * (0.5 - p.beta) * a0) /
                    ((1.0 - p.alpha_m) + (1.0 - p.alpha_f) * p.beta * w2);
  const double h = kStep;
  return {h * h * ((0.5 - p.beta) * a0 + p.beta * a1), h * ((1.0 - p.gamma) * a0 + p.gamma * a1)};
}

FirstStep simulated(double omegaH, bool filtered)
{
  const double k = kMass * std::pow(omegaH / kStep, 2);
  char text[1024];
  // The bar's centre (its centre of mass) at the origin: the force and the
  // spring act through it, so it translates along x only.
  std::snprintf(text, sizeof text,
                "name: one-mode\nanalysis: dynamic\nbodies:\n"
                "  - {name: bar, type: rigid, length: 0.2, origin: [-0.1, 0], section: {rhoA: 5.0}}\n"
                "loads:\n  - {type: point_force, body: bar, at: 0.1, force: [%.17g, 0]}\n"
                "springs:\n  - {body: bar, at: 0.1, point: [0, 0], stiffness: %.17g, rest_length: 0}\n"
                "dynamic: {t_end: %.17g, dt: %.17g, rho_inf: 0.8}\n"
                "output:\n  sensors:\n    - {name: centre, body: bar, at: 0.1}\n",
                kForce, k, kStep, kStep);
  SimulationOptions options = testOptions(0);
  options.filteredStart = filtered;
  const DynamicHistory h = runDynamicWith(parseScene(text, "one-mode.yaml"), PETSC_COMM_SELF, options);
  EXPECT_TRUE(h.summary.completed) << h.summary.failure;
  EXPECT_EQ(h.summary.steps, 1);
  const SensorReading &r = h.sensors.back()[0];
  EXPECT_LT(std::abs(r.position.y()) + std::abs(r.velocity.y()), 1e-14) << "translation along x only";
  return {r.position.x(), r.velocity.x()};
}

} // namespace

TEST(FilteredStart, FirstStepOfOneModeMatchesTheClosedForm)
{
  for (double omegaH : {0.3, 30.0, 3000.0})
    for (bool filtered : {false, true}) {
      const FirstStep want = closedForm(omegaH, filtered), got = simulated(omegaH, filtered);
      PetscPrintf(PETSC_COMM_SELF, "  omega h = %6g, %-10s q_1 = %.10e m (closed form %.10e), v_1 = %.10e m/s (%.10e)\n",
                  omegaH, filtered ? "filtered:" : "a_0 = qdd_0:", got.q, want.q, got.v, want.v);
      // The scale of each: the static deflection F/k and the velocity h F/m.
      const double k = kMass * std::pow(omegaH / kStep, 2);
      EXPECT_NEAR(got.q, want.q, 1e-9 * kForce / k) << "omega h " << omegaH;
      EXPECT_NEAR(got.v, want.v, 1e-9 * std::max(std::abs(want.v), kStep * kForce / kMass * 1e-6)) << "omega h " << omegaH;
    }
}

TEST(FilteredStart, FirstStepEnergyStaysAtTheStaticScale)
{
  // The kinetic energy a mode takes from the first step, against its static
  // strain energy F^2/(2k): unfiltered it grows like (c omega h)^2 without
  // bound; filtered it stays below 1/(4 theta) = 0.97 of it (docs/model.md
  // §4.3), and a well resolved mode is left as it was.
  const AlphaParameters p = AlphaParameters::fromRhoInf(0.8);
  const double theta = p.beta * (1.0 - p.alpha_f) / (1.0 - p.alpha_m);
  for (double omegaH : {0.3, 30.0, 300.0, 3000.0, 30000.0}) {
    const double k = kMass * std::pow(omegaH / kStep, 2), strain = kForce * kForce / (2 * k);
    const FirstStep raw = simulated(omegaH, false), filtered = simulated(omegaH, true);
    const double eRaw = 0.5 * kMass * raw.v * raw.v / strain, eFiltered = 0.5 * kMass * filtered.v * filtered.v / strain;
    PetscPrintf(PETSC_COMM_SELF, "  omega h = %7g: kinetic energy after step 1 / (F^2/2k): %.3e unfiltered, %.3e filtered\n",
                omegaH, eRaw, eFiltered);
    EXPECT_LT(eFiltered, 1.0 / (4.0 * theta)) << "omega h " << omegaH;
    if (omegaH >= 3000) EXPECT_GT(eRaw, 100.0 * eFiltered) << "omega h " << omegaH;
    if (omegaH <= 0.3) EXPECT_NEAR(filtered.q, raw.q, 1e-4 * std::abs(raw.q)) << "a resolved mode keeps its start";
  }
}
