// Compliant slide pads with clearance at sliding joints (docs/model.md §2.1,
// pad variant): the rigid limit against the bilateral joint, and a beam on
// two pads loaded transversely through zero against statics.
#include "support.hpp"

#include "boomdyn/pad_contact.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// Tip sensor and modes of a static run with its modal analysis.
class StaticModesRecorder : public Monitor {
public:
  StaticModesRecorder(Simulation &sim, double &tip, std::vector<double> &hz) : sim_(sim), tip_(tip), hz_(hz) {}
  PetscErrorCode modes(double, const ModalResult &m) override
  {
    hz_ = m.frequencyHz;
    return 0;
  }
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override
  {
    std::vector<SensorReading> r;
    PetscFunctionBeginUser;
    PetscCheck(outcome.completed(), PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "static run failed");
    PetscCall(sim_.sensors().read(s.q, s.v, r));
    tip_ = r.empty() ? 0.0 : r[0].position.y();
    PetscCallMPI(MPI_Bcast(&tip_, 1, MPI_DOUBLE, 0, sim_.comm()));
    PetscFunctionReturn(0);
  }

private:
  Simulation &sim_;
  double &tip_;
  std::vector<double> &hz_;
};

// The three-boom telescope of test_telescope_statics (retracted), static
// under gravity and a tip load, with its four sliding joints rigid or padded.
Scene telescope(const std::string &pad)
{
  std::string s = R"(name: telescope-pads
analysis: static
gravity: [0, -9.81]
bodies:
  - {name: boom1, length: 2.0, elements: 8, origin: [0, 0], section: {E: 2.1e11, rho: 7850, A: 6.944e-3, I: 6.395214e-5}}
  - {name: boom2, length: 2.0, elements: 8, origin: [0.25, 0], section: {E: 2.1e11, rho: 7850, A: 5.264e-3, I: 3.720306e-5}}
  - {name: boom3, length: 2.0, elements: 8, origin: [0.5, 0], section: {E: 2.1e11, rho: 7850, A: 3.816e-3, I: 1.986431e-5}}
constraints:
  - {type: clamp, name: base, body: boom1, at: start}
  - {type: sliding_joint, name: j1, body: boom1, at: end, track: boom2PAD}
  - {type: sliding_joint, name: j2, body: boom2, at: start, track: boom1PAD}
  - {type: sliding_joint, name: j3, body: boom2, at: end, track: boom3PAD}
  - {type: sliding_joint, name: j4, body: boom3, at: start, track: boom2PAD}
  - {type: extraction_drive, name: extraction, joint: j2, displacement: 0}
  - {type: rope, name: rope, from: boom1, from_at: start, pulley: boom2, pulley_at: end, to: boom3, to_at: start}
loads:
  - {type: point_force, name: tip_load, body: boom3, at: end, force: [0, -1000]}
static: {load_steps: 1}
modal: {count: 3}
output:
  sensors:
    - {name: tip, body: boom3, at: end}
)";
  for (std::size_t at = s.find("PAD"); at != std::string::npos; at = s.find("PAD"))
    s.replace(at, 3, pad.empty() ? "" : ", pad: " + pad);
  return parseScene(s, "telescope-pads.yaml");
}

void staticWithModes(const Scene &scene, double &tip, std::vector<double> &hz)
{
  SimulationOptions o = testOptions();
  o.modal = true;
  Simulation sim(scene, PETSC_COMM_WORLD, o);
  check(sim.setUp());
  sim.addMonitor(std::make_unique<StaticModesRecorder>(sim, tip, hz));
  check(sim.run());
}

} // namespace

