// Statics of spatial scenes (dimension: 3) through the whole pipeline
// (scene -> model -> assembly -> StaticSolver with load steps), against
// closed forms derived here, and the rebasing of the spatial beam's node
// references (docs/model.md §1.7): a cantilever under small tip loads and a
// torque (linear beam theory), a rigid-body structure on joints (hand
// statics of the reactions), the dynamic start `initial: static` at rest,
// the roll-up under an end moment at M = pi EI/L and 2 pi EI/L (circular
// arcs; the tip turns by a half and a whole turn, which needs rebasing),
// objectivity of a static solution, rebasing as a change of chart that keeps
// the state, a restart across rebases and 1 rank = 2 ranks.
#include "support.hpp"

#include "boomdyn/spatial_ancf_beam.hpp"
#include "boomdyn/spatial_embedding.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <random>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

namespace sb = spatial_beam;
constexpr double kPi = 3.14159265358979323846;

std::string number(double x)
{
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

std::string vec(const Eigen::Vector3d &v)
{
  return "[" + number(v[0]) + ", " + number(v[1]) + ", " + number(v[2]) + "]";
}

// The final state of a run: coordinates and unscaled multipliers (every
// rank), and how many steps it took.
struct Final {
  std::vector<double> q, lambda;
  bool completed = false;
  int steps = 0;
  double energy = 0; // strain + potential (+ kinetic) at the end
};

class FinalRecorder : public Monitor {
public:
  explicit FinalRecorder(Final &out) : out_(out) {}
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override
  {
    PetscFunctionBeginUser;
    out_.q = gatherAll(s.q);
    out_.lambda = gatherAll(s.lambda);
    out_.completed = outcome.completed();
    out_.steps = outcome.steps;
    out_.energy = s.energy.strain + s.energy.potential + s.energy.kinetic;
    PetscFunctionReturn(0);
  }

private:
  Final &out_;
};

Final runScene(const std::string &text, MPI_Comm comm = PETSC_COMM_WORLD)
{
  const Scene scene = parseScene(text, "spatial-static.yaml");
  Final out;
  Simulation sim(scene, comm, testOptions());
  check(sim.setUp());
  sim.addMonitor(std::make_unique<FinalRecorder>(out));
  check(sim.run());
  return out;
}

int rowOf(const Model &m, const std::string &name)
{
  for (const ConstraintItem *c : m.constraints())
    if (c->name() == name) return static_cast<int>(c->firstRow());
  ADD_FAILURE() << "no constraint " << name;
  return 0;
}

// A clamped spatial cantilever (ancf_beam, clamp "root" at its start) in a
// static scene: the beam's placement, section and tip loads.
struct Cantilever {
  double L = 1.0;
  int elements = 8;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::UnitX(), up = Eigen::Vector3d::UnitY();
  std::string section = "EA: 1.0e4, EI_y: 1, EI_z: 1, GJ: 1, rhoA: 1, rho_Ip: 0.01";
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  int loadSteps = 1;
  std::string gravity = "[0, 0, 0]";

  std::string scene() const
  {
    std::string s = "name: spatial-cantilever\ndimension: 3\nanalysis: static\ngravity: " + gravity +
                    "\nbodies:\n  - {name: beam, type: ancf_beam, length: " + number(L) +
                    ", elements: " + std::to_string(elements) + ", origin: " + vec(origin) + ", axis: " + vec(axis) +
                    ", up: " + vec(up) + ", section: {" + section +
                    "}}\nconstraints:\n  - {type: clamp, name: root, body: beam, at: start}\n";
    if (force.norm() > 0 || moment.norm() > 0) s += "loads:\n";
    if (force.norm() > 0)
      s += "  - {type: point_force, name: tipforce, body: beam, at: end, force: " + vec(force) + "}\n";
    if (moment.norm() > 0)
      s += "  - {type: point_moment, name: tipmoment, body: beam, at: end, moment: " + vec(moment) + "}\n";
    return s + "static: {load_steps: " + std::to_string(loadSteps) + "}\n";
  }
};

Eigen::Vector3d node(const std::vector<double> &q, int n, int offset = 0)
{
  return Eigen::Vector3d(q[7 * n + offset], q[7 * n + offset + 1], q[7 * n + offset + 2]);
}

// Tip error / L of the roll-up (EI = 1, L = 1) under the moment phi EI/L
// about the unit axis m normal to the beam, with `steps` load steps.
double rollUpError(int elements, double phi, const Eigen::Vector3d &m, const std::string &section, int steps)
{
  Cantilever c;
  c.elements = elements;
  c.section = section;
  c.moment = phi * m;
  c.loadSteps = steps;
  const Final f = runScene(c.scene());
  EXPECT_TRUE(f.completed) << elements << " elements, phi " << phi;
  const Eigen::Vector3d across = m.cross(Eigen::Vector3d::UnitX());
  const Eigen::Vector3d exact = std::sin(phi) / phi * Eigen::Vector3d::UnitX() + (1 - std::cos(phi)) / phi * across;
  return (node(f.q, elements) - exact).norm();
}

void checkRollUp(const std::string &section, const Eigen::Vector3d &m, const char *what)
{
  for (double phi : {kPi, 2 * kPi}) {
    double previous = 0;
    for (int n : {4, 8, 16, 32}) {
      const double err = rollUpError(n, phi, m, section, 16);
      std::printf("scene roll-up %s, M L/EI = %.4f: %2d elements, tip error %.3e L", what, phi, n, err);
      if (previous > 0) std::printf(", rate %.2f", std::log2(previous / err));
      std::printf("\n");
      if (n == 16) EXPECT_LT(err, 1e-4) << what << " phi " << phi;
      if (previous > 0 && n <= 16) EXPECT_GT(std::log2(previous / err), 3.5) << what << " " << n << " elements";
      previous = err;
    }
  }
}

// A post clamped to the ground with a boom hinged at its top and held by an
// angle drive (RigidStructureOnJointsHasTheHandStaticsReactions).
std::string rigidStructure(const std::string &analysis, const std::string &settings)
{
  return "name: rigid-structure\ndimension: 3\nanalysis: " + analysis + "\ngravity: [0, 0, -9.81]\nbodies:\n"
         "  - {name: post, type: rigid, length: 2.0, mass: 50, inertia: [10, 10, 1], axis: [0, 0, 1], up: [1, 0, 0]}\n"
         "  - {name: boom, type: rigid, length: 3.0, mass: 100, inertia: [1, 80, 80], origin: [0, 0, 2], axis: [1, 0, "
         "0], up: [0, 1, 0]}\n"
         "constraints:\n"
         "  - {type: clamp, name: base, body: post, at: start}\n"
         "  - {type: revolute_joint, name: hinge, body: boom, at: start, other: post, other_at: end, axis: [0, 1, 0]}\n"
         "  - {type: angle_drive, name: luff, body: boom, at: start, other: post, other_at: end, axis: [0, 1, 0]}\n"
         "loads:\n  - {type: point_force, name: hook, body: boom, at: end, force: [0, 300, -1000]}\n" +
         settings + "\n";
}

} // namespace

