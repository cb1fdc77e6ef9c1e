// Reaction forces of prescribed motions (issue 40, item 1): a rigid 10 kg
// block slides without friction along a clamped rigid rail, moved by an
// extraction drive along an accel-limited profile. The block's motion is
// fully prescribed, so the drive force is exactly m a(t), a(t) the
// profile's second derivative (right limit at a jump). The index-3
// generalized-alpha multipliers carry an error that every jump of a(t)
// excites (at rho_inf = 1 it never decays); with the restart at
// acceleration jumps and the multipliers reported from the
// acceleration-level equations (docs/model.md §4.8) the force must equal
// m a(t) to 1e-6 of its peak at every step after a jump, at rho_inf = 0.8
// and 1, for a trapezoidal and for an S-curve (jerk-limited) profile.
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kMass = 10.0, kBlockLength = 0.5;
// Drive row: clamp (pin 2 + angle 1), rear (2), front (2), push (1).
constexpr int kPushRow = 7;

std::string blockScene(const std::string &profile, double rhoInf, double h, double tEnd)
{
  char text[2048];
  std::snprintf(text, sizeof text, R"(
name: driven-block
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: rail, type: rigid, length: 4.0, section: {rhoA: 10.0}}
  - {name: block, type: rigid, length: %g, origin: [0.5, 0.0], section: {rhoA: %g}}
constraints:
  - {type: clamp, name: base, body: rail, at: start}
  - {type: sliding_joint, name: rear, body: block, at: start, track: rail}
  - {type: sliding_joint, name: front, body: block, at: end, track: rail}
  - {type: extraction_drive, name: push, joint: rear, displacement: %s}
dynamic: {t_end: %g, dt: %g, rho_inf: %g}
)",
                kBlockLength, kMass / kBlockLength, profile.c_str(), tEnd, h, rhoInf);
  return text;
}

struct Profile {
  const char *name;
  const char *yaml;
  TimeFunction f;
};

// The profiles start off the step grid (t0 = 0.0123 s), so that every jump
// lies inside a nominal step.
std::vector<Profile> profiles()
{
  return {{"trapezoid", "{type: accel_limited, t0: 0.0123, to: 0.6, speed: 0.5, accel: 2.0}",
           TimeFunction::accelLimited(0.0123, 0.0, 0.6, 0.5, 2.0)},
          {"S-curve", "{type: accel_limited, t0: 0.0123, to: 0.6, speed: 0.5, accel: 2.0, jerk: 20.0}",
           TimeFunction::accelLimited(0.0123, 0.0, 0.6, 0.5, 2.0, 20.0)}};
}

struct ForceError {
  double worst = 0;   // max |F - m a| / (m a_peak) over the steps after the first jump
  double atWorst = 0; // time of that step
};

ForceError driveForceError(const DynamicHistory &h, const TimeFunction &f, double peakAccel)
{
  ForceError e;
  for (std::size_t k = 1; k < h.time.size(); ++k) {
    const double t = h.time[k];
    // The drive's multiplier pushes the block along -C_q^T lambda: F = -lambda.
    const double err = std::abs(-h.multipliers[k][kPushRow] - kMass * f.accel(t)) / (kMass * peakAccel);
    if (err > e.worst) e.worst = err, e.atWorst = t;
  }
  return e;
}

DynamicHistory runBlock(const Profile &p, double rhoInf, double h, bool restart = true, bool consistent = true)
{
  const double tEnd = p.f.endTime() + 0.1;
  SimulationOptions o = testOptions();
  o.kinkRestart = restart;            // -boom_kink_restart
  o.consistentMultipliers = consistent; // -boom_consistent_multipliers
  return runDynamicWith(parseScene(blockScene(p.yaml, rhoInf, h, tEnd), "driven-block.yaml"), PETSC_COMM_SELF, o);
}

} // namespace

TEST(DriveReactions, RigidBlockForceEqualsMassTimesProfileAcceleration)
{
  const double h = 5e-3, peak = 2.0;
  for (const Profile &p : profiles())
    for (double rho : {0.8, 1.0}) {
      const DynamicHistory run = runBlock(p, rho, h, true);
      ASSERT_TRUE(run.summary.completed) << run.summary.failure;
      const ForceError e = driveForceError(run, p.f, peak);
      // The block follows the profile (position level).
      double worstPosition = 0;
      for (std::size_t k = 0; k < run.time.size(); ++k)
        worstPosition =
          std::max(worstPosition, std::abs(run.slacks[k][0] - run.slacks[0][0] - p.f.value(run.time[k])));
      PetscPrintf(PETSC_COMM_SELF,
                  "  %-9s rho_inf = %.1f, h = %g s: max |F - m a| / (m a_peak) = %.2e at t = %.4f s; "
                  "position error %.1e m\n",
                  p.name, rho, h, e.worst, e.atWorst, worstPosition);
      EXPECT_LT(e.worst, 1e-6) << p.name << " at rho_inf = " << rho;
      EXPECT_LT(worstPosition, 1e-10);
    }
}

// Each fix alone, on the step's own (index-3) multipliers: the restart at
// the trapezoid's acceleration jumps makes them exact too (generalized-alpha
// follows a piecewise constant acceleration exactly from a consistent
// start), but not on the S-curve, whose linear acceleration phases leave an
// O(h) alternating error; without the restart both ring (at rho_inf = 1
// without decay). So every comparison above can fail.
TEST(DriveReactions, IndexThreeMultipliersRingWithoutTheFixes)
{
  const double h = 5e-3, peak = 2.0;
  const std::vector<Profile> p = profiles();
  struct Case {
    const Profile &profile;
    bool restart;
    double rho;
    bool exact; // expected below 1e-6, else above 1e-2
  };
  for (const Case &c : {Case{p[0], true, 1.0, true}, Case{p[0], true, 0.8, true}, Case{p[0], false, 1.0, false},
                        Case{p[0], false, 0.8, false}, Case{p[1], true, 1.0, false}, Case{p[1], false, 1.0, false}}) {
    const DynamicHistory run = runBlock(c.profile, c.rho, h, c.restart, false);
    ASSERT_TRUE(run.summary.completed) << run.summary.failure;
    const ForceError e = driveForceError(run, c.profile.f, peak);
    PetscPrintf(PETSC_COMM_SELF,
                "  index-3 multipliers, %-9s rho_inf = %.1f, restart %s: max |F - m a| / (m a_peak) = %.2e at t = "
                "%.4f s\n",
                c.profile.name, c.rho, c.restart ? "on " : "off", e.worst, e.atWorst);
    if (c.exact)
      EXPECT_LT(e.worst, 1e-6) << c.profile.name;
    else
      EXPECT_GT(e.worst, 1e-2) << c.profile.name;
  }
}