TEST(Pads, StiffPadsWithoutClearanceReproduceTheBilateralJoint)
{
  double tipRigid = 0, tipPad = 0;
  std::vector<double> hzRigid, hzPad;
  staticWithModes(telescope(""), tipRigid, hzRigid);
  staticWithModes(telescope("{stiffness: 1.0e12, clearance: 0}"), tipPad, hzPad);
  ASSERT_FALSE(hzRigid.empty());
  ASSERT_FALSE(hzPad.empty());
  const double dTip = std::abs(tipPad - tipRigid) / std::abs(tipRigid);
  const double dHz = std::abs(hzPad[0] - hzRigid[0]) / hzRigid[0];
  PetscPrintf(PETSC_COMM_WORLD,
              "  telescope, rigid joints: tip %.9e m, f1 %.6f Hz; pads k = 1e12 N/m, g = 0: tip %.9e m, f1 %.6f Hz; "
              "relative differences %.2e (tip), %.2e (f1)\n",
              tipRigid, hzRigid[0], tipPad, hzPad[0], dTip, dHz);
  EXPECT_LT(dTip, 1e-4);
  EXPECT_LT(dHz, 1e-4);
  // Softer pads lower the frequency and increase the deflection.
  double tipSoft = 0;
  std::vector<double> hzSoft;
  staticWithModes(telescope("{stiffness: 1.0e7}"), tipSoft, hzSoft);
  PetscPrintf(PETSC_COMM_WORLD, "  pads k = 1e7 N/m: tip %.6e m, f1 %.6f Hz\n", tipSoft, hzSoft.at(0));
  EXPECT_LT(tipSoft, tipRigid);
  EXPECT_LT(hzSoft.at(0), hzRigid[0]);
}