// Linear cantilever statics (L = 2 m, EI_y = 2, EI_z = 1, GJ = 0.5 N m^2),
// one load per run: a tip force Py along y (bending about d3, EI_z), Pz
// along z (about d2, EI_y) or a torque T about the axis gives the tip
// deflection P L^3/(3 EI) and slope P L^2/(2 EI), or the twist T L/GJ,
// exact for the cubic element in linear theory. The loads turn the
// sections by ~1e-5 rad, so geometric nonlinearity changes each response
// by ~1e-10 relative (loads together would couple at first order in the
// rotations: a torque turned by the bending slope, ~1e-6). The clamp's
// force rows carry the applied force (C = r(0) - p: lambda = the force the
// clamp takes from the beam).
TEST(SpatialStatics, CantileverUnderSmallTipLoadsAndTorqueMatchesLinearTheory)
{
  const double EIy = 2, EIz = 1, GJ = 0.5, L = 2.0, P = 2e-6, T = 2e-6;
  for (int k = 0; k < 3; ++k) {
    Cantilever c;
    c.L = L;
    c.section = "EA: 1.0e6, EI_y: 2, EI_z: 1, GJ: 0.5, rhoA: 1, rho_Ip: 0.01";
    if (k < 2) c.force[1 + k] = P;
    else c.moment[0] = T;
    c.loadSteps = 2;
    const Scene scene = parseScene(c.scene(), "cantilever.yaml");
    Final f;
    Simulation sim(scene, PETSC_COMM_WORLD, testOptions());
    check(sim.setUp());
    sim.addMonitor(std::make_unique<FinalRecorder>(f));
    check(sim.run());
    ASSERT_TRUE(f.completed);
    const int tip = c.elements;
    const Eigen::Vector3d r = node(f.q, tip), slope = node(f.q, tip, 3);
    const double twist = f.q[7 * tip + 6];
    if (k < 2) {
      const double EI = k == 0 ? EIz : EIy, deflection = P * L * L * L / (3 * EI), angle = P * L * L / (2 * EI);
      const int c1 = 1 + k, c2 = 2 - k; // loaded and other lateral direction
      std::printf("linear cantilever, tip force along %c: deflection %.12e (exact %.12e), slope %.12e (%.12e)\n",
                  "yz"[k], r[c1], deflection, slope[c1] / slope[0], angle);
      EXPECT_NEAR(r[c1], deflection, 1e-8 * deflection);
      EXPECT_NEAR(slope[c1] / slope[0], angle, 1e-8 * angle);
      EXPECT_LT(std::abs(r[c2]) + std::abs(twist), 1e-12 * deflection); // no coupling
    } else {
      std::printf("linear cantilever, tip torque: twist %.12e (exact %.12e)\n", twist, T * L / GJ);
      EXPECT_NEAR(twist, T * L / GJ, 1e-8 * T * L / GJ);
      EXPECT_LT(std::abs(r[1]) + std::abs(r[2]), 1e-12 * T * L / GJ);
    }
    // Reaction force of the clamp (its first three rows).
    const int root = rowOf(sim.model(), "root");
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(f.lambda[root + d], c.force[d], 1e-9 * P) << "row " << d;
  }
}

