// The spatial sliding joint (type sliding_joint, dimension: 3) through the
// model and the solvers, against hand statics and closed forms:
//  - a rigid sleeve locked on the middle of a straight beam clamped at both
//    ends, loaded by a force in either lateral direction, a torque about
//    the axis or a couple about either lateral axis: the joint's reactions
//    (force_2, force_3, torque, moment_2, moment_3; the others zero) are
//    minus the loads on the sleeve, and the
//    twist under the torque is T L / (4 GJ) (statics by the model's own
//    StaticSolver on the assembled model: analysis: static is not yet open
//    to spatial scenes);
//  - a sleeve sliding without friction down a stiff inclined beam under
//    gravity: s(t) = s0 - g sin(alpha) t^2 / 2 across element boundaries,
//    and the normal reaction m g cos(alpha);
//  - a planar sliding-joint scene run as a spatial model (-boom_spatial)
//    equals the planar run.
#include "support.hpp"

#include "boomdyn/spatial_embedding.hpp"
#include "boomdyn/static_solver.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string number(double x)
{
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// The value of output channel (group sliding_joint, quantity) from the
// multipliers (full layout of x, unscaled) or the state.
// A padded direction's force is a state channel (at q, v = 0).
double channel(const Model &model, const std::string &quantity, const std::vector<double> &lambda,
               const std::vector<double> &q = {})
{
  for (const OutputChannel &c : model.outputChannels()) {
    if (c.group != "sliding_joint" || c.quantity != quantity) continue;
    if (!c.fromState()) return c.factor * lambda.at(static_cast<std::size_t>(model.numCoordinates() + c.index));
    std::vector<double> qw, vw(c.watched.size(), 0.0);
    for (PetscInt i : c.watched) qw.push_back(q.at(static_cast<std::size_t>(i)));
    return c.evaluate(0.0, qw.data(), vw.data());
  }
  ADD_FAILURE() << "no output channel sliding_joint/" << quantity;
  return std::nan("");
}

struct StaticSleeve {
  bool converged = false;
  std::vector<double> q, lambda;
  double force1 = 0, force2 = 0, force3 = 0, moment2 = 0, moment3 = 0, torque = 0;
};

// Track: 1 m, 4 elements, clamped at both ends, section axes d2 = y, d3 = z;
// a rigid sleeve whose joint point sits at s = 0.5 (a node), rotation
// locked, its contact coordinate held by an extraction drive (the sliding
// direction has no stiffness in statics). Loads on the sleeve at its joint point.
StaticSleeve solveSleeve(const std::string &loads, const std::string &jointKeys = "", const std::string &gravity = "0")
{
  const std::string text = R"(
name: sleeve-statics
dimension: 3
analysis: dynamic
gravity: [0, 0, )" + gravity + R"(]
bodies:
  - {name: track, type: ancf_beam, length: 1.0, elements: 4,
     section: {EA: 1.0e4, EI_y: 1.0, EI_z: 2.0, GJ: 0.5, rhoA: 1.0, rho_Ip: 0.01}}
  - {name: sleeve, type: rigid, length: 0.2, origin: [0.4, 0, 0], mass: 1.0, inertia: [0.01, 0.01, 0.01]}
constraints:
  - {type: clamp, name: root, body: track, at: start}
  - {type: clamp, name: far, body: track, at: end}
  - {type: sliding_joint, name: sleeve, body: sleeve, at: 0.1, track: track, rotation: locked)" + jointKeys + R"(}
  - {type: extraction_drive, name: hold, joint: sleeve, displacement: 0}
loads:
)" + loads + "dynamic: {t_end: 0.1, dt: 0.01}\n";
  const Scene scene = parseScene(text, "sleeve-statics.yaml");
  Model model(scene);
  Assembler assembler(model);
  PetscHandle<Vec> x;
  check(assembler.setUp(PETSC_COMM_WORLD));
  check(assembler.createVector(x.address()));
  check(assembler.initialState(x));
  StaticSolver statics(assembler);
  check(statics.setUp());
  PetscBool converged = PETSC_FALSE;
  check(statics.solve(0.0, 1, x, nullptr, &converged));
  StaticSleeve out;
  out.converged = converged;
  out.q = gatherAll(x);
  out.lambda = gatherAll(statics.multipliers());
  out.force1 = channel(model, "force_tangential", out.lambda);
  out.force2 = channel(model, "force_2", out.lambda, out.q);
  out.force3 = channel(model, "force_3", out.lambda, out.q);
  out.moment2 = channel(model, "moment_2", out.lambda);
  out.moment3 = channel(model, "moment_3", out.lambda);
  out.torque = channel(model, "torque", out.lambda);
  return out;
}

} // namespace

