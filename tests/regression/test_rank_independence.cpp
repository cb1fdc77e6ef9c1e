// mpirun -n N must give the same answers as one rank: the same dynamic run on
// the world communicator and on each rank alone agrees to 1e-10 relative.
// Meaningful under mpiexec -n 2 (CTest entry mpi2.regression).
#include "support.hpp"

#include "boomdyn/damped_eigen_solver.hpp"
#include "boomdyn/frequency_tracker.hpp"

#include <slepcsys.h>

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// Two pinned beams, a clamp with a moving angle, a tip mass and a load: every
// kind of work item, spread over both ranks.
const char *kScene = R"(
name: rank-independence
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: lower, length: 2.0, elements: 12, section: {EA: 8.5e8, EI: 4.95e6, rhoA: 31.8}}
  - {name: upper, length: 1.5, elements: 9, origin: [2.0, 0.0], section: {EA: 6.0e8, EI: 3.0e6, rhoA: 25.0}}
constraints:
  - type: clamp
    body: lower
    at: start
    angle: {type: smooth_step, t0: 0.0, t1: 0.15, from: 0, to: 10}
  - {type: pin, body: lower, at: end, other: upper, other_at: 0.0}
  - {type: angle_drive, body: upper, at: 0.0, angle: 0}
loads:
  - {type: point_force, body: upper, at: end, force: [0, -10000]}
masses:
  - {body: upper, at: end, mass: 50}
dynamic: {t_end: 0.2, dt: 1.0e-3, rho_inf: 0.8}
output:
  sensors:
    - {name: tip, body: upper, at: end}
)";

// kScene with extra keys in the section map of one body (", eta_axial: ...").
void addSectionKeys(std::string &text, const std::string &body, const std::string &keys)
{
  const std::size_t at = text.find("rhoA", text.find("name: " + body));
  text.insert(text.find('}', at), keys);
}

// These tests compare the parallel assembly and solvers with one rank at
// 1e-10, so they run full Newton (-boom_jacobian_reuse 0), whose results do
// not depend on round-off. With the default Jacobian reuse the order of
// summation on 2 ranks can flip a refresh decision of the modified iteration
// and move the result at the Newton tolerance (measured: 2e-10 to 4e-6
// relative on these scenes), which says nothing about the parallel code.
class FullNewtonEnvironment : public ::testing::Environment {
public:
  void SetUp() override { PetscCallVoid(PetscOptionsSetValue(nullptr, "-boom_jacobian_reuse", "0")); }
  void TearDown() override { PetscCallVoid(PetscOptionsClearValue(nullptr, "-boom_jacobian_reuse")); }
};
const ::testing::Environment *const fullNewton = ::testing::AddGlobalTestEnvironment(new FullNewtonEnvironment);

// Largest difference of the final q, v between the two runs, relative to the largest entry.
double finalStateDifference(const DynamicHistory &distributed, const DynamicHistory &alone)
{
  EXPECT_EQ(distributed.finalState.size(), alone.finalState.size());
  double diff = 0, norm = 0;
  for (std::size_t i = 0; i < std::min(alone.finalState.size(), distributed.finalState.size()); ++i) {
    diff = std::max(diff, std::abs(distributed.finalState[i] - alone.finalState[i]));
    norm = std::max(norm, std::abs(alone.finalState[i]));
  }
  return diff / norm;
}

// The scene on every rank and on this rank alone: both runs must complete
// (completed is false, after a recorded failure, when one does not), the
// final q, v agree to 1e-10 relative and the step counts match. `what`
// names the case in the printed difference.
struct RankRuns {
  DynamicHistory distributed, alone;
  bool completed = false;
  double relative = 0; // finalStateDifference
};