namespace {

// A stiff beam (the slider, 1 m, 50 kg) resting on two pads with clearance
// at its ends on a clamped rigid rail, held axially by a drive on its slack
// coordinate, under gravity W and an upward force P at x = a from its start.
// Statics: R_A = W/2 - P (1 - a/L), R_B = W/2 - P a/L (forces of the pads on
// the slider, +y): pad B changes sides at P = W L / (2a), pad A at
// P = W L / (2 (L - a)).
constexpr double kL = 1.0, kA = 0.75, kMass = 50.0, kW = kMass * 9.81, kGap = 1e-3, kPadK = 1e8;

Scene padBeam(double P)
{
  char force[64];
  std::snprintf(force, sizeof force, "%.17g", P);
  std::string s = R"(name: pads-clearance
analysis: static
gravity: [0, -9.81]
bodies:
  - {name: rail, type: rigid, length: 2.0, origin: [0, 0], section: {rhoA: 10}}
  - {name: slider, length: 1.0, elements: 4, origin: [0.5, 0], section: {EA: 1.0e10, EI: 1.0e8, rhoA: 50}}
constraints:
  - {type: clamp, body: rail, at: start}
  - {type: sliding_joint, name: A, body: slider, at: start, track: rail, pad: {stiffness: 1.0e8, clearance: 1.0e-3}}
  - {type: sliding_joint, name: B, body: slider, at: end, track: rail, pad: {stiffness: 1.0e8, clearance: 1.0e-3}}
  - {type: extraction_drive, name: hold, joint: A, displacement: 0}
loads:
  - {type: point_force, name: lift, body: slider, at: 0.75, force: [0, )";
  s += force;
  s += "]}\nstatic: {load_steps: 1}\n";
  return parseScene(s, "pads-clearance.yaml");
}

struct PadOutcome {
  std::vector<PadState> pads;
  int iterations = 0;
  bool converged = false;
};

// The pads' states at the end of a static run, from the gathered state.
class PadRecorder : public Monitor {
public:
  PadRecorder(Simulation &sim, PadOutcome &out) : sim_(sim), out_(out) {}
  PetscErrorCode afterStep(const RunState &s, std::string *) override
  {
    out_.iterations += s.iterations;
    return 0;
  }
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override
  {
    out_.converged = outcome.completed();
    const std::vector<double> q = gatherAll(s.q);
    for (const PadContact *pad : sim_.model().pads()) {
      std::vector<PetscInt> dofs;
      pad->coordinates(dofs);
      std::vector<double> qp;
      for (PetscInt i : dofs) qp.push_back(q[i]);
      out_.pads.push_back(pad->state(qp.data(), nullptr));
    }
    return 0;
  }

private:
  Simulation &sim_;
  PadOutcome &out_;
};

PadOutcome solvePadBeam(double P)
{
  PadOutcome out;
  Simulation sim(padBeam(P), PETSC_COMM_WORLD, testOptions());
  check(sim.setUp());
  sim.addMonitor(std::make_unique<PadRecorder>(sim, out));
  check(sim.run());
  return out;
}

} // namespace

TEST(Pads, BeamOnTwoPadsSwitchesSidesAtThePredictedLoadsAndMatchesStatics)
{
  const double switchB = kW * kL / (2 * kA), switchA = kW * kL / (2 * (kL - kA));
  double worst = 0;
  int maxIterations = 0;
  // Just below and above each predicted switch (1 %): the side changes there.
  for (double P : {-0.5 * kW, 0.0, 0.5 * kW, switchB * 0.99, switchB * 1.01, kW, switchA * 0.99, switchA * 1.01,
                   3 * kW}) {
    const PadOutcome out = solvePadBeam(P);
    ASSERT_TRUE(out.converged) << "P = " << P;
    ASSERT_EQ(out.pads.size(), 2u);
    const double R[2] = {kW / 2 - P * (1 - kA / kL), kW / 2 - P * kA / kL};
    for (int k = 0; k < 2; ++k) {
      const PadState &st = out.pads[k];
      // A pad pushing the slider up (R > 0) holds it from below: d < -g.
      EXPECT_EQ(st.side, R[k] > 0 ? -1 : 1) << "pad " << "AB"[k] << " at P = " << P;
      EXPECT_NEAR(st.penetration, std::abs(R[k]) / kPadK, 1e-8 * kW / kPadK);
      worst = std::max(worst, std::abs(st.force - R[k]) / kW);
    }
    maxIterations = std::max(maxIterations, out.iterations);
    PetscPrintf(PETSC_COMM_WORLD,
                "  P/W = %8.5f: pad A side %+d force %12.6f N (statics %12.6f), pad B side %+d force %12.6f N "
                "(statics %12.6f), %d Newton iterations\n",
                P / kW, out.pads[0].side, out.pads[0].force, R[0], out.pads[1].side, out.pads[1].force, R[1],
                out.iterations);
  }
  PetscPrintf(PETSC_COMM_WORLD, "  max |f - R| / W = %.2e, max Newton iterations %d\n", worst, maxIterations);
  EXPECT_LT(worst, 1e-8);
}

TEST(Pads, FallOntoPadsThenLiftOffUnderARisingForceAreEvents)
{
  // The beam of the static test, released inside the clearance (d = 0): it
  // falls freely by g onto both pads (contact at t = sqrt(2 g / 9.81)); an
  // upward force P = 1000 N (t - 0.05 s) / 0.5 s then lifts pad B off at
  // P = W L / (2a) and pad A at P = W L / (2 (L - a)) (quasi-static: the
  // pad-beam frequencies are ~200 Hz, the load rises over 0.5 s).
  std::string text = R"(name: pads-lift-off
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: rail, type: rigid, length: 2.0, origin: [0, 0], section: {rhoA: 10}}
  - {name: slider, length: 1.0, elements: 4, origin: [0.5, 0], section: {EA: 1.0e10, EI: 1.0e8, rhoA: 50}}
constraints:
  - {type: clamp, body: rail, at: start}
  - {type: sliding_joint, name: A, body: slider, at: start, track: rail, pad: {stiffness: 1.0e8, clearance: 1.0e-3, damping: 5.0e4}}
  - {type: sliding_joint, name: B, body: slider, at: end, track: rail, pad: {stiffness: 1.0e8, clearance: 1.0e-3, damping: 5.0e4}}
  - {type: extraction_drive, name: hold, joint: A, displacement: 0}
loads:
  - {type: point_force, name: lift, body: slider, at: 0.75, force: [0, 1000], scale: {type: ramp, t0: 0.05, t1: 0.55, from: 0, to: 1}}
dynamic: {t_end: 0.56, dt: 1.0e-3, rho_inf: 0.8}
)";
  const Scene scene = parseScene(text, "pads-lift-off.yaml");
  const DynamicHistory run = runDynamic(scene);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return; // events and outputs live on rank 0
  const double tContact = std::sqrt(2 * kGap / 9.81);
  const double tB = 0.05 + 0.5 * (kW * kL / (2 * kA)) / 1000, tA = 0.05 + 0.5 * (kW * kL / (2 * (kL - kA))) / 1000;
  double firstContact[2] = {-1, -1}, liftOff[2] = {-1, -1};
  for (const TypeEvent &e : run.events) {
    const int pad = e.component == "A" ? 0 : 1;
    PetscPrintf(PETSC_COMM_SELF, "  event t = %.6f s pad %s %s (side %+d)\n", e.t, e.component.c_str(), e.kind.c_str(),
                e.direction);
    if (e.kind == "contact" && firstContact[pad] < 0) firstContact[pad] = e.t;
    if (e.kind == "lift_off" && e.direction == -1 && e.t > 0.1) liftOff[pad] = e.t;
  }
  PetscPrintf(PETSC_COMM_SELF,
              "  first contact A %.6f s, B %.6f s (free fall %.6f s); lift-off B %.4f s (predicted %.4f), A %.4f s "
              "(predicted %.4f)\n",
              firstContact[0], firstContact[1], tContact, liftOff[1], tB, liftOff[0], tA);
  // An event's time interpolates the penetration linearly inside its step:
  // within one step h = 1 ms of the exact time (measured: contact 0.19 h
  // late, where the pad stops the fall inside the step; lift-offs < 0.1 h).
  const double h = 1e-3;
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(firstContact[k], tContact, h);
  EXPECT_NEAR(liftOff[1], tB, h);
  EXPECT_NEAR(liftOff[0], tA, h);
  // The outputs (pad group: force, penetration, side per pad): at the end
  // pad B bears on the upper side.
  ASSERT_FALSE(run.outputs.empty());
  const Model model(scene);
  int sideB = -1;
  for (std::size_t k = 0; k < model.outputChannels().size(); ++k) {
    const OutputChannel &c = model.outputChannels()[k];
    if (c.group == "pad" && c.name == "B" && c.quantity == "side") sideB = static_cast<int>(k);
  }
  ASSERT_GE(sideB, 0);
  EXPECT_EQ(run.outputs.back().at(sideB), 1.0);
}