// A sleeve at mid-span of a beam clamped at both ends: by symmetry the
// section there keeps its initial axes under a lateral force (the tangent
// stays along x, no twist), so the reactions on the sleeve are minus the
// force in (y, z) and nothing else; under a torque T about the axis the
// axis stays straight, the reaction torque is -T and the section at
// mid-span turns by T L / (4 GJ) (two halves of torsional stiffness 2 GJ / L
// in parallel; exact for the element, whose twist is linear per element).
TEST(SpatialSlidingJointStatics, SleeveReactionsMatchHandStatics)
{
  const double F = 3.0, T = 0.7, GJ = 0.5, L = 1.0;
  {
    const StaticSleeve s = solveSleeve("  - {type: point_force, body: sleeve, at: 0.1, force: [0, " + number(F) + ", 0]}\n");
    ASSERT_TRUE(s.converged);
    std::printf("lateral y: force_t %.3e force_2 %.15g force_3 %.3e moments %.3e %.3e torque %.3e\n", s.force1,
                s.force2, s.force3, s.moment2, s.moment3, s.torque);
    EXPECT_NEAR(s.force2, -F, 1e-10 * F);
    for (double zero : {s.force1, s.force3}) EXPECT_NEAR(zero, 0.0, 1e-10 * F);
    for (double zero : {s.moment2, s.moment3, s.torque}) EXPECT_NEAR(zero, 0.0, 1e-10 * F * L);
    // The beam did bend: the mid-span node moved along y.
    EXPECT_GT(s.q[7 * 2 + 1], 1e-3);
  }
  {
    const StaticSleeve s = solveSleeve("  - {type: point_force, body: sleeve, at: 0.1, force: [0, 0, " + number(-F) + "]}\n");
    ASSERT_TRUE(s.converged);
    std::printf("lateral z: force_t %.3e force_2 %.3e force_3 %.15g moments %.3e %.3e torque %.3e\n", s.force1,
                s.force2, s.force3, s.moment2, s.moment3, s.torque);
    EXPECT_NEAR(s.force3, F, 1e-10 * F);
    for (double zero : {s.force1, s.force2}) EXPECT_NEAR(zero, 0.0, 1e-10 * F);
    for (double zero : {s.moment2, s.moment3, s.torque}) EXPECT_NEAR(zero, 0.0, 1e-10 * F * L);
    EXPECT_LT(s.q[7 * 2 + 2], -1e-3);
  }
  {
    const StaticSleeve s = solveSleeve("  - {type: point_moment, body: sleeve, at: 0.1, moment: [" + number(T) + ", 0, 0]}\n");
    ASSERT_TRUE(s.converged);
    const double twist = s.q[7 * 2 + 6], exact = T * L / (4.0 * GJ);
    std::printf("torque: force_t %.3e forces %.3e %.3e moments %.3e %.3e torque %.15g twist %.15g (exact %.15g)\n",
                s.force1, s.force2, s.force3, s.moment2, s.moment3, s.torque, twist, exact);
    EXPECT_NEAR(s.torque, -T, 1e-10 * T);
    for (double zero : {s.force1, s.force2, s.force3}) EXPECT_NEAR(zero, 0.0, 1e-10 * T / L);
    for (double zero : {s.moment2, s.moment3}) EXPECT_NEAR(zero, 0.0, 1e-10 * T);
    EXPECT_NEAR(twist, exact, 1e-10 * exact);
  }
  // A couple M about y (z) bends the beam antisymmetrically in the x-z (x-y)
  // plane: the section at mid-span turns about y (z), so d2 = y (d3 = z)
  // still, and the reaction moment on the sleeve is -M about it.
  for (int axis : {1, 2}) {
    const double M = 0.4;
    const std::string moment = axis == 1 ? "[0, " + number(M) + ", 0]" : "[0, 0, " + number(M) + "]";
    const StaticSleeve s = solveSleeve("  - {type: point_moment, body: sleeve, at: 0.1, moment: " + moment + "}\n");
    ASSERT_TRUE(s.converged);
    const double reported = axis == 1 ? s.moment2 : s.moment3, other = axis == 1 ? s.moment3 : s.moment2;
    std::printf("couple about %c: forces %.3e %.3e %.3e moment %.15g other %.3e torque %.3e, slope %.3e\n", "xyz"[axis],
                s.force1, s.force2, s.force3, reported, other, s.torque, s.q[7 * 2 + 3 + (axis == 1 ? 2 : 1)]);
    EXPECT_NEAR(reported, -M, 1e-10 * M);
    for (double zero : {s.force1, s.force2, s.force3}) EXPECT_NEAR(zero, 0.0, 1e-10 * M / L);
    for (double zero : {other, s.torque}) EXPECT_NEAR(zero, 0.0, 1e-10 * M);
    EXPECT_GT(std::abs(s.q[7 * 2 + 3 + (axis == 1 ? 2 : 1)]), 1e-3); // the section did turn
  }
}