RankRuns runOnAllRanksAndOne(const Scene &scene, const char *what)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  RankRuns r;
  r.distributed = runDynamic(scene, PETSC_COMM_WORLD);
  r.alone = runDynamic(scene, PETSC_COMM_SELF);
  EXPECT_TRUE(r.distributed.summary.completed) << r.distributed.summary.failure;
  EXPECT_TRUE(r.alone.summary.completed) << r.alone.summary.failure;
  r.completed = r.distributed.summary.completed && r.alone.summary.completed;
  if (!r.completed) return r;
  r.relative = finalStateDifference(r.distributed, r.alone);
  PetscPrintf(PETSC_COMM_WORLD, "  %s, %d ranks vs 1: max relative difference of final q, v = %.3e, %d steps\n", what, size,
              r.relative, (int)r.alone.summary.steps);
  EXPECT_LT(r.relative, 1e-10);
  EXPECT_EQ(r.distributed.summary.steps, r.alone.summary.steps);
  return r;
}

} // namespace

TEST(RankIndependence, DynamicRunMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  const Scene scene = parseScene(kScene, "rank-independence.yaml");
  runOnAllRanksAndOne(scene, "plain");
}

// An elastic rope (state output channels, an event source, a force element
// whose coordinates lie on both ranks) gives the same run on 2 ranks as on one.
TEST(RankIndependence, ElasticRopeRunMatchesSingleRank)
{
  PetscMPIInt size, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  std::string text = kScene;
  text.insert(text.find("loads:"), "  - {type: elastic_rope, name: stay, from: lower, from_at: 0.5, pulley: lower, "
                                   "pulley_at: end, to: upper, to_at: end, EA: 1.0e7, pretension: 2000, damping: 50}\n");
  const Scene scene = parseScene(text, "rank-independence-rope.yaml");
  const RankRuns r = runOnAllRanksAndOne(scene, "elastic rope");
  ASSERT_TRUE(r.completed);
  const DynamicHistory &distributed = r.distributed, &alone = r.alone;
  if (rank == 0) { // outputs and events live on rank 0
    ASSERT_EQ(distributed.outputs.size(), alone.outputs.size());
    double tension = 0, scale = 0;
    for (std::size_t s = 0; s < alone.outputs.size(); ++s)
      tension = std::max(tension, std::abs(distributed.outputs[s][0] - alone.outputs[s][0])),
      scale = std::max(scale, std::abs(alone.outputs[s][0]));
    EXPECT_LT(tension, 1e-10 * scale);
    EXPECT_EQ(distributed.events.size(), alone.events.size());
  }
}

// A hoist (issue 16): a rigid payload with point masses, one of them
// released at 0.1 s, resting on the ground (ground_contact), hoisted by a
// winch rope from the lower beam over a sheave list at the upper beam's end:
// the same run on 2 ranks as on one (breakpoints, restarts, events).
TEST(RankIndependence, HoistRunMatchesSingleRank)
{
  PetscMPIInt size, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  std::string text = kScene;
  text.insert(text.find("constraints:"),
              "  - {name: payload, type: rigid, length: 0.4, origin: [3.3, -1.0], section: {rhoA: 200}}\n");
  text.insert(text.find("loads:"),
              "  - {type: elastic_rope, name: hoist, from: lower, from_at: 1.0, pulleys: [{body: upper, at: end}], "
              "to: payload, to_at: 0.2, EA: 2.0e6, pretension: 500, winch: {type: ramp, t0: 0.05, t1: 0.2, from: 0, "
              "to: -0.04}}\n"
              "  - {type: ground_contact, name: ground, body: payload, at: 0.2, level: -1.0, stiffness: 1.0e6}\n");
  text.insert(text.find("dynamic:"), "  - {name: hook, body: payload, at: 0.2, mass: 40}\n"
                                     "  - {name: part, body: payload, at: 0.3, mass: 20, release_at: 0.1}\n");
  const Scene scene = parseScene(text, "rank-independence-hoist.yaml");
  const RankRuns r = runOnAllRanksAndOne(scene, "hoist");
  ASSERT_TRUE(r.completed);
  const DynamicHistory &distributed = r.distributed, &alone = r.alone;
  if (rank == 0) {
    ASSERT_EQ(distributed.outputs.size(), alone.outputs.size());
    double diff = 0, scale = 0;
    for (std::size_t s = 0; s < alone.outputs.size(); ++s)
      for (std::size_t c = 0; c < alone.outputs[s].size(); ++c)
        diff = std::max(diff, std::abs(distributed.outputs[s][c] - alone.outputs[s][c])),
        scale = std::max(scale, std::abs(alone.outputs[s][c]));
    EXPECT_LT(diff, 1e-10 * scale);
    ASSERT_EQ(distributed.events.size(), alone.events.size());
    bool released = false;
    for (const TypeEvent &e : alone.events) released = released || (e.kind == "release" && e.t == 0.1);
    EXPECT_TRUE(released);
  }
}