namespace {

// Every output channel's value at the end of a static run (rank 0).
class OutputRecorder : public Monitor {
public:
  OutputRecorder(Simulation &sim, std::vector<double> &out, bool &converged) : sim_(sim), out_(out), converged_(converged) {}
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override
  {
    std::vector<double> slacks, multipliers;
    PetscFunctionBeginUser;
    converged_ = outcome.completed();
    PetscCall(sim_.sensors().readJoints(s.q, s.lambda, slacks, multipliers));
    PetscCall(sim_.sensors().readOutputs(s.t, s.q, s.v, multipliers, out_));
    PetscFunctionReturn(0);
  }

private:
  Simulation &sim_;
  std::vector<double> &out_;
  bool &converged_;
};

} // namespace

// Stress resultants at the joints: boom2 (8 elements of 0.25 m) slides in a
// clamped boom1 on a rear pad (its start on boom1) and a front pad (boom1's
// end on boom2, at s = 1.75 m, a node); a 100 N tip load down. Beyond the
// front pad boom2 carries only the tip load: M(s) = -P (L - s) = -25 N m and
// Q = dM/ds = +P. The moment is linear there, which cubic elements
// represent exactly: what is left is the geometric nonlinearity (slopes ~1e-4).
// Measured: M = -24.9999999907 N m (3.7e-10 relative), Q = -14.2857142968 N
// against -100 * 0.25 / 1.75 (7.8e-10 relative), rigid and padded alike.
TEST(Pads, StressResultantsAtTheFrontPadMatchStatics)
{
  for (const std::string pad : {std::string(""), std::string(", pad: {stiffness: 1.0e9}")}) {
    const std::string text = R"(name: joint-resultants
analysis: static
bodies:
  - {name: boom1, length: 2.0, elements: 8, section: {EA: 8.5e8, EI: 4.95e6, rhoA: 31.8}}
  - {name: boom2, length: 2.0, elements: 8, origin: [0.25, 0], section: {EA: 6.0e8, EI: 3.0e6, rhoA: 25.0}}
constraints:
  - {type: clamp, name: base, body: boom1, at: start}
  - {type: sliding_joint, name: rear, body: boom2, at: start, track: boom1)" +
                             pad + R"(}
  - {type: sliding_joint, name: front, body: boom1, at: end, track: boom2)" +
                             pad + R"(}
  - {type: extraction_drive, name: hold, joint: rear, displacement: 0}
loads:
  - {type: point_force, name: tip, body: boom2, at: end, force: [0, -100]}
static: {load_steps: 1}
)";
    const Scene scene = parseScene(text, "joint-resultants.yaml");
    std::vector<double> out;
    bool converged = false;
    Simulation sim(scene, PETSC_COMM_WORLD, testOptions());
    check(sim.setUp());
    sim.addMonitor(std::make_unique<OutputRecorder>(sim, out, converged));
    check(sim.run());
    ASSERT_TRUE(converged);
    PetscMPIInt rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank != 0) continue;
    auto channel = [&](const std::string &joint, const std::string &quantity) {
      const auto &channels = sim.model().outputChannels();
      for (std::size_t k = 0; k < channels.size(); ++k)
        if (channels[k].group == "joint_resultants" && channels[k].name == joint && channels[k].quantity == quantity)
          return out.at(k);
      ADD_FAILURE() << "no channel " << joint << "." << quantity;
      return 0.0;
    };
    const double M = channel("front", "track_M"), Q = channel("front", "track_Q"), N = channel("front", "track_N");
    const double Fn = channel("front", "normal_force"), Fr = channel("rear", "normal_force");
    PetscPrintf(PETSC_COMM_SELF,
                "  %s joints: front pad on boom2: M = %.10f N m (statics -25), Q = %.10f N (statics -14.2857142857 before the pad, 100 beyond), N = %.3e N; "
                "normal forces front %.6f N, rear %.6f N (statics |front| = 114.285714 = 100 * 2 / 1.75)\n",
                pad.empty() ? "rigid" : "padded", M, Q, N, Fn, Fr);
    EXPECT_NEAR(M, -25.0, 25.0 * 1e-6);
    // The shear jumps at the pad by the pad force: -P 0.25/1.75 between the
    // pads, +P beyond. The contact point sits on a node, so Q is the value of
    // whichever element holds s (here the one before the node, s = 1.75 - O(1e-9)).
    const double Qbetween = -100.0 * 0.25 / 1.75;
    EXPECT_TRUE(std::abs(Q - Qbetween) < 1e-6 * 100.0 || std::abs(Q - 100.0) < 1e-6 * 100.0) << "Q = " << Q;
    // Boom2 statics: rear at 0 and front at 1.75 m from its start, tip at 2 m.
    EXPECT_NEAR(std::abs(Fn), 100.0 * 2.0 / 1.75, 1e-3);
  }
}