// A rigid structure on joints with hand statics: a post (50 kg, 2 m along
// z) clamped to the ground, a boom (100 kg, 3 m along x, centre of mass at
// its middle) hinged at the post's top about y and held horizontal by an
// angle drive about the same axis, a force F = (0, 300, -1000) N at the
// boom's end, gravity 9.81 m/s^2 along -z. Rows C = r_a - r_b (a: the
// body named first), so the multipliers are the forces the joints take:
// the hinge takes the boom's load m_b g + F, the clamp all of it,
// (m_p + m_b) g + F; the drive's torque about y is
// m_b g L/2 + |F_z| L = 4471.5 N m. The Euler parameters stay unit. R(p)
// is quadratic in p, so the forces on a body do work on a uniform scaling
// of p: p . Q_p = 2 sum_j rho_j . F_j (rho_j: the lever arm from the centre
// of mass to where force F_j acts), and the normalization row (2p) takes
// it, lambda_n = -sum_j rho_j . F_j. The post: the clamp's force at
// rho = -1 m e_z, the boom's at +1 m e_z: |lambda_n| = 2471.5 + 1981 =
// 4452.5 N m; the boom: every force normal to its lever arm, 0.
TEST(SpatialStatics, RigidStructureOnJointsHasTheHandStaticsReactions)
{
  const std::string text = rigidStructure("static", "static: {load_steps: 2}");
  const Scene scene = parseScene(text, "rigid-structure.yaml");
  Final f;
  Simulation sim(scene, PETSC_COMM_WORLD, testOptions());
  check(sim.setUp());
  sim.addMonitor(std::make_unique<FinalRecorder>(f));
  check(sim.run());
  ASSERT_TRUE(f.completed);
  const double g = 9.81, mp = 50, mb = 100, L = 3;
  const Eigen::Vector3d F(0, 300, -1000), boomLoad = F + Eigen::Vector3d(0, 0, -mb * g),
                        allLoad = boomLoad + Eigen::Vector3d(0, 0, -mp * g);
  const Model &m = sim.model();
  const int base = rowOf(m, "base"), hinge = rowOf(m, "hinge"), luff = rowOf(m, "luff");
  const double scale = allLoad.norm();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(f.lambda[hinge + k], boomLoad[k], 1e-9 * scale) << "hinge row " << k;
    EXPECT_NEAR(f.lambda[base + k], allLoad[k], 1e-9 * scale) << "base row " << k;
  }
  const double torque = mb * g * L / 2 + 1000 * L;
  EXPECT_NEAR(std::abs(f.lambda[luff]), torque, 1e-9 * torque);
  std::printf("rigid structure: hinge force (%.6f, %.6f, %.6f) N, base (%.6f, %.6f, %.6f) N, drive %.6f N m "
              "(hand: %.6f)\n",
              f.lambda[hinge], f.lambda[hinge + 1], f.lambda[hinge + 2], f.lambda[base], f.lambda[base + 1],
              f.lambda[base + 2], f.lambda[luff], torque);
  // The structure does not move; the Euler parameters stay unit, their rows idle.
  for (int b = 0; b < 2; ++b) {
    const double *q = f.q.data() + 7 * b;
    EXPECT_NEAR(Eigen::Vector4d(q[3], q[4], q[5], q[6]).norm(), 1.0, 1e-14) << "body " << b;
  }
  EXPECT_NEAR(f.q[7 + 0], 1.5, 1e-12); // the boom's centre of mass stays at (1.5, 0, 2)
  EXPECT_NEAR(f.q[7 + 2], 2.0, 1e-12);
  const double postVirial = f.lambda[rowOf(m, "post.euler")], boomVirial = f.lambda[rowOf(m, "boom.euler")];
  std::printf("normalization multipliers: post %.6f N m (hand: -4452.5), boom %.3e\n", postVirial, boomVirial);
  EXPECT_NEAR(postVirial, -(2471.5 + 1981.0), 1e-9 * torque);
  EXPECT_LT(std::abs(boomVirial), 1e-9 * torque);
}