TEST(RankIndependence, DampedDynamicRunMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  // The scene above with Kelvin-Voigt damping in both beams (both forms of the keys).
  std::string text = kScene;
  addSectionKeys(text, "lower", ", eta_axial: 2.0e-4, eta_bending: 4.0e-3");
  addSectionKeys(text, "upper", ", damping_ratio: 0.03, damping_frequency: 5.0");
  const Scene scene = parseScene(text, "rank-independence-damped.yaml");
  const RankRuns r = runOnAllRanksAndOne(scene, "damped");
  ASSERT_TRUE(r.completed);
  const double p1 = r.alone.energyParts.back().dissipation, p2 = r.distributed.energyParts.back().dissipation;
  PetscPrintf(PETSC_COMM_WORLD, "  damped: dissipated power %.6g W vs %.6g W\n", p2, p1);
  EXPECT_GT(p1, 0.0);
  EXPECT_LT(std::abs(p2 - p1), 1e-10 * p1);
}

TEST(RankIndependence, ExtractionSceneMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  // Shortened: 0.5 m of extraction in 0.5 s, so the contact points cross elements.
  const Scene scene = shortenedExtraction(0.5);
  runOnAllRanksAndOne(scene, "extraction");
}

// The kink restart on a distributed layout: the extraction along a linear
// ramp (velocity kinks at 0.1005 s and 0.3005 s, off the 1 ms grid: steps land on
// them, the velocities are projected, accelerations re-solved).
TEST(RankIndependence, KinkedExtractionMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  Scene scene = shortenedExtraction(0.4);
  for (auto &c : scene.constraints)
    if (c.type == "extraction_drive") c.set("displacement", TimeFunction::ramp(0.1005, 0.3005, 0.0, 0.05));
  runOnAllRanksAndOne(scene, "kinked extraction");
}

// The cantilever clamped at its end and loaded at its start: the last rank
// owns the clamp's coordinates and (as every rank's multipliers are
// numbered last) its multipliers, so its items touch only its own rows
// while the first rank's need the other's. That rank skipped the local
// scatter, which is collective, and the run hung on 2 ranks (MUMPS and
// -boom_schur_dd alike) until the ranks decided it together.
TEST(RankIndependence, CantileverClampedAtItsEndMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  const Scene scene = parseScene(R"(
name: clamped-at-end
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: boom, length: 10.0, elements: 20, section: {E: 2.1e11, rho: 7850, A: 4.056e-3, I: 2.3586272e-5}}
constraints:
  - {type: clamp, name: base, body: boom, at: end}
loads:
  - {type: point_force, name: tip, body: boom, at: start, force: [0, -1000], scale: {type: smooth_step, t0: 0, t1: 0.01, from: 0, to: 1}}
dynamic: {t_end: 0.05, dt: 1.0e-3, rho_inf: 0.8}
)",
                                 "clamped-at-end.yaml");
  runOnAllRanksAndOne(scene, "cantilever clamped at its end");
}