// A 1 kg block falls through the clearance g onto a pad (k = 1e5 N/m,
// c = 190 N s/m: 30 % of critical) and bounces. The pad is a linear
// Kelvin-Voigt pad (docs/model.md §2.1): its force -k p - c pdot acts while
// the penetration p > 0, and so it pulls on the block while the block leaves
// faster than k p / c. Closed form of the contact phase (p down into the
// pad, tau from the contact):
//   p = p_s + exp(-beta tau) (A cos(omega tau) + B sin(omega tau)),
//   p_s = m g0/k, beta = c/2m, omega^2 = k/m - beta^2, A = -p_s, B = (v_in - beta p_s)/omega;
// the block leaves at p = 0 and rises by pdot^2/(2 g0). A pad that let go
// where its force vanishes (k p + c pdot = 0, p > 0) would let it rebound
// 1.46 instead of 0.95 mm: the test tells the two laws apart.
TEST(Pads, BouncingBlockMatchesTheKelvinVoigtContactInClosedForm)
{
  const double m = 1.0, k = 1e5, c = 190.0, gap = 0.01, g0 = 9.81, h = 2e-5;
  char text[2048];
  std::snprintf(text, sizeof text, R"(name: pad-bounce
analysis: dynamic
gravity: [0, %.17g]
bodies:
  - {name: rail, type: rigid, length: 2.0, origin: [0, 0], section: {rhoA: 10}}
  - {name: block, type: rigid, length: 0.2, origin: [0.9, 0], section: {rhoA: %.17g}}
constraints:
  - {type: clamp, body: rail, at: start}
  - {type: sliding_joint, name: pad, body: block, at: 0.1, track: rail, pad: {stiffness: %.17g, clearance: %.17g, damping: %.17g}}
dynamic: {t_end: 0.09, dt: %.17g, rho_inf: 0.8}
output:
  sensors:
    - {name: centre, body: block, at: 0.1}
)",
                -g0, m / 0.2, k, gap, c, h);
  const DynamicHistory run = runDynamic(parseScene(text, "pad-bounce.yaml"));
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;

  // Closed form.
  const double vIn = std::sqrt(2 * g0 * gap), ps = m * g0 / k, beta = c / (2 * m);
  const double omega = std::sqrt(k / m - beta * beta), A = -ps, B = (vIn - beta * ps) / omega;
  auto p = [&](double tau) { return ps + std::exp(-beta * tau) * (A * std::cos(omega * tau) + B * std::sin(omega * tau)); };
  auto pdot = [&](double tau) {
    return std::exp(-beta * tau) *
           ((-beta * A + omega * B) * std::cos(omega * tau) + (-beta * B - omega * A) * std::sin(omega * tau));
  };
  auto firstRoot = [](auto f, double lo, double hi) { // f(lo) > 0: the first sign change on a fine grid, then bisection
    double a = lo;
    for (double b = lo + 1e-6; b <= hi; b += 1e-6) {
      if (f(b) <= 0) {
        for (int i = 0; i < 60; ++i) {
          const double mid = 0.5 * (a + b);
          (f(mid) > 0 ? a : b) = mid;
        }
        return 0.5 * (a + b);
      }
      a = b;
    }
    return hi;
  };
  const double tauRelease = firstRoot([&](double t) { return k * p(t) + c * pdot(t); }, 1e-9, 0.05);
  const double apexClipped = -gap - (p(tauRelease) - pdot(tauRelease) * pdot(tauRelease) / (2 * g0));
  const double tauZero = firstRoot([&](double t) { return p(t); }, 1e-9, 0.05);
  const double apexPulling = -gap - (0.0 - pdot(tauZero) * pdot(tauZero) / (2 * g0));

  // Simulated: the highest point after the first contact, and the pad force never pulling.
  const Model model(parseScene(text, "pad-bounce.yaml"));
  int force = -1, side = -1;
  for (std::size_t i = 0; i < model.outputChannels().size(); ++i) {
    const OutputChannel &ch = model.outputChannels()[i];
    if (ch.group == "pad" && ch.quantity == "force") force = static_cast<int>(i);
    if (ch.group == "pad" && ch.quantity == "side") side = static_cast<int>(i);
  }
  ASSERT_GE(force, 0);
  ASSERT_GE(side, 0);
  bool touched = false;
  double apex = -1e9, lowest = 0, worstPull = 0;
  for (std::size_t n = 0; n < run.time.size(); ++n) {
    const double y = run.sensors[n][0].position.y();
    worstPull = std::max(worstPull, run.outputs[n][side] * run.outputs[n][force]);
    lowest = std::min(lowest, y);
    if (run.outputs[n][side] != 0) touched = true;
    else if (touched) apex = std::max(apex, y);
  }
  // The pull at the end of the contact: c |pdot| at p = 0.
  const double pullAtRelease = c * std::abs(pdot(tauZero));
  PetscPrintf(PETSC_COMM_SELF,
              "  bounce apex %.6e m (closed form %.6e m; a pad letting go where its force vanishes: %.6e m), lowest "
              "%.6e m, largest pull %.3g N (closed form, at p = 0: %.3g N)\n",
              apex, apexPulling, apexClipped, lowest, worstPull, pullAtRelease);
  ASSERT_TRUE(touched);
  const double rebound = apexPulling + gap; // above the pad's surface
  EXPECT_NEAR(apex, apexPulling, 0.01 * rebound);
  EXPECT_GT(std::abs(apexPulling - apexClipped), 0.2 * rebound) << "the test tells the two laws apart";
  EXPECT_GT(worstPull, 0.5 * pullAtRelease) << "the Kelvin-Voigt pad pulls while the block leaves fast";
  EXPECT_LE(worstPull, 1.001 * pullAtRelease);
}