// A dynamic run that starts from static equilibrium (initial: static)
// begins at rest: a spatial cantilever under its own weight, a tip load in
// both lateral directions and a torque, and the rigid structure above
// (Euler parameters with their normalization rows and the inertia's
// regularizing term). The accelerations at the start and the velocities
// and displacements over the run stay at the static solve's tolerance:
// Newton leaves a residual of ~1e-10 of the load, which the smallest mass
// (the twist's rotary inertia rho_Ip l/3 ~ 1e-3 of rhoA L) turns into
// accelerations of ~1e-7 g; bounds 1e-6 g, g t and g t^2.
class RestRecorder : public Monitor {
public:
  explicit RestRecorder(Simulation &sim) : sim_(sim) {}
  PetscErrorCode start(const RunState &s, bool) override
  {
    PetscFunctionBeginUser;
    q0 = gatherAll(s.q);
    const std::vector<double> a = gatherAll(sim_.integrator()->accelerations());
    for (int i = 0; i < sim_.model().numCoordinates(); ++i) acceleration = std::max(acceleration, std::abs(a[i]));
    PetscFunctionReturn(0);
  }
  PetscErrorCode afterStep(const RunState &s, std::string *) override
  {
    PetscFunctionBeginUser;
    const std::vector<double> q = gatherAll(s.q), v = gatherAll(s.v);
    for (int i = 0; i < sim_.model().numCoordinates(); ++i) {
      moved = std::max(moved, std::abs(q[i] - q0[i]));
      velocity = std::max(velocity, std::abs(v[i]));
    }
    ++steps;
    PetscFunctionReturn(0);
  }
  std::vector<double> q0;
  double acceleration = 0, velocity = 0, moved = 0;
  int steps = 0;

private:
  Simulation &sim_;
};

TEST(SpatialStatics, DynamicStartFromStaticEquilibriumIsAtRest)
{
  Cantilever c;
  c.section = "EA: 1.0e4, EI_y: 2, EI_z: 1, GJ: 0.5, rhoA: 1, rho_Ip: 0.02";
  c.force = Eigen::Vector3d(0, 0.2, -0.3);
  c.moment = Eigen::Vector3d(0.1, 0, 0);
  c.gravity = "[0, 0, -1]";
  std::string beam = c.scene();
  beam.replace(beam.find("analysis: static"), 16, "analysis: dynamic");
  beam.replace(beam.find("static: {load_steps: 1}"), 23, "dynamic: {t_end: 0.2, dt: 0.01, initial: static}");
  const std::string rigid = rigidStructure("dynamic", "dynamic: {t_end: 0.02, dt: 1.0e-3, initial: static}");
  for (const std::string &text : {beam, rigid}) {
    const Scene scene = parseScene(text, "static-start.yaml");
    Simulation sim(scene, PETSC_COMM_WORLD, testOptions());
    check(sim.setUp());
    auto owned = std::make_unique<RestRecorder>(sim);
    RestRecorder &rest = *owned;
    sim.addMonitor(std::move(owned));
    check(sim.run());
    ASSERT_TRUE(sim.summary().completed) << sim.summary().failure;
    const double g = scene.name == "rigid-structure" ? 9.81 : 1.0, t = scene.dynamic.t_end;
    std::printf("%s from static equilibrium: start acceleration %.3e, velocity %.3e, displacement %.3e over %d "
                "steps\n",
                scene.name.c_str(), rest.acceleration, rest.velocity, rest.moved, rest.steps);
    EXPECT_GT(rest.steps, 10);
    EXPECT_LT(rest.acceleration, 1e-6 * g) << scene.name;
    EXPECT_LT(rest.velocity, 1e-6 * g * t) << scene.name;
    EXPECT_LT(rest.moved, 1e-6 * g * t * t) << scene.name;
  }
}

// Roll-up through static scenes (16 load steps): a cantilever (L = 1 m,
// EI = 1 N m^2, EA = 1e4 N) under an end moment M fixed in space bends into
// a circular arc of radius EI/M (pure bending: no axial force, so the exact
// arc holds for the extensible beam too); tip at L sin(phi)/phi along the
// beam and L (1 - cos phi)/phi across it, phi = M L/EI. At phi = pi the tip
// has turned by half a turn, at 2 pi by a whole one: beyond the chart of
// the initial references, so the beam rebases (every 120 degrees of turn).
// Tip error within 1e-4 L at 16 elements, convergence rate > 3.5 up to 16
// elements (below 32 the error meets the Newton tolerance). About a
// principal axis of a section with EI_y = 2 EI_z, and about the axis at 45
// degrees between the principal axes of a section with EI_y = EI_z.
TEST(SpatialStatics, RollUpUnderEndMomentIsACircularArc)
{
  checkRollUp("EA: 1.0e4, EI_y: 2, EI_z: 1, GJ: 1, rhoA: 1, rho_Ip: 0.01", Eigen::Vector3d::UnitZ(), "about d3");
  checkRollUp("EA: 1.0e4, EI_y: 1, EI_z: 0.5, GJ: 1, rhoA: 1, rho_Ip: 0.01", Eigen::Vector3d::UnitY(), "about d2");
  checkRollUp("EA: 1.0e4, EI_y: 1, EI_z: 1, GJ: 1, rhoA: 1, rho_Ip: 0.01", Eigen::Vector3d(0, 1, 1).normalized(),
              "about 45 deg");
}