namespace {

// Tracked frequencies every 0.1 s along a shortened extraction of the paper scene.
std::vector<double> trackedAlongExtraction(MPI_Comm comm)
{
  const Scene scene = shortenedExtraction(0.4);
  HandIntegration run(scene, comm);
  GeneralizedAlpha &integrator = *run.integrator;
  // Two followed modes (tracking.follow: 2): each by its own MAC, on every rank count alike.
  FrequencyTracker tracker(run.assembler, 4, false, 2);
  std::vector<double> out;
  double next = 0.0;
  auto onStep = [&](const StepInfo &s) -> PetscErrorCode {
    PetscFunctionBeginUser;
    if (s.t >= next - 1e-9) {
      TrackedModes m;
      PetscCall(tracker.analyze(s.t, integrator.positions(), integrator.multipliers(), &m));
      out.insert(out.end(), m.frequencyHz.begin(), m.frequencyHz.end());
      for (const FollowedMode &f : m.followed) out.insert(out.end(), {f.hz, 1.0 + f.index});
      next += 0.1;
    }
    PetscFunctionReturn(0);
  };
  RunSummary summary;
  check(integrate(integrator, scene.dynamic, onStep, &summary));
  EXPECT_TRUE(summary.completed);
  return out;
}

} // namespace

TEST(RankIndependence, TrackedFrequenciesMatchSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  const std::vector<double> distributed = trackedAlongExtraction(PETSC_COMM_WORLD);
  const std::vector<double> alone = trackedAlongExtraction(PETSC_COMM_SELF);
  ASSERT_EQ(distributed.size(), alone.size());
  ASSERT_GE(alone.size(), 12u);
  double worst = 0;
  for (std::size_t i = 0; i < alone.size(); ++i) worst = std::max(worst, std::abs(distributed[i] - alone[i]) / alone[i]);
  PetscPrintf(PETSC_COMM_WORLD, "  tracked frequencies, %d ranks vs 1: %zu values, max relative difference %.3e\n", size,
              alone.size(), worst);
  EXPECT_LT(worst, 1e-8);
}

namespace {

// Tracking twice on the world communicator with `option` set (nullptr: the
// defaults) and once on each rank alone: the two distributed runs must agree
// bitwise, and with one rank to 1e-8.
void expectReproducibleTracking(const char *option, const char *label)
{
  if (option) PetscOptionsSetValue(nullptr, option, "1");
  const std::vector<double> first = trackedAlongExtraction(PETSC_COMM_WORLD);
  const std::vector<double> second = trackedAlongExtraction(PETSC_COMM_WORLD);
  if (option) PetscOptionsClearValue(nullptr, option);
  const std::vector<double> alone = trackedAlongExtraction(PETSC_COMM_SELF);
  ASSERT_EQ(first.size(), alone.size());
  ASSERT_EQ(second.size(), alone.size());
  ASSERT_GE(alone.size(), 12u);
  double worst = 0;
  for (std::size_t i = 0; i < alone.size(); ++i) {
    EXPECT_EQ(first[i], second[i]) << "value " << i;
    worst = std::max(worst, std::abs(first[i] - alone[i]) / alone[i]);
  }
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  PetscPrintf(PETSC_COMM_WORLD, "  tracked frequencies %s, %d ranks vs 1: max relative difference %.3e\n", label, size,
              worst);
  EXPECT_LT(worst, 1e-8);
}

} // namespace

// By default the eigen-analyses on several ranks factor the whole pencil on
// every rank with KLU (useRedundantDirectSolver): two runs give bitwise the
// same tracked frequencies (with MUMPS they differed in the last bits from
// run to run: its distributed factorization adds the ranks' contributions
// in the order its messages arrive), and they agree with one rank.
TEST(RankIndependence, TrackingIsReproducibleAndMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  expectReproducibleTracking(nullptr, "by default");
}

