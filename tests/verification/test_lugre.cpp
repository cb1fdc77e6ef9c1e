// LuGre friction at a sliding joint: steady sliding and presliding of a rigid
// block on a rigid horizontal rail (two sliding joints, friction on the rear
// one), driven along the rail by an extraction drive or pushed by a force.
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kMuS = 0.15, kMuC = 0.1, kVs = 1e-3, kAlpha = 2.0, kSigma2 = 3.0;
// Rows: rail clamp (pin 2, angle 1), rear (lambda_d, lambda_n), front (2), drive (1).
constexpr int kRearNormal = 4, kDrive = 7;

std::string blockOnRail(double sigma0, const std::string &extra)
{
  char text[4096];
  std::snprintf(text, sizeof text, R"(
name: block-on-rail
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: rail, type: rigid, length: 4.0, section: {rhoA: 10.0}}
  - {name: block, type: rigid, length: 0.4, origin: [1.0, 0.0], section: {rhoA: 25.0}}
constraints:
  - {type: clamp, body: rail, at: start}
  - type: sliding_joint
    name: rear
    body: block
    at: start
    track: rail
    friction: {mu_s: %g, mu_c: %g, v_s: %g, alpha: %g, sigma0: %g, sigma1: %g, sigma2: %g}
  - {type: sliding_joint, name: front, body: block, at: end, track: rail}
%s
)",
                kMuS, kMuC, kVs, kAlpha, sigma0, std::sqrt(sigma0) * 0.01, kSigma2, extra.c_str());
  return text;
}

double stribeck(double v) { return kMuC + (kMuS - kMuC) * std::exp(-std::pow(std::abs(v / kVs), kAlpha)); }

} // namespace

TEST(LuGre, SteadySlidingForceIsStribeckTimesNormalForcePlusViscous)
{
  for (double v : {2e-4, 1e-3, 3e-3, 1e-2, 0.1}) {
    // Drive the block along the rail at speed v after a smooth start.
    const double t1 = 0.2, tEnd = 1.5, distance = v * (tEnd - t1 / 2);
    char drive[512];
    std::snprintf(drive, sizeof drive,
                  "  - {type: extraction_drive, name: drive, joint: rear, displacement: {type: table, t: [0, %g, %g], "
                  "values: [0, %.12g, %.12g]}}\ndynamic: {t_end: %g, dt: 1.0e-3, rho_inf: 0.8}\n",
                  t1, tEnd, v * t1 / 2, distance, tEnd);
    const DynamicHistory run = runDynamic(parseScene(blockOnRail(1e5, drive), "block-on-rail.yaml"));
    ASSERT_TRUE(run.summary.completed) << run.summary.failure;
    const auto &m = run.multipliers.back();
    const double normal = std::abs(m[kRearNormal]), force = std::abs(m[kDrive]);
    const double expected = stribeck(v) * normal + kSigma2 * v;
    const double rel = std::abs(force - expected) / expected;
    PetscPrintf(PETSC_COMM_WORLD, "  v = %6.0e m/s: drive force %.9f N, g(v)|lambda_n| + sigma2 v = %.9f N (|lambda_n| = %.4f N), relative error %.1e\n",
                v, force, expected, normal, rel);
    EXPECT_LT(rel, 1e-6) << "v = " << v;
  }
}

TEST(LuGre, PreslidingStaysBoundedBelowStaticFriction)
{
  // A tangential force of half the static friction, applied smoothly: the
  // block creeps by the bristle deflection ~ F / (sigma0 |lambda_n|) and stops.
  // Only the rear joint has friction and it carries half the weight, so its
  // static limit is mu_s m g / 2.
  const double sigma0 = 1e5, mass = 25.0 * 0.4, weight = mass * 9.81;
  const double push = 0.5 * kMuS * weight / 2;
  char extra[512];
  std::snprintf(extra, sizeof extra,
                "loads:\n  - {type: point_force, body: block, at: 0.2, force: [%.12g, 0], scale: {type: smooth_step, t0: 0, "
                "t1: 0.2, from: 0, to: 1}}\ndynamic: {t_end: 1.0, dt: 1.0e-3, rho_inf: 0.8}\n",
                push);
  const DynamicHistory run = runDynamic(parseScene(blockOnRail(sigma0, extra), "presliding.yaml"));
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  const double slip = run.slacks.back()[0] - run.slacks.front()[0];
  const double bound = kMuS / sigma0; // bristle deflection at the static limit
  double lateSpeed = 0;
  for (std::size_t k = 0; k < run.time.size(); ++k)
    if (run.time[k] > 0.8)
      lateSpeed = std::max(lateSpeed, std::abs(run.slacks[k][0] - run.slacks[k - 1][0]) / (run.time[k] - run.time[k - 1]));
  PetscPrintf(PETSC_COMM_WORLD, "  presliding: push %.3f N (half the static limit), displacement %.3e m, mu_s/sigma0 = %.3e m, speed after 0.8 s %.1e m/s\n",
              push, slip, bound, lateSpeed);
  EXPECT_GT(slip, 0.0);
  EXPECT_LT(slip, bound);
  EXPECT_LT(lateSpeed, 1e-5) << "no sliding";
}