// Objectivity through scenes: the same cantilever (8 elements), clamp and
// tip loads (a moment with components about both principal axes and along
// the beam, and a force) rotated as a whole by 2.3 rad about an arbitrary
// axis through the global origin (origin, axis, up, force and moment
// rotated) ends in the rotated equilibrium: every node's position and slope
// rotated, the same twists (the references turn with the problem), to 1e-10.
// The tip turns by about two radians: both runs rebase on the way.
TEST(SpatialStatics, RotatedSceneHasTheRotatedSolution)
{
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2.3, Eigen::Vector3d(0.3, -0.8, 0.5).normalized()).toRotationMatrix();
  Cantilever a;
  a.L = 2.0;
  a.section = "EA: 1.0e4, EI_y: 2, EI_z: 1, GJ: 0.5, rhoA: 1, rho_Ip: 0.01";
  a.origin = Eigen::Vector3d(0.5, -1.0, 2.0);
  a.moment = Eigen::Vector3d(0.4 * 0.5, 1.1 * 2, 2.0 * 1) / a.L;
  a.force = Eigen::Vector3d(-0.2, 0.3, 0.4);
  a.loadSteps = 8;
  Cantilever b = a;
  b.origin = R * a.origin, b.axis = R * a.axis, b.up = R * a.up, b.moment = R * a.moment, b.force = R * a.force;
  const Final fa = runScene(a.scene()), fb = runScene(b.scene());
  ASSERT_TRUE(fa.completed);
  ASSERT_TRUE(fb.completed);
  double position = 0, slope = 0, twist = 0, maxTwist = 0, turn = 0;
  for (int n = 0; n <= a.elements; ++n) {
    position = std::max(position, (node(fb.q, n) - R * node(fa.q, n)).norm() / a.L);
    slope = std::max(slope, (node(fb.q, n, 3) - R * node(fa.q, n, 3)).norm());
    twist = std::max(twist, std::abs(fb.q[7 * n + 6] - fa.q[7 * n + 6]));
    maxTwist = std::max(maxTwist, std::abs(fa.q[7 * n + 6]));
  }
  turn = std::acos(node(fa.q, a.elements, 3).normalized().dot(a.axis));
  std::printf("rotated scene: positions %.2e L, slopes %.2e, twists %.2e rad; tip turned %.3f rad, largest twist "
              "%.3f rad\n",
              position, slope, twist, turn, maxTwist);
  EXPECT_LT(position, 1e-10);
  EXPECT_LT(slope, 1e-10);
  EXPECT_LT(twist, 1e-10);
  EXPECT_GT(turn, 1.5);      // far enough to rebase
  EXPECT_GT(maxTwist, 0.05); // the torque does twist the beam
}