// The same sleeve (1 kg, centre of mass at its joint point) on pads instead
// of the rigid lateral rows: pads along d2 = y (stiffness 2e4 N/m,
// clearance 1 mm) and, with their own values, along d3 = z (1e4 N/m, 2 mm).
// Under gravity -z the sleeve rests on the lower d3 pad: it sits
// m g / k3 + c3 below the track's axis at s (whatever the beam's own
// deflection), the d3 pad force is m g and the d2 pads are free (the sleeve
// stays in their clearance, force 0). A lateral force F along y (no
// gravity) presses it onto the d2 pad: offset F / k2 + c2 along y, pad force
// -F. The loads act on the axis of a symmetric clamped beam at mid-span, so
// the track's section there keeps d2 = y, d3 = z and the forces are exactly
// along the pads.
TEST(SpatialSlidingJointStatics, SleeveOnPadsDeflectsByLoadOverStiffnessPlusClearance)
{
  const double m = 1.0, g = 9.81, k2 = 2.0e4, c2 = 1.0e-3, k3 = 1.0e4, c3 = 2.0e-3, F = 3.0;
  const std::string pads = ", pad: {stiffness: 2.0e4, clearance: 1.0e-3, damping: 5}, "
                           "pad_3: {stiffness: 1.0e4, clearance: 2.0e-3}";
  // Track node 2 (s = 0.5): coordinates 14..16; sleeve position 35..37 (its
  // joint point is its origin + 0.1 along x; it does not turn).
  {
    const StaticSleeve s = solveSleeve("  - {type: point_force, body: sleeve, at: 0.1, force: [0, 0, 0]}\n", pads, "-9.81");
    ASSERT_TRUE(s.converged);
    const double drop = s.q[16] - s.q[37], exact = m * g / k3 + c3, side = s.q[36] - s.q[15];
    std::printf("gravity on pads: drop %.15g (exact %.15g), force_3 %.15g, force_2 %.3e, offset y %.3e, beam %.3e\n",
                drop, exact, s.force3, s.force2, side, s.q[16]);
    EXPECT_NEAR(drop, exact, 1e-10 * exact);
    EXPECT_NEAR(s.force3, m * g, 1e-10 * m * g);
    EXPECT_EQ(s.force2, 0.0);
    EXPECT_LT(std::abs(side), c2);
    EXPECT_LT(s.q[16], -1e-3); // the beam did bend: the drop is relative to it
  }
  {
    const StaticSleeve s =
        solveSleeve("  - {type: point_force, body: sleeve, at: 0.1, force: [0, " + number(F) + ", 0]}\n", pads);
    ASSERT_TRUE(s.converged);
    const double offset = s.q[36] - s.q[15], exact = F / k2 + c2;
    std::printf("lateral on pads: offset %.15g (exact %.15g), force_2 %.15g, force_3 %.3e, torque %.3e\n", offset,
                exact, s.force2, s.force3, s.torque);
    EXPECT_NEAR(offset, exact, 1e-10 * exact);
    EXPECT_NEAR(s.force2, -F, 1e-10 * F);
    EXPECT_EQ(s.force3, 0.0);
    EXPECT_NEAR(s.force1, 0.0, 1e-10 * F);
    EXPECT_GT(s.q[15], 1e-3);
  }
}

