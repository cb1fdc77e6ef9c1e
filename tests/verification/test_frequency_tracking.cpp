// Frequencies from the linearized constrained system (docs/model.md §5) along a
// run and at static states: cantilever with and without a tip mass (tracked),
// a beam under axial tension and compression, and the paper's telescope
// (retracted, extended) against an independent pad-coupled beam model.
#include "support.hpp"
#include "telescope_reference.hpp"

#include "boomdyn/frequency_tracker.hpp"

#include <slepcsys.h>

#include <cmath>
#include <functional>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kL = 2.0, kEI = 4.9531e6, kRhoA = 31.8396;

double bisect(const std::function<double(double)> &f, double lo, double hi)
{
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(lo) * f(mid) <= 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// First cantilever root beta L with a tip mass ratio (0: plain cantilever).
double firstRoot(double ratio)
{
  return bisect([&](double x) { return 1 + std::cos(x) * std::cosh(x) + ratio * x * (std::cos(x) * std::sinh(x) - std::sin(x) * std::cosh(x)); },
                0.3, 3.0);
}

// Tracked first frequency of a cantilever at rest, at t = 0 and after 20 steps.
std::vector<double> trackedCantilever(double tipMass)
{
  std::string text = R"(
name: tracked-cantilever
analysis: dynamic
bodies:
  - {name: boom, length: 2.0, elements: 16, section: {EA: 8.5176e8, EI: 4.9531e6, rhoA: 31.8396}}
constraints:
  - {type: clamp, body: boom, at: start}
dynamic: {t_end: 0.02, dt: 1.0e-3}
)";
  if (tipMass > 0) text += "masses:\n  - {body: boom, at: end, mass: " + std::to_string(tipMass) + "}\n";
  const Scene scene = parseScene(text, "tracked-cantilever.yaml");
  HandIntegration run(scene); // rho_inf 0.8, 25 Newton iterations: the scene's defaults
  GeneralizedAlpha &integrator = *run.integrator;
  std::vector<double> out;
  FrequencyTracker tracker(run.assembler, 4);
  TrackedModes modes;
  check(tracker.analyze(0.0, integrator.positions(), integrator.multipliers(), &modes));
  out.push_back(modes.trackedHz);
  RunSummary summary;
  check(integrate(integrator, scene.dynamic, nullptr, &summary));
  check(tracker.analyze(integrator.time(), integrator.positions(), integrator.multipliers(), &modes));
  out.push_back(modes.trackedHz);
  out.push_back(modes.mac);
  return out;
}

// Modes at the static equilibrium of a scene (like analysis: modal). With
// bendingOnly, modes whose beam nodes move more along x than along y (axial
// modes) are dropped.
std::vector<double> staticModes(const Scene &scene, int count, bool bendingOnly = false)
{
  const ModalResult modes = modesAtStaticEquilibrium(scene, count);
  const Model model(scene); // the layout of the coordinates
  if (!bendingOnly) return modes.frequencyHz;
  std::vector<double> bending;
  for (std::size_t k = 0; k < modes.frequencyHz.size(); ++k) {
    int transverse = 1;
    if (!modes.shapes.empty()) { // shapes live on rank 0
      double ux = 0, uy = 0;
      for (const auto &b : model.bodies())
        for (PetscInt i = b->firstCoordinate(); i < b->firstCoordinate() + b->numCoordinates(); i += 4)
          ux = std::max(ux, std::abs(modes.shapes[k][i])), uy = std::max(uy, std::abs(modes.shapes[k][i + 1]));
      transverse = uy > ux;
    }
    MPI_Bcast(&transverse, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    if (transverse) bending.push_back(modes.frequencyHz[k]);
  }
  return bending;
}

} // namespace

TEST(FrequencyTracking, CantileverWithAndWithoutTipMass)
{
  for (double mass : {0.0, 100.0}) {
    const double bl = firstRoot(mass / (kRhoA * kL));
    const double exact = bl * bl / (kL * kL) * std::sqrt(kEI / kRhoA) / (2 * M_PI);
    const std::vector<double> f = trackedCantilever(mass);
    PetscPrintf(PETSC_COMM_WORLD, "  tip mass %5.1f kg: tracked %.6f Hz (t = 0), %.6f Hz (t = 0.02 s, MAC %.6f); theory %.6f Hz\n",
                mass, f[0], f[1], f[2], exact);
    EXPECT_LT(std::abs(f[0] - exact) / exact, 1e-3);
    EXPECT_LT(std::abs(f[1] - exact) / exact, 1e-3);
    EXPECT_GT(f[2], 0.999);
  }
}