// With -boom_schur_dd the shift-and-invert solves go through the interface
// Schur complement instead (useAnalysisDirectSolver): reproducible too.
TEST(RankIndependence, SchurTrackingIsReproducibleAndMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  expectReproducibleTracking("-boom_schur_dd", "with -boom_schur_dd");
}

namespace {

struct EquilibriumAndModes {
  std::vector<double> state; // on rank 0 (gatherShape)
  std::vector<double> omega2;
};

// The static equilibrium of `scene` at t = 0 and its lowest modes there
// (like `analysis: modal`), on `comm`.
EquilibriumAndModes equilibriumAndModes(const Scene &scene, MPI_Comm comm)
{
  EquilibriumAndModes out;
  out.omega2 = modesAtStaticEquilibrium(scene, 4, comm, &out.state).omega2;
  return out;
}

} // namespace

// Statics and modal analyses on several ranks factor the whole matrix on
// every rank with KLU (NewtonSolver::setUp, useAnalysisDirectSolver): two
// runs agree bitwise. With MUMPS they did not: the static pre-solve of this
// scene (pads in contact, 221 unknowns) differed from run to run in the last
// bits (MUMPS adds the ranks' contributions in message-arrival order).
TEST(RankIndependence, StaticsAndModesAreReproducibleAndMatchSingleRank)
{
  PetscMPIInt size, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  const Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/paper_extraction_pads.yaml");
  const EquilibriumAndModes first = equilibriumAndModes(scene, PETSC_COMM_WORLD);
  const EquilibriumAndModes second = equilibriumAndModes(scene, PETSC_COMM_WORLD);
  const EquilibriumAndModes alone = equilibriumAndModes(scene, PETSC_COMM_SELF);
  ASSERT_EQ(first.omega2.size(), 4u);
  ASSERT_EQ(second.omega2.size(), 4u);
  ASSERT_EQ(alone.omega2.size(), 4u);
  double worstModes = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(first.omega2[k], second.omega2[k]) << "mode " << k;
    worstModes = std::max(worstModes, std::abs(first.omega2[k] - alone.omega2[k]) / alone.omega2[k]);
  }
  double worstState = 0, scale = 0;
  if (rank == 0) {
    ASSERT_EQ(first.state.size(), alone.state.size());
    ASSERT_EQ(second.state.size(), alone.state.size());
    for (std::size_t i = 0; i < alone.state.size(); ++i) {
      EXPECT_EQ(first.state[i], second.state[i]) << "unknown " << i;
      worstState = std::max(worstState, std::abs(first.state[i] - alone.state[i]));
      scale = std::max(scale, std::abs(alone.state[i]));
    }
  }
  PetscPrintf(PETSC_COMM_WORLD,
              "  pads scene statics and modes, %d ranks vs 1: state %.3e, omega^2 %.3e relative\n", size,
              worstState / std::max(scale, 1e-300), worstModes);
  EXPECT_LE(worstState, 1e-9 * scale);
  EXPECT_LT(worstModes, 1e-8);
}

// Work items distributed by a METIS partition of the item graph
// (-boom_partition metis) instead of by the owner of their first unknown:
// entries computed for other ranks' rows travel with the COO assembly and the
// reverse scatter; the answers are those of one rank.
TEST(RankIndependence, MetisItemPartitionMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  const Scene scene = shortenedExtraction(0.5);
  const DynamicHistory distributed = runDynamicWithOption(scene, PETSC_COMM_WORLD, "-boom_partition", "metis");
  const DynamicHistory alone = runDynamic(scene, PETSC_COMM_SELF);
  ASSERT_TRUE(distributed.summary.completed) << distributed.summary.failure;
  ASSERT_TRUE(alone.summary.completed) << alone.summary.failure;
  const double d = maxRelativeDifference(alone.finalState, distributed.finalState);
  PetscPrintf(PETSC_COMM_WORLD, "  extraction, METIS item partition on %d ranks vs 1: %.3e relative\n", size, d);
  EXPECT_LT(d, 1e-10);
}