// A 1 kg sleeve (centre of mass at its joint point, rotation locked) on a
// 2 m beam inclined by alpha = 30 deg in the x-z plane, clamped at both ends
// and stiff enough (EI = 1e8 N m^2: deflection under the sleeve ~ 1e-9 m)
// to be straight, gravity -z: without friction it slides down as a free
// block, s(t) = s0 - g sin(alpha) t^2 / 2, from s0 = 1.5 m over 0.5 s
// (0.61 m: it crosses two or three of the 8 elements), with the normal
// reaction m g cos(alpha) on its upper side d3 and no other reaction.
TEST(SpatialSlidingJointDynamics, SleeveSlidesDownAnInclineLikeAFreeBlock)
{
  const double alpha = kPi / 6, g = 9.81, m = 1.0, s0 = 1.5;
  const double c = std::cos(alpha), s = std::sin(alpha);
  const std::string text = R"(
name: sleeve-incline
dimension: 3
analysis: dynamic
gravity: [0, 0, -9.81]
bodies:
  - {name: track, type: ancf_beam, length: 2.0, elements: 8, axis: [)" +
                           number(c) + ", 0, " + number(s) + R"(], up: [0, 1, 0],
     section: {EA: 1.0e10, EI_y: 1.0e8, EI_z: 1.0e8, GJ: 1.0e8, rhoA: 1.0, rho_Ip: 0.01}}
  - {name: sleeve, type: rigid, length: 0.2, origin: [)" +
                           number((s0 - 0.1) * c) + ", 0, " + number((s0 - 0.1) * s) + R"(], axis: [)" + number(c) +
                           ", 0, " + number(s) + R"(], up: [0, 1, 0],
     mass: 1.0, inertia: [0.01, 0.01, 0.01]}
constraints:
  - {type: clamp, name: root, body: track, at: start}
  - {type: clamp, name: far, body: track, at: end}
  - {type: sliding_joint, name: sleeve, body: sleeve, at: 0.1, track: track, rotation: locked}
dynamic: {t_end: 0.5, dt: 1.0e-3, rho_inf: 0.8}
)";
  const DynamicHistory h = runDynamic(parseScene(text, "sleeve-incline.yaml"));
  ASSERT_TRUE(h.summary.completed) << h.summary.failure;
  EXPECT_GE(h.patternVersion, 2); // the contact point moved to other elements
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return; // outputs are evaluated on rank 0
  // Channels of this scene: s, force_tangential, force_2, force_3, moment_2, moment_3, torque.
  // The reactions once the start has settled: gravity switched on at t = 0
  // rings the stiff, light track (its vibration, far above 1/h, is damped
  // out by rho_inf within about 0.1 s).
  double worstS = 0, worstN = 0, worstOther = 0;
  for (std::size_t k = 0; k < h.time.size(); ++k) {
    const double t = h.time[k];
    const std::vector<double> &o = h.outputs[k];
    ASSERT_EQ(o.size(), 7u);
    worstS = std::max(worstS, std::abs(o[0] - (s0 - 0.5 * g * s * t * t)));
    if (t < 0.2) continue;
    worstN = std::max(worstN, std::abs(o[3] - m * g * c));
    for (int j : {1, 2, 4, 5, 6}) worstOther = std::max(worstOther, std::abs(o[j]));
  }
  std::printf("incline: s(t_end) = %.12f m (exact %.12f), max |s - exact| %.3e m, max |N - m g cos a| %.3e N, "
              "max |other reactions| %.3e, %d pattern versions\n",
              h.outputs.back()[0], s0 - 0.5 * g * s * 0.25, worstS, worstN, worstOther, h.patternVersion);
  // s: the track's deflection under the sleeve (~1e-9 m) and its ringing.
  EXPECT_LT(worstS, 2e-8);
  EXPECT_LT(worstN, 1e-6 * m * g);
  EXPECT_LT(worstOther, 1e-6 * m * g);
}