TEST(FrequencyTracking, AxialForceRaisesAndLowersTheFirstFrequency)
{
  // Simply supported beam: pinned at s = 0, its end s = L sliding on a clamped
  // rigid rail (a roller), axial force N at the end. Exact:
  //   omega^2 = (pi/L)^2 [ (pi/L)^2 EI + N ] / rhoA.
  const double EI = 1.0e4, rhoA = 10.0, L = 2.0, Ncr = M_PI * M_PI * EI / (L * L);
  for (double ratio : {-0.5, 0.0, 0.5, 2.0}) {
    const double N = ratio * Ncr;
    char text[2048];
    std::snprintf(text, sizeof text, R"(
name: axially-loaded
analysis: modal
bodies:
  - {name: beam, length: 2.0, elements: 16, section: {EA: 1.0e11, EI: 1.0e4, rhoA: 10.0}}
  - {name: rail, type: rigid, length: 1.0, origin: [1.5, 0], section: {rhoA: 1.0}}
constraints:
  - {type: pin, body: beam, at: start}
  - {type: clamp, body: rail, at: start}
  - {type: sliding_joint, name: roller, body: beam, at: end, track: rail}
loads:
  - {type: point_force, body: beam, at: end, force: [%.12g, 0]}
static: {load_steps: 4}
modal: {count: 2}
)",
                  N);
    const std::vector<double> f = staticModes(parseScene(text, "axially-loaded.yaml"), 2);
    const double k = M_PI / L, exact = std::sqrt(k * k * (k * k * EI + N) / rhoA) / (2 * M_PI);
    PetscPrintf(PETSC_COMM_WORLD, "  N = %+5.2f N_cr: first frequency %.6f Hz, exact %.6f Hz, relative error %.2e\n", ratio,
                f[0], exact, std::abs(f[0] - exact) / exact);
    EXPECT_LT(std::abs(f[0] - exact) / exact, 1e-3) << "N = " << ratio << " N_cr";
  }
}

class TelescopeModes : public ::testing::TestWithParam<bool> {};

TEST_P(TelescopeModes, FirstThreeMatchPadCoupledBeams)
{
  const bool extended = GetParam();
  TelescopeReference ref;
  ref.g = 0;
  if (extended) ref.x0[1] = 1.5, ref.x0[2] = 3.0;
  char text[4096];
  std::snprintf(text, sizeof text, R"(
name: telescope-modes
analysis: modal
bodies:
  - {name: boom1, length: 2.0, elements: 16, origin: [%.12g, 0], section: {E: 2.1e11, rho: 7850, A: 6.944e-3, I: 6.395214e-5}}
  - {name: boom2, length: 2.0, elements: 16, origin: [%.12g, 0], section: {E: 2.1e11, rho: 7850, A: 5.264e-3, I: 3.720306e-5}}
  - {name: boom3, length: 2.0, elements: 16, origin: [%.12g, 0], section: {E: 2.1e11, rho: 7850, A: 3.816e-3, I: 1.986431e-5}}
constraints:
  - {type: clamp, name: base, body: boom1, at: start}
  - {type: sliding_joint, name: j1, body: boom1, at: end, track: boom2}
  - {type: sliding_joint, name: j2, body: boom2, at: start, track: boom1}
  - {type: sliding_joint, name: j3, body: boom2, at: end, track: boom3}
  - {type: sliding_joint, name: j4, body: boom3, at: start, track: boom2}
  - {type: extraction_drive, name: extraction, joint: j2, displacement: 0}
  - {type: rope, name: rope, from: boom1, from_at: start, pulley: boom2, pulley_at: end, to: boom3, to_at: start}
modal: {count: 6}
)",
                ref.x0[0], ref.x0[1], ref.x0[2]);
  // The model also has axial modes (booms 2 and 3 moving along the axis
  // against the rope and the drive, 208.8 Hz retracted) that the transverse
  // reference cannot have: compare the first three bending modes.
  const std::vector<double> model = staticModes(parseScene(text, "telescope-modes.yaml"), 6, true);
  ASSERT_GE(model.size(), 3u);
  const std::vector<double> reference = ref.frequencies(3);
  for (int k = 0; k < 3; ++k) {
    const double rel = std::abs(model[k] - reference[k]) / reference[k];
    PetscPrintf(PETSC_COMM_WORLD, "  telescope %s mode %d: %.6f Hz, pad-coupled beams %.6f Hz, relative difference %.2e\n",
                extended ? "extended " : "retracted", k + 1, model[k], reference[k], rel);
    EXPECT_LT(rel, 1e-3) << "mode " << k + 1;
  }
}

INSTANTIATE_TEST_SUITE_P(Configurations, TelescopeModes, ::testing::Values(false, true),
                         [](const auto &info) { return std::string(info.param ? "Extended" : "Retracted"); });