// Damped modes (SLEPc PEP) of the damped scene above plus a spring-damper at
// the tip (non-proportional damping), linearized at the initial state, on
// the world communicator and on each rank alone.
namespace {

DampedModalResult dampedModesOn(const Scene &scene, MPI_Comm comm)
{
  Model model(scene);
  Assembler assembler(model);
  PetscHandle<Vec> q, lambda;
  check(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  check(assembler.setUp(comm));
  check(assembler.createVector(q.address()));
  check(assembler.createVector(lambda.address()));
  const std::vector<double> q0 = model.initialCoordinates();
  PetscInt lo, hi;
  check(VecGetOwnershipRange(q, &lo, &hi));
  for (PetscInt i = lo; i < std::min<PetscInt>(hi, model.numCoordinates()); ++i)
    check(VecSetValue(q, i, q0[i], INSERT_VALUES));
  check(VecAssemblyBegin(q));
  check(VecAssemblyEnd(q));
  DampedModalResult modes;
  check(solveDampedModes(assembler, 0.0, q, lambda, 5, &modes));
  return modes;
}

} // namespace

TEST(RankIndependence, DampedModesMatchSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  std::string text = kScene;
  // Light damping (a few % in the low modes), so that the low modes oscillate.
  addSectionKeys(text, "lower", ", eta_axial: 2.0e-5, eta_bending: 4.0e-5");
  addSectionKeys(text, "upper", ", damping_ratio: 0.02, damping_frequency: 30.0");
  text.insert(text.find("dynamic:"),
              "springs:\n  - {name: s, body: upper, at: 1.5, point: [3.5, -1.0], stiffness: 2.0e4, damping: 800}\n");
  const Scene scene = parseScene(text, "rank-independence-damped-modes.yaml");
  const DampedModalResult distributed = dampedModesOn(scene, PETSC_COMM_WORLD);
  const DampedModalResult alone = dampedModesOn(scene, PETSC_COMM_SELF);
  ASSERT_EQ(distributed.dampedOmega.size(), alone.dampedOmega.size());
  double worst = 0;
  for (std::size_t k = 0; k < alone.dampedOmega.size(); ++k) {
    worst = std::max(worst, std::abs(distributed.dampedOmega[k] - alone.dampedOmega[k]) / alone.dampedOmega[k]);
    worst = std::max(worst, std::abs(distributed.dampingRatio[k] - alone.dampingRatio[k]) / alone.dampingRatio[k]);
    PetscPrintf(PETSC_COMM_WORLD, "  damped mode %zu: omega_d %.10g vs %.10g rad/s, zeta %.10g vs %.10g\n", k + 1,
                distributed.dampedOmega[k], alone.dampedOmega[k], distributed.dampingRatio[k], alone.dampingRatio[k]);
  }
  PetscPrintf(PETSC_COMM_WORLD, "  damped modes, %d ranks vs 1: max relative difference %.3e\n", size, worst);
  EXPECT_LT(worst, 1e-10);
}

TEST(RankIndependence, PaddedJointsWithFrictionMatchSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  // A beam dropped into two compliant pads with clearance (one with LuGre
  // friction from the pad force), pulled along and lifted by a rising force:
  // contact, lift-off and the pad-driven friction on a distributed layout.
  const Scene scene = parseScene(R"(name: rank-independence-pads
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: rail, length: 2.0, elements: 6, section: {EA: 1.0e9, EI: 1.0e7, rhoA: 30}}
  - {name: slider, length: 1.0, elements: 4, origin: [0.5, 0], section: {EA: 1.0e9, EI: 1.0e6, rhoA: 50}}
constraints:
  - {type: clamp, body: rail, at: start}
  - type: sliding_joint
    name: A
    body: slider
    at: start
    track: rail
    pad: {stiffness: 1.0e8, clearance: 1.0e-3, damping: 5.0e4}
    friction: {mu_s: 0.15, mu_c: 0.1, v_s: 0.01, sigma0: 1.0e4, sigma1: 10}
  - {type: sliding_joint, name: B, body: slider, at: end, track: rail, pad: {stiffness: 1.0e8, clearance: 1.0e-3, damping: 5.0e4}}
loads:
  - {type: point_force, name: lift, body: slider, at: 0.75, force: [200, 1000], scale: {type: ramp, t0: 0.02, t1: 0.22, from: 0, to: 1}}
dynamic: {t_end: 0.12, dt: 1.0e-3, rho_inf: 0.8}
)",
                                 "rank-independence-pads.yaml");
  runOnAllRanksAndOne(scene, "pads");
}

