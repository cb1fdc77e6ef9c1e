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
  - {body: block, at: 0.05, point: [10.0, 1.0], stiffness: 1.0e+8}
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
  Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/hoist_bounce_cylinder.yaml");
  Model model(scene);
  Assembler assembler(model);
  PetscHandle<Vec> x;
  check(assembler.setUp(PETSC_COMM_WORLD));
  check(assembler.createVector(x.address()));
  check(assembler.initialState(x));
  StaticSolver statics(assembler);
  check(statics.setUp());
  PetscBool converged;
  check(statics.solve(0.0, scene.statics.load_steps, x, nullptr, &converged));
  ASSERT_TRUE(converged);
  check(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  const int count = scene.tracking.count;
  FrequencyTracker tracker(assembler, count);
  TrackedModes tracked;
  DampedModalResult refined, full;
  check(tracker.analyze(0.0, x, statics.multipliers(), &tracked));
  check(tracker.analyzeDamped(0.0, x, statics.multipliers(), &tracked, &refined));
  DampedModalOptions options;
  options.allowFewer = true; // as the tracking's full solve
  check(solveDampedModes(assembler, 0.0, x, statics.multipliers(), count, &full, options));
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