TEST(Pads, ZeroClearancePadStartingInContactReportsNoEventAtTheStart)
{
  // Issue 40: a beam on two pads without clearance, placed on the track's
  // centerline (d = 0: in contact, no force), under gravity. The first
  // step decides the side (the pads hold the beam from below, side -1);
  // before, the start reported a lift_off from side +1 and a contact on
  // side -1 at t = 0. With the pads' damping the beam settles (at most
  // twice the static deflection W / (2 k) = 2.5e-6 m) and never comes back
  // to d = 0: no event at all, and both pads end on side -1.
  const std::string text = R"(name: pads-in-contact
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: rail, type: rigid, length: 2.0, origin: [0, 0], section: {rhoA: 10}}
  - {name: slider, length: 1.0, elements: 4, origin: [0.5, 0], section: {EA: 1.0e10, EI: 1.0e8, rhoA: 50}}
constraints:
  - {type: clamp, body: rail, at: start}
  - {type: sliding_joint, name: A, body: slider, at: start, track: rail, pad: {stiffness: 1.0e8, clearance: 0, damping: 5.0e4}}
  - {type: sliding_joint, name: B, body: slider, at: end, track: rail, pad: {stiffness: 1.0e8, clearance: 0, damping: 5.0e4}}
  - {type: extraction_drive, name: hold, joint: A, displacement: 0}
dynamic: {t_end: 0.05, dt: 1.0e-3, rho_inf: 0.8}
)";
  const Scene scene = parseScene(text, "pads-in-contact.yaml");
  const DynamicHistory run = runDynamic(scene);
  ASSERT_TRUE(run.summary.completed) << run.summary.failure;
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return; // events and outputs live on rank 0
  for (const TypeEvent &e : run.events)
    ADD_FAILURE() << "event t = " << e.t << " s pad " << e.component << " " << e.kind << " (side " << e.direction << ")";
  const Model model(scene);
  for (std::size_t k = 0; k < model.outputChannels().size(); ++k) {
    const OutputChannel &c = model.outputChannels()[k];
    if (c.group == "pad" && c.quantity == "side") EXPECT_EQ(run.outputs.back()[k], -1.0) << "pad " << c.name;
    if (c.group == "pad" && c.quantity == "penetration")
      PetscPrintf(PETSC_COMM_SELF, "  pad %s: penetration at the end %.3e m (W / (2 k) = %.3e m)\n", c.name.c_str(),
                  run.outputs.back()[k], 50.0 * 9.81 / (2 * 1.0e8));
  }
}
