// Order of accuracy of generalized-alpha at rho_inf = 0.8 on a rigid
// pendulum whose inertia depends on the state: a planar rigid bar pinned at
// its start (centre of mass off the pin) with and without a point mass at
// its tip, planar and as a spatial model in its plane. The reference is
// computed here, independently of the code: RK4 on the closed-form pendulum
// equation J_O theta'' = -(m_b L/2 + M L) g cos(theta), with the compound
// inertia about the pin J_O = m_b L^2/3 + M L^2.
#include "support.hpp"

#include "boomdyn/spatial_embedding.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kLength = 1.0, kRhoA = 10.0, kGravity = 9.81, kTEnd = 0.4;

Scene pendulum(double tipMass, double h)
{
  std::string s = R"(
name: pendulum-tip-mass
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: bar, type: rigid, length: 1.0, angle: 0, section: {rhoA: 10}}
constraints:
  - {type: pin, body: bar, at: start}
)";
  if (tipMass > 0) s += "masses:\n  - {body: bar, at: end, mass: " + std::to_string(tipMass) + "}\n";
  char dyn[160];
  std::snprintf(dyn, sizeof dyn, "dynamic: {t_end: %.17g, dt: %.17g, rho_inf: 0.8}\n", kTEnd, h);
  s += dyn;
  return parseScene(s, "pendulum-tip-mass.yaml");
}

// theta(t_end) of the closed-form pendulum, released at rest from theta = 0
// (RK4 with 40 000 steps: error far below 1e-12 rad).
double referenceAngle(double tipMass)
{
  const double mb = kRhoA * kLength;
  const double J = mb * kLength * kLength / 3.0 + tipMass * kLength * kLength;
  const double k = (0.5 * mb * kLength + tipMass * kLength) * kGravity / J;
  auto acc = [k](double th) { return -k * std::cos(th); };
  const int n = 40000;
  const double dt = kTEnd / n;
  double th = 0, w = 0;
  for (int i = 0; i < n; ++i) {
    const double k1t = w, k1w = acc(th);
    const double k2t = w + 0.5 * dt * k1w, k2w = acc(th + 0.5 * dt * k1t);
    const double k3t = w + 0.5 * dt * k2w, k3w = acc(th + 0.5 * dt * k2t);
    const double k4t = w + dt * k3w, k4w = acc(th + dt * k3t);
    th += dt / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    w += dt / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
  return th;
}

// The bar's angle at t_end from its centre of mass (the first two
// coordinates in both models: the planar body's centre, the spatial body's
// position), which lies at L/2 (cos theta, sin theta) from the pin.
double angleAtEnd(const Scene &scene)
{
  SimulationOptions options = testOptions();
  // Full Newton (the default of spatial runs): the modified iteration stops
  // anywhere within the Newton tolerance, which would blur the order.
  check(PetscOptionsSetValue(nullptr, "-boom_jacobian_reuse", "0"));
  const DynamicHistory run = runDynamicWith(scene, PETSC_COMM_WORLD, options);
  check(PetscOptionsClearValue(nullptr, "-boom_jacobian_reuse"));
  EXPECT_TRUE(run.summary.completed) << run.summary.failure;
  return std::atan2(run.finalState[1], run.finalState[0]);
}

// Errors at h = 2, 1, 0.5, 0.25 ms and the observed orders between them.
void expectSecondOrder(double tipMass, bool spatial)
{
  const double reference = referenceAngle(tipMass);
  std::vector<double> errors;
  const std::vector<double> steps{2e-3, 1e-3, 5e-4, 2.5e-4};
  for (double h : steps) {
    const Scene planar = pendulum(tipMass, h);
    errors.push_back(std::abs(angleAtEnd(spatial ? spatialEmbedding(planar) : planar) - reference));
  }
  PetscPrintf(PETSC_COMM_WORLD, "  %s, tip mass %g kg: theta(%.1f s) = %.6f rad; errors", spatial ? "spatial" : "planar",
              tipMass, kTEnd, reference);
  for (double e : errors) PetscPrintf(PETSC_COMM_WORLD, " %.3e", e);
  PetscPrintf(PETSC_COMM_WORLD, "; orders");
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    const double order = std::log2(errors[k] / errors[k + 1]);
    PetscPrintf(PETSC_COMM_WORLD, " %.3f", order);
    EXPECT_GE(order, 1.8) << "h = " << steps[k] << " -> " << steps[k + 1];
  }
  PetscPrintf(PETSC_COMM_WORLD, "\n");
  // The swing is real (-1.13 rad alone, -0.80 rad with the tip mass).
  EXPECT_LT(reference, -0.5);
  EXPECT_LT(errors.back(), 1e-5);
}

} // namespace

TEST(PendulumOrder, RigidBarAloneIsSecondOrder) { expectSecondOrder(0.0, false); }

TEST(PendulumOrder, TipPointMassIsSecondOrder) { expectSecondOrder(40.0, false); }

TEST(PendulumOrder, SpatialTipPointMassIsSecondOrder) { expectSecondOrder(40.0, true); }