// inputs/sleeve_push.yaml (a flexible rod pushed through a clamped sleeve by
// an extraction drive on one of its two frictionless sliding joints; the
// contact points cross element boundaries) without its sensor, planar and
// through spatialEmbedding (-boom_spatial), full Newton: the rod's and the
// sleeve's node positions and slopes and both contact coordinates agree, and
// nothing leaves the plane.
TEST(SpatialSlidingJointDynamics, PlanarSlidingJointSceneRunAsSpatialModelInItsPlane)
{
  Scene planar = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/sleeve_push.yaml");
  planar.output.sensors.clear();
  planar.dynamic.t_end = 0.3;
  const Scene spatial = spatialEmbedding(planar);
  check(PetscOptionsSetValue(nullptr, "-boom_jacobian_reuse", "0"));
  const DynamicHistory a = runDynamicWith(planar, PETSC_COMM_WORLD, testOptions());
  const DynamicHistory b = runDynamicWith(spatial, PETSC_COMM_WORLD, testOptions());
  check(PetscOptionsClearValue(nullptr, "-boom_jacobian_reuse"));
  ASSERT_TRUE(a.summary.completed) << a.summary.failure;
  ASSERT_TRUE(b.summary.completed) << b.summary.failure;
  ASSERT_EQ(a.time.size(), b.time.size());
  EXPECT_GE(a.patternVersion, 2);
  EXPECT_EQ(a.patternVersion, b.patternVersion);
  // Rod: 17 nodes, sleeve: 2; then the two contact coordinates.
  const int nodes = 19, planarSlack = 4 * nodes, spatialSlack = 7 * nodes;
  double position = 0, size = 0, outOfPlane = 0;
  for (int n = 0; n < nodes; ++n) {
    const double *p = a.finalState.data() + 4 * n, *s = b.finalState.data() + 7 * n;
    for (int c = 0; c < 2; ++c) {
      position = std::max({position, std::abs(s[c] - p[c]), std::abs(s[3 + c] - p[2 + c])});
      size = std::max({size, std::abs(p[c]), std::abs(p[2 + c])});
    }
    outOfPlane = std::max({outOfPlane, std::abs(s[2]), std::abs(s[5]), std::abs(s[6])});
  }
  double slack = 0;
  for (int j = 0; j < 2; ++j)
    slack = std::max(slack, std::abs(a.finalState[planarSlack + j] - b.finalState[spatialSlack + j]));
  std::printf("sleeve push in its plane: positions and slopes %.3e relative, contact coordinates %.3e m (s = %.9f, "
              "%.9f), out of plane %.3e, %d pattern versions\n",
              position / size, slack, a.finalState[planarSlack], a.finalState[planarSlack + 1], outOfPlane,
              a.patternVersion);
  EXPECT_LT(position / size, 1e-8);
  EXPECT_LT(slack, 1e-8);
  EXPECT_EQ(outOfPlane, 0.0);
}