// Rebasing is a change of chart, not of state (docs/model.md §1.7): at the
// equilibrium of the half-turn roll-up (8 elements) and at a perturbed,
// twisted state, rebasing every node's reference onto its current zero-twist
// triad leaves the strain energy, every section's position and triad and
// (at equilibrium) the residual of the free coordinates as they were, to
// round-off.
TEST(SpatialStatics, RebasingKeepsStrainEnergyTriadsAndResidual)
{
  Cantilever c;
  c.moment = Eigen::Vector3d(0, 0, kPi);
  c.loadSteps = 16;
  const Scene scene = parseScene(c.scene(), "roll-up.yaml");
  Final f;
  Simulation sim(scene, PETSC_COMM_WORLD, testOptions());
  check(sim.setUp());
  sim.addMonitor(std::make_unique<FinalRecorder>(f));
  check(sim.run());
  ASSERT_TRUE(f.completed);
  const auto *solved = dynamic_cast<const SpatialAncfBeam *>(sim.model().bodies()[0].get());
  ASSERT_NE(solved, nullptr);
  const int n = c.elements;
  SpatialAncfBeam beam("copy", c.L, n, solved->section(), Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), 0);
  beam.setReferences(solved->references().data());

  // Strain energy, the sections' frames at a few points per element, and the
  // residual f - Q of the free coordinates (nodes 1..n).
  struct Look {
    double energy = 0;
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Matrix3d> triads;
    Eigen::VectorXd residual;
  };
  auto look = [&](const std::vector<double> &q) {
    Look l;
    l.residual = Eigen::VectorXd::Zero(7 * (n + 1));
    for (int e = 0; e < n; ++e) {
      const sb::Vec14 x = Eigen::Map<const sb::Vec14>(q.data() + 7 * e);
      const sb::Geometry geo = beam.geometry(e);
      l.energy += sb::strainEnergy(beam.section(), geo, x);
      sb::Vec14 fe;
      sb::internalForce(beam.section(), geo, x, fe, nullptr);
      l.residual.segment<14>(7 * e) += fe;
      for (double xi : {0.0, 0.3, 0.7, 1.0}) {
        const sb::SectionFrame fr = sb::sectionFrame(geo, x, xi);
        l.points.push_back(fr.r);
        l.triads.push_back(fr.d);
      }
      if (e == n - 1) {
        sb::Vec14 Q;
        sb::sectionMomentForce(geo, x, 1.0, c.moment, Q, nullptr);
        l.residual.segment<14>(7 * e) -= Q;
      }
    }
    l.residual = l.residual.tail(7 * n).eval();
    return l;
  };
  auto slopes = [&](const std::vector<double> &q) {
    std::vector<double> s;
    for (int a = 0; a <= n; ++a) s.insert(s.end(), q.begin() + 7 * a + 3, q.begin() + 7 * a + 6);
    return s;
  };
  auto compare = [&](const Look &x, const Look &y, const char *what) {
    double point = 0, triad = 0;
    for (std::size_t k = 0; k < x.points.size(); ++k) {
      point = std::max(point, (x.points[k] - y.points[k]).norm());
      triad = std::max(triad, (x.triads[k] - y.triads[k]).norm());
    }
    const double energy = std::abs(x.energy - y.energy) / x.energy;
    std::printf("rebasing at %s: energy %.2e relative, positions %.2e, triads %.2e, |residual| %.2e before, %.2e "
                "after, change %.2e\n",
                what, energy, point, triad, x.residual.norm(), y.residual.norm(), (x.residual - y.residual).norm());
    EXPECT_LT(energy, 1e-13) << what;
    EXPECT_LT(point, 1e-15) << what; // the centreline does not depend on the references at all
    EXPECT_LT(triad, 1e-13) << what;
  };

  // At the equilibrium (the tip turned by half a turn).
  const std::vector<double> q(f.q.begin(), f.q.begin() + 7 * (n + 1));
  const std::vector<double> references = beam.references();
  const Look before = look(q);
  ASSERT_TRUE(beam.rebase(slopes(q).data(), true));
  const Look after = look(q);
  compare(before, after, "the half-turn equilibrium");
  const double scale = std::abs(c.moment[2]); // the residual's force scale (EI/L^2 = M/pi)
  EXPECT_LT(before.residual.norm(), 1e-8 * scale);
  EXPECT_LT(after.residual.norm(), 1e-8 * scale);
  EXPECT_LT((after.residual - before.residual).norm(), 1e-8 * scale);

  // At a perturbed, twisted state (no equilibrium) from the same references.
  beam.setReferences(references.data());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  std::vector<double> p = q;
  for (int a = 1; a <= n; ++a) {
    for (int k = 0; k < 6; ++k) p[7 * a + k] += u(rng);
    p[7 * a + 6] += 10 * u(rng);
  }
  const Look perturbed = look(p);
  ASSERT_TRUE(beam.rebase(slopes(p).data(), true));
  compare(perturbed, look(p), "a perturbed state");
}

namespace {

// A dynamic roll-up (8 elements, L = 1 m, EI = 1 N m^2): the end moment
// 2 pi EI/L rises smoothly over 1 s and Kelvin-Voigt damping slows the
// beam; the tip turns by about a whole turn, so the beam rebases its
// references (at 120 degrees) several times during the run.
std::string dynamicRollUp()
{
  return "name: dynamic-roll-up\ndimension: 3\nanalysis: dynamic\ngravity: [0, 0, 0]\nbodies:\n"
         "  - {name: beam, type: ancf_beam, length: 1.0, elements: 8, section: {EA: 1.0e4, EI_y: 1, EI_z: 1, GJ: 1, "
         "rhoA: 1, rho_Ip: 0.01, eta_bending: 0.3, eta_axial: 0.3, eta_torsion: 0.3}}\n"
         "constraints:\n  - {type: clamp, body: beam, at: start}\n"
         "loads:\n  - {type: point_moment, body: beam, at: end, moment: [0, 0.3, " +
         number(2 * kPi) + "], scale: {type: smooth_step, t0: 0, t1: 1, from: 0, to: 1}}\n"
         "dynamic: {t_end: 1.2, dt: 0.02, rho_inf: 0.8}\n";
}

// Writes a checkpoint after step `at`, counts the rebasing (references
// that changed from one step to the next).
class RebaseCounter : public Monitor {
public:
  RebaseCounter(const Simulation &sim, int at, std::string path) : sim_(sim), at_(at), path_(std::move(path)) {}
  PetscErrorCode start(const RunState &, bool) override
  {
    last_ = beam().references();
    return 0;
  }
  PetscErrorCode afterStep(const RunState &s, std::string *) override
  {
    PetscFunctionBeginUser;
    const std::vector<double> now = beam().references();
    if (now != last_) ++rebases, last_ = now, steps.push_back(s.step);
    if (at_ && s.step == at_) {
      PetscCall(sim_.writeCheckpoint(path_));
      rebasesAtCheckpoint = rebases;
    }
    PetscFunctionReturn(0);
  }
  const SpatialAncfBeam &beam() const { return dynamic_cast<const SpatialAncfBeam &>(*sim_.model().bodies()[0]); }
  int rebases = 0, rebasesAtCheckpoint = 0;
  std::vector<int> steps; // at which the beam rebased

private:
  const Simulation &sim_;
  int at_;
  std::string path_;
  std::vector<double> last_;
};

} // namespace