// A spatial model (dimension 3): a tower welded to the ground, a boom on a
// hinge at its top slewed by an angle drive, a link on a spherical joint at
// the boom's tip with a mass of rotary inertia, fixed and follower loads:
// every spatial kind of work item, spread over both ranks.
TEST(RankIndependence, SpatialRunMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  const char *text = R"(
name: spatial-rank-independence
dimension: 3
analysis: dynamic
gravity: [0, 0, -9.81]
bodies:
  - {name: tower, type: rigid, length: 2.0, mass: 50, inertia: [1, 20, 20], axis: [0, 0, 1], up: [1, 0, 0]}
  - {name: boom, type: rigid, length: 4.0, origin: [0, 0, 2], mass: 100, inertia: [5, 130, 133], products: [0, 0.5, 0]}
  - {name: link, type: rigid, length: 1.0, origin: [4, 0, 2], axis: [0.3, 0.2, -1], mass: 10, inertia: [0.1, 1, 1]}
constraints:
  - {type: clamp, body: tower, at: start}
  - {type: revolute_joint, body: boom, at: start, other: tower, other_at: end, axis: [0, 0, 1]}
  - type: angle_drive
    body: boom
    at: start
    other: tower
    other_at: end
    axis: [0, 0, 1]
    angle: {type: accel_limited, t0: 0.02, from: 0, to: 20, speed: 40, accel: 400}
  - {type: spherical_joint, body: link, at: start, other: boom, other_at: end}
loads:
  - {type: point_force, body: link, at: end, force: [0, 200, 0]}
  - {type: point_force, body: link, at: 0.5, follower_force: [0, 0, -100]}
  - {type: point_moment, body: link, at: 0.5, follower_moment: [5, 0, 0]}
masses:
  - {body: link, at: end, mass: 20, inertia: [0.1, 0.2, 0.3]}
dynamic: {t_end: 0.2, dt: 1.0e-3, rho_inf: 0.8}
)";
  const Scene scene = parseScene(text, "spatial-rank-independence.yaml");
  runOnAllRanksAndOne(scene, "spatial");
}

// Spatial beams (dimension 3): a clamped box boom with Kelvin-Voigt damping,
// a second beam on a spherical joint at its tip, a side load, a torque and
// gravity: the spatial beam elements and joints on beam points, spread
// over both ranks.
TEST(RankIndependence, SpatialBeamRunMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  const char *text = R"(
name: spatial-beam-rank-independence
dimension: 3
analysis: dynamic
gravity: [0, 0, -9.81]
bodies:
  - name: boom
    type: ancf_beam
    length: 3.0
    elements: 8
    section: {E: 2.1e11, G: 8.1e10, rho: 7850, width: 0.15, height: 0.2, thickness: 0.006, eta_bending: 2.0e-4}
  - name: jib
    type: ancf_beam
    length: 1.0
    elements: 4
    origin: [3, 0, 0]
    axis: [0, 1, 1]
    section: {EA: 1.0e8, EI_y: 2.0e5, EI_z: 3.0e5, GJ: 1.0e5, rhoA: 20, rho_Ip: 0.05}
constraints:
  - {type: clamp, body: boom, at: start}
  - {type: spherical_joint, body: jib, at: start, other: boom, other_at: end}
loads:
  - {type: point_force, body: boom, at: end, force: [0, 2000, 0]}
  - {type: point_moment, body: boom, at: 1.5, moment: [1000, 0, 0]}
  - {type: point_force, body: jib, at: end, follower_force: [0, 0, -100]}
dynamic: {t_end: 0.05, dt: 1.0e-3, rho_inf: 0.8}
)";
  const Scene scene = parseScene(text, "spatial-beam-rank-independence.yaml");
  runOnAllRanksAndOne(scene, "spatial-beam");
}

