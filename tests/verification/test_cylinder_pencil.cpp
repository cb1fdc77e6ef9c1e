// The hydraulic cylinder in the damped eigen-analysis (docs/model.md §2.6,
// "Eigen-analysis"), on a rigid block of mass m held up by a vertical
// cylinder from a ground point (rotation locked by an angle drive, held
// sideways by a long horizontal spring, as in test_hydraulic_cylinder.cpp,
// but stiff enough that the vertical mode is the lowest of the two), at the
// static equilibrium (the stroke held at s0):
//  - closed valve with viscous friction c_v and smoothed Coulomb friction
//    F_c tanh(s'/v_c): about rest the friction is the damper
//    c = c_v + F_c / v_c on the stroke, and the block's vertical mode is the
//    damped oscillator m s'' + c s' + k_h s = 0 with k_h = A1^2/C1 + A2^2/C2:
//    zeta = c / (2 sqrt(k_h m)), omega_d = omega_n sqrt(1 - zeta^2). The
//    damped pencil (SLEPc PEP) and the tracking's damped refinement (no
//    fall-back to the full solve) must give both within 1e-8;
#include "cylinder_block.hpp"
#include "support.hpp"

#include "boomdyn/damped_eigen_solver.hpp"
#include "boomdyn/frequency_tracker.hpp"

#include <slepcsys.h>

#include <cmath>
#include <complex>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

using namespace boomdyn::testing::cylinder_block;
const double kh = A1 * A1 / C1 + A2 * A2 / C2;

// The damped mode with |lambda| nearest omega.
int nearest(const DampedModalResult &dm, double omega)
{
  int best = -1;
  for (int k = 0; k < (int)dm.omega.size(); ++k)
    if (best < 0 || std::abs(dm.omega[k] - omega) < std::abs(dm.omega[best] - omega)) best = k;
  return best;
}

} // namespace

TEST(CylinderPencil, FrictionDampsTheOilColumnLikeTheClosedForm)
{
  const double cv = 2.0e4, Fc = 150.0, vc = 5e-3, c = cv + Fc / vc;
  StaticEquilibrium block(parseScene(cylinder_block::scene("valve: closed, initial_pressure_rod: 2.0e+6, friction_viscous: 2.0e+4, "
                                          "friction_coulomb: 150, friction_velocity: 5.0e-3",
                                          "{t_end: 0.01, dt: 1.0e-3, initial: static}", "1.0e+8"),
                                            "cylinder-pencil.yaml"));
  const double omega = std::sqrt(kh / m), zeta = c / (2 * std::sqrt(kh * m)), omegaD = omega * std::sqrt(1 - zeta * zeta);

  // The full PEP solve.
  DampedModalResult dm;
  check(solveDampedModes(block.assembler, 0.0, block.x, block.multipliers(), 1, &dm));
  const int k = nearest(dm, omega);
  ASSERT_GE(k, 0);
  // The tracking's refinement of the same modes.
  FrequencyTracker tracker(block.assembler, 1);
  TrackedModes tracked;
  DampedModalResult refined;
  check(tracker.analyze(0.0, block.x, block.multipliers(), &tracked));
  check(tracker.analyzeDamped(0.0, block.x, block.multipliers(), &tracked, &refined));
  const int r = nearest(refined, omega);
  ASSERT_GE(r, 0);
  PetscPrintf(PETSC_COMM_WORLD,
              "  oil column with friction (c = %.0f N s/m): zeta PEP %.10f refined %.10f closed form %.10f; omega_d PEP "
              "%.8f refined %.8f closed form %.8f rad/s; refinement %s\n",
              c, dm.dampingRatio[k], refined.dampingRatio[r], zeta, dm.dampedOmega[k], refined.dampedOmega[r], omegaD,
              tracked.dampedRefined ? "converged" : "fell back to the full solve");
  EXPECT_NEAR(dm.dampingRatio[k] / zeta, 1.0, 1e-8);
  EXPECT_NEAR(dm.dampedOmega[k] / omegaD, 1.0, 1e-8);
  EXPECT_TRUE(tracked.dampedRefined);
  EXPECT_NEAR(refined.dampingRatio[r] / zeta, 1.0, 1e-8);
  EXPECT_NEAR(refined.dampedOmega[r] / omegaD, 1.0, 1e-8);
}

// The boom of inputs/hoist_bounce_cylinder.yaml held by the closed cylinder
// with its friction, at the static start: the tracking's damped refinement
// converges (no fall-back to the full PEP solve), its modes agree with the
// full solve's to 1e-8, and every damping ratio is positive (the booms'
// Kelvin-Voigt damping, the dampers of pads and ropes and the cylinder's
// friction only take energy out).
TEST(CylinderPencil, DampedRefinementConvergesOnTheBoomHeldByTheCylinder)
{
  StaticEquilibrium boom(readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/hoist_bounce_cylinder.yaml"));
  Assembler &assembler = boom.assembler;
  const Vec x = boom.x, multipliers = boom.multipliers();
  const int count = boom.scene.tracking.count;
  FrequencyTracker tracker(assembler, count);
  TrackedModes tracked;
  DampedModalResult refined, full;
  check(tracker.analyze(0.0, x, multipliers, &tracked));
  check(tracker.analyzeDamped(0.0, x, multipliers, &tracked, &refined));
  DampedModalOptions options;
  options.allowFewer = true; // as the tracking's full solve
  check(solveDampedModes(assembler, 0.0, x, multipliers, count, &full, options));
  EXPECT_TRUE(tracked.dampedRefined);
  ASSERT_EQ(refined.omega.size(), full.omega.size());
  double worstOmega = 0, worstZeta = 0, smallestZeta = HUGE_VAL;
  for (std::size_t k = 0; k < full.omega.size(); ++k) {
    worstOmega = std::max(worstOmega, std::abs(refined.dampedOmega[k] / full.dampedOmega[k] - 1));
    worstZeta = std::max(worstZeta, std::abs(refined.dampingRatio[k] / full.dampingRatio[k] - 1));
    smallestZeta = std::min({smallestZeta, refined.dampingRatio[k], full.dampingRatio[k]});
  }
  PetscPrintf(PETSC_COMM_WORLD,
              "  hoist_bounce_cylinder at the static start: %zu damped modes, refinement %s; refined against full PEP: "
              "omega_d %.2e, zeta %.2e; smallest zeta %.3e; the oil-column mode %.6f Hz, zeta %.6e\n",
              full.omega.size(), tracked.dampedRefined ? "converged" : "fell back", worstOmega, worstZeta, smallestZeta,
              full.dampedOmega.size() > 2 ? full.dampedOmega[2] / (2 * M_PI) : 0.0,
              full.dampingRatio.size() > 2 ? full.dampingRatio[2] : 0.0);
  EXPECT_LT(worstOmega, 1e-8);
  EXPECT_LT(worstZeta, 1e-8);
  EXPECT_GT(smallestZeta, 0.0);
}