// A restart across rebases continues bit for bit: the checkpoint holds the
// node references (hook_states), without which the same coordinates would
// mean other section triads. The run to t_end against a stop between the
// first and the last rebase
// (after some rebases, with more to come) and a restart: the same final
// positions, velocities and references, bitwise (one rank; full Newton).
TEST(SpatialStatics, RestartAcrossRebasesContinuesBitwise)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size > 1) GTEST_SKIP() << "bitwise restart holds on one rank";
  PetscOptionsSetValue(nullptr, "-boom_jacobian_reuse", "0");
  const Scene scene = parseScene(dynamicRollUp(), "dynamic-roll-up.yaml");
  const std::string path = std::string(BOOMDYN_BINARY_DIR) + "/test_output/spatial_rebase_restart.chk.h5";
  std::remove(path.c_str());
  // A first run finds the steps that rebase; the checkpoint goes between
  // the first and the last of them.
  int at = 0;
  {
    Simulation probe(scene, PETSC_COMM_WORLD, testOptions());
    check(probe.setUp());
    auto owned = std::make_unique<RebaseCounter>(probe, 0, "");
    RebaseCounter &c = *owned;
    probe.addMonitor(std::move(owned));
    check(probe.run());
    ASSERT_GE(c.steps.size(), 2u) << "the run must rebase twice";
    at = (c.steps.front() + c.steps.back()) / 2;
  }
  Simulation full(scene, PETSC_COMM_WORLD, testOptions());
  check(full.setUp());
  auto counter = std::make_unique<RebaseCounter>(full, at, path);
  RebaseCounter &fullCount = *counter;
  full.addMonitor(std::move(counter));
  check(full.run());
  ASSERT_TRUE(full.summary().completed) << full.summary().failure;

  SimulationOptions options = testOptions();
  options.restartPath = path;
  Simulation restarted(scene, PETSC_COMM_WORLD, options);
  check(restarted.setUp());
  auto second = std::make_unique<RebaseCounter>(restarted, 0, "");
  RebaseCounter &restartCount = *second;
  restarted.addMonitor(std::move(second));
  check(restarted.run());
  ASSERT_TRUE(restarted.summary().completed) << restarted.summary().failure;
  PetscOptionsClearValue(nullptr, "-boom_jacobian_reuse");
  std::printf("dynamic roll-up: %d rebases in the run, %d before the checkpoint at step %d, %d after the restart\n",
              fullCount.rebases, fullCount.rebasesAtCheckpoint, at, restartCount.rebases);
  EXPECT_GE(fullCount.rebasesAtCheckpoint, 1);
  EXPECT_GE(fullCount.rebases - fullCount.rebasesAtCheckpoint, 1);
  EXPECT_EQ(restartCount.rebases, fullCount.rebases - fullCount.rebasesAtCheckpoint);
  EXPECT_EQ(gatherAll(full.integrator()->positions()), gatherAll(restarted.integrator()->positions()));
  EXPECT_EQ(gatherAll(full.integrator()->velocities()), gatherAll(restarted.integrator()->velocities()));
  EXPECT_EQ(fullCount.beam().references(), restartCount.beam().references());
}

// 1 rank = 2 ranks with rebasing: the dynamic roll-up and the static
// half-turn roll-up on PETSC_COMM_SELF and on two ranks take the same
// rebasing decisions (from the slopes every rank receives) and end in the
// same state to 1e-10. Runs under mpiexec -n 2 (CTest: mpi2.verification).
TEST(SpatialStatics, RebasingRunsMatchSingleRank)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size == 1) GTEST_SKIP() << "run under mpiexec -n 2 (CTest: mpi2.verification)";
  Cantilever c;
  c.elements = 16;
  c.moment = Eigen::Vector3d(0, 0.5, 2 * kPi);
  c.loadSteps = 16;
  for (const std::string &text : {c.scene(), dynamicRollUp()}) {
    const Final alone = runScene(text, PETSC_COMM_SELF), both = runScene(text, PETSC_COMM_WORLD);
    ASSERT_TRUE(alone.completed);
    ASSERT_TRUE(both.completed);
    ASSERT_EQ(alone.q.size(), both.q.size());
    const double d = maxRelativeDifference(alone.q, both.q);
    std::printf("1 rank against 2: largest difference %.2e relative\n", d);
    EXPECT_LT(d, 1e-10);
  }
}