// inputs/spatial_sleeve_incline.yaml: a locked rigid sleeve sliding down a
// luffed flexible box boom (spatial sliding joint) under a side load and a
// torque; its contact point changes element during the run.
TEST(RankIndependence, SpatialSlidingJointMatchesSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  const Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/spatial_sleeve_incline.yaml");
  const RankRuns r = runOnAllRanksAndOne(scene, "spatial sliding joint");
  if (!r.completed) return;
  EXPECT_GE(r.alone.patternVersion, 1); // the contact point changed element (once, at t = 0.213 s)
  EXPECT_EQ(r.distributed.patternVersion, r.alone.patternVersion);
}

// Cylindrical and prismatic joints (dimension 3): a carriage on a prismatic
// joint fixed in the tip section of a clamped spatial beam, moved along it
// by a slide drive, and an arm on a cylindrical joint at the carriage's end
// (free to slide and turn, its centre of mass off the axis), loaded: the
// offset, alignment and roll rows on beam and rigid ends, spread over both
// ranks, at rho_inf = 0.8 and 1.
TEST(RankIndependence, SpatialAxisJointsMatchSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.regression)";
  const char *text = R"(
name: spatial-axis-joints-rank-independence
dimension: 3
analysis: dynamic
gravity: [0, 0, -9.81]
bodies:
  - name: mast
    type: ancf_beam
    length: 2.0
    elements: 6
    axis: [0, 0, 1]
    section: {EA: 1.0e8, EI_y: 2.0e5, EI_z: 3.0e5, GJ: 1.0e5, rhoA: 20, rho_Ip: 0.05}
  - {name: carriage, type: rigid, length: 1.0, origin: [0, 0, 2], mass: 30, inertia: [0.5, 2, 2], axis: [1, 0, 0]}
  - {name: arm, type: rigid, length: 1.5, origin: [1, 0, 2], mass: 10, inertia: [0.1, 1, 1], center_of_mass: [0.75, 0.05, 0.02]}
constraints:
  - {type: clamp, body: mast, at: start}
  - type: prismatic_joint
    body: carriage
    at: start
    other: mast
    other_at: end
    axis: [1, 0, 0]
    slide: {type: accel_limited, t0: 0.01, from: 0, to: 0.2, speed: 2, accel: 40}
  - {type: cylindrical_joint, body: arm, at: start, other: carriage, other_at: end, axis: [1, 0.2, 0]}
loads:
  - {type: point_force, body: arm, at: end, force: [0, 300, -100]}
  - {type: point_moment, body: carriage, at: 0.5, follower_moment: [50, 0, 20]}
dynamic: {t_end: 0.1, dt: 1.0e-3, rho_inf: 0.8}
)";
  const Scene scene = parseScene(text, "spatial-axis-joints-rank-independence.yaml");
  runOnAllRanksAndOne(scene, "spatial-axis-joints");
  // At rho_inf = 1 spatial runs restart with consistent accelerations after
  // every step (docs/model.md §9.1): that solve on a distributed layout too.
  std::string undamped = text;
  undamped.replace(undamped.find("rho_inf: 0.8"), 12, "rho_inf: 1");
  runOnAllRanksAndOne(parseScene(undamped, "spatial-axis-joints-rho1.yaml"), "spatial-axis-joints at rho_inf = 1");
}