// The example scene inputs/spatial_roll_up.yaml (3 m box boom, 16
// elements, end moment 2 pi EI_z/L in 16 load steps): after each load step
// the tip lies on the arc of radius EI_z/(f M); at f = 0.5 (half circle) and
// f = 1 (full circle, tip back at the clamp) within 1e-4 L.
class LoadStepTips : public Monitor {
public:
  explicit LoadStepTips(int tip) : tip_(tip) {}
  PetscErrorCode afterStep(const RunState &s, std::string *) override
  {
    PetscFunctionBeginUser;
    const std::vector<double> q = gatherAll(s.q);
    factors.push_back(s.t);
    tips.push_back(node(q, tip_));
    PetscFunctionReturn(0);
  }
  std::vector<double> factors;
  std::vector<Eigen::Vector3d> tips;

private:
  int tip_;
};

TEST(SpatialStatics, RollUpExampleSceneFollowsTheArcs)
{
  const Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/spatial_roll_up.yaml");
  Simulation sim(scene, PETSC_COMM_WORLD, testOptions());
  check(sim.setUp());
  auto owned = std::make_unique<LoadStepTips>(16);
  LoadStepTips &tips = *owned;
  sim.addMonitor(std::move(owned));
  check(sim.run());
  ASSERT_TRUE(sim.outcome().completed()) << sim.outcome().status;
  ASSERT_EQ(tips.factors.size(), 16u);
  const double L = 3.0;
  double worst = 0;
  for (std::size_t k = 0; k < tips.factors.size(); ++k) {
    const double phi = 2 * kPi * tips.factors[k];
    const Eigen::Vector3d exact(L * std::sin(phi) / phi, L * (1 - std::cos(phi)) / phi, 0);
    const double err = (tips.tips[k] - exact).norm() / L;
    worst = std::max(worst, err);
    if (k == 7 || k == 15)
      std::printf("example roll-up at f = %.4f: tip (%.6f, %.6f, %.2e) m, exact (%.6f, %.6f, 0), error %.2e L\n",
                  tips.factors[k], tips.tips[k][0], tips.tips[k][1], tips.tips[k][2], exact[0], exact[1], err);
  }
  EXPECT_LT(worst, 1e-4);
}

// A planar static scene run as a spatial model in its plane
// (spatialEmbedding, what -boom_spatial does): the cantilever of
// inputs/cantilever_static.yaml (2 m steel box, 16 elements) under its own
// weight and a tip load raised to P L^2/EI = 5 (the tip turns by about 70
// degrees) in 10 load steps: every node's position and slope equal the
// planar run's to 1e-8 relative, and the out-of-plane coordinates (z, z',
// twist) stay zero.
TEST(SpatialStatics, PlanarStaticSceneRunAsSpatialModelInItsPlane)
{
  const char *text = R"(
name: planar-static-cantilever
analysis: static
gravity: [0, -9.81]
bodies:
  - {name: boom, length: 2.0, elements: 16, section: {E: 2.1e11, rho: 7850, A: 4.056e-3, I: 2.3586272e-5}}
constraints:
  - {type: clamp, name: base, body: boom, at: start}
loads:
  - {type: point_force, name: tip, body: boom, at: end, force: [0, -6.19e6]}
static: {load_steps: 10}
)";
  const Scene planar = parseScene(text, "planar-static.yaml");
  const Scene spatial = spatialEmbedding(planar);
  Final a, b;
  for (int k = 0; k < 2; ++k) {
    Simulation sim(k == 0 ? planar : spatial, PETSC_COMM_WORLD, testOptions());
    check(sim.setUp());
    sim.addMonitor(std::make_unique<FinalRecorder>(k == 0 ? a : b));
    check(sim.run());
  }
  ASSERT_TRUE(a.completed);
  ASSERT_TRUE(b.completed);
  double difference = 0, size = 0, outOfPlane = 0;
  for (int n = 0; n <= 16; ++n) {
    const double *p = a.q.data() + 4 * n, *s = b.q.data() + 7 * n;
    for (int c = 0; c < 2; ++c) {
      difference = std::max({difference, std::abs(s[c] - p[c]), std::abs(s[3 + c] - p[2 + c])});
      size = std::max({size, std::abs(p[c]), std::abs(p[2 + c])});
    }
    outOfPlane = std::max({outOfPlane, std::abs(s[2]), std::abs(s[5]), std::abs(s[6])});
  }
  const double turn = std::atan2(-a.q[4 * 16 + 3], a.q[4 * 16 + 2]);
  std::printf("planar static scene in its plane: positions and slopes %.3e relative, out of plane %.3e, tip turned "
              "%.3f rad\n",
              difference / size, outOfPlane, turn);
  EXPECT_LT(difference / size, 1e-8);
  EXPECT_LT(outOfPlane, 1e-12);
  EXPECT_GT(turn, 1.0);
}
