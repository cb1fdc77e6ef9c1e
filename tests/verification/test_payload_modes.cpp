// A payload on a hoist rope under a flexible boom (issue 16): the lowest
// frequencies of the eigen-analysis against an independent model built here,
// and the tracked pendulum frequency against the swing of the same run.
//
// The FE model: a cantilever boom (ANCF, length Lb, clamped at s = 0,
// horizontal), an elastic rope from the clamped root s = 0 (the fixed rope
// end stands in for the winch) over a point pulley at the boom tip down to a
// 1 t payload (a short rigid bar, rope at its centre of mass, its rotation
// held by an angle drive, so it is a point mass that translates), hanging l
// below the tip, the rope pretensioned to the payload's weight.
//
// The independent model (stated; every number derived in the test):
//  - boom tip stiffness k_b = P / delta from a static tip-load run of the
//    boom alone; boom modal (tip) mass m_b = k_b / omega_0^2 from the boom
//    alone's first frequency (a cantilever's tip mass is 0.243 rhoA Lb
//    this way; Rayleigh's 33/140 = 0.236 differs by 0.6 % of a mass that is
//    3 % of the payload);
//  - the rope a massless spring k_r = EA / L0 (L0: the unstretched length of
//    the whole rope, root to tip to payload; the vertical motion of the tip
//    changes only the hanging part, the horizontal part to second order);
//  - the pendulum: a point mass on the hanging length l (at tension m g the
//    lateral stiffness of the rope is T / l = m g / l): omega_p^2 = g / l.
//    The boom is horizontal, so the swing (horizontal) is uncoupled from the
//    bending (vertical) to first order, and the vertical motion is the
//    two-degree-of-freedom chain ground -k_b- m_b -k_r- m:
//      [m_b 0; 0 m] y'' + [k_b + k_r, -k_r; -k_r, k_r] y = 0.
//    Left out: the rope force's axial compression of the boom (geometric
//    softening ~1.2 T / Lb) and the restoring pull of the tilted horizontal
//    rope part (T / Lb), each ~0.2 % of k_b here, of opposite sign.
// The two lowest frequencies of the FE model are the pendulum and the lower
// root of the chain (the payload bouncing on rope and boom); the stiff boom
// gives them within 1 % (measured: pendulum 1.4e-5, bounce 2.0e-3). The higher root (the boom
// bending under the rope spring) is printed, not asserted: it depends on the
// boom's mode shape more than a one-mass model holds.
//
// The tracked pendulum: from the static equilibrium (initial: static) under a
// sideways push F = m g a / l on the payload, removed over 10 ms, the payload
// swings with amplitude a; a FrequencyTracker analyzes the run every 0.1 s (MAC following
// from the lowest mode); the tracked frequency must be the pendulum at every
// analysis (MAC > 0.99) and agree with the frequency from the zero
// crossings of the swing (payload x minus tip x, linearly interpolated)
// within 1e-3 (measured 4.9e-4; the tracked value varies by 2e-3 with the
// tension along the swing; the amplitude correction of the period, theta^2 / 16, is
// 2e-4 at a = 0.05 m, l = 1 m).
#include "support.hpp"

#include "boomdyn/frequency_tracker.hpp"

#include <slepcsys.h>

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double g = 9.81, Lb = 2.0, m = 1000.0, EA = 2.0e7, l = 1.0;
// Paper boom 1 section (inputs/paper_extraction.yaml, before the calibration of I).
const std::string kSection = "{E: 2.1e11, A: 6.944e-3, I: 6.395214e-5, rho: 7850}";

std::string boomAlone(const std::string &analysis, double tipLoad)
{
  return "name: boom-alone\nanalysis: " + analysis +
         "\ngravity: [0, 0]\nbodies:\n  - {name: boom, length: 2.0, elements: 8, section: " + kSection +
         "}\nconstraints:\n  - {type: clamp, body: boom, at: start}\nloads:\n  - {type: point_force, body: boom, at: end, "
         "force: [0, " +
         std::to_string(-tipLoad) + "]}\noutput:\n  sensors:\n    - {name: tip, body: boom, at: end}\n";
}

// The boom with the payload on the rope, hanging l below the tip.
std::string withPayload(const std::string &analysis)
{
  char text[4096];
  std::snprintf(text, sizeof text, R"(
name: boom-payload
analysis: %s
gravity: [0, -9.81]
bodies:
  - {name: boom, length: 2.0, elements: 8, section: %s}
  - {name: payload, type: rigid, length: 0.2, origin: [%.17g, %.17g], section: {rhoA: %.17g}}
constraints:
  - {type: clamp, body: boom, at: start}
  - {type: angle_drive, body: payload, at: 0.1, angle: 0}
  - {type: elastic_rope, name: hoist, from: boom, from_at: 0.0, pulley: boom, pulley_at: end, to: payload, to_at: 0.1, EA: %.17g, pretension: %.17g}
output:
  sensors:
    - {name: tip, body: boom, at: end}
    - {name: payload, body: payload, at: 0.1}
)",
                analysis.c_str(), kSection.c_str(), Lb - 0.1, -l, m / 0.2, EA,
                m * g);
  return text;
}

// Modes at the static equilibrium of a scene.
std::vector<double> staticModes(const Scene &scene, int count)
{
  return modesAtStaticEquilibrium(scene, count).frequencyHz;
}

// The two roots (Hz) of the chain ground -kb- mb -kr- m.
std::pair<double, double> chainFrequencies(double kb, double mb, double kr)
{
  // det([kb + kr - w mb, -kr; -kr, kr - w m]) = 0, w = omega^2.
  const double a = mb * m, b = -(mb * kr + m * (kb + kr)), c = kb * kr;
  const double disc = std::sqrt(b * b - 4 * a * c);
  const double lo = (-b - disc) / (2 * a), hi = (-b + disc) / (2 * a);
  return {std::sqrt(lo) / (2 * M_PI), std::sqrt(hi) / (2 * M_PI)};
}

// Runs the tracker every `interval` seconds of a dynamic run (the scene's
// tracking.count and tracking.follow when it has a tracking block).
class TrackerMonitor : public Monitor {
public:
  TrackerMonitor(Simulation &sim, double interval) : sim_(sim), interval_(interval) {}
  PetscErrorCode setUp() override
  {
    PetscFunctionBeginUser;
    PetscCall(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
    const TrackingSpec &spec = sim_.scene().tracking;
    if (spec.interval > 0)
      tracker_ = std::make_unique<FrequencyTracker>(sim_.assembler(), spec.count, false, spec.follow, spec.followHz);
    else
      tracker_ = std::make_unique<FrequencyTracker>(sim_.assembler(), 4);
    PetscFunctionReturn(0);
  }
  PetscErrorCode start(const RunState &s, bool) override { return analyze(s); }
  PetscErrorCode afterStep(const RunState &s, std::string *) override { return analyze(s); }
  std::vector<TrackedModes> modes;

private:
  PetscErrorCode analyze(const RunState &s)
  {
    PetscFunctionBeginUser;
    if (s.t < next_ - 1e-9) PetscFunctionReturn(0);
    TrackedModes out;
    PetscCall(tracker_->analyze(s.t, s.q, s.lambda, &out));
    out.shape.clear();
    modes.push_back(out);
    next_ += interval_;
    PetscFunctionReturn(0);
  }
  Simulation &sim_;
  double interval_, next_ = 0;
  std::unique_ptr<FrequencyTracker> tracker_;
};

// A dynamic run of `scene` with its sensor/output history and the tracker
// every `interval` s (both kept for the test to read).
struct TrackedRun {
  TrackedRun(const Scene &scene, double interval) : sim(scene, PETSC_COMM_WORLD, testOptions(0))
  {
    check(sim.setUp());
    sim.addMonitor(std::make_unique<HistoryRecorder>(sim, history));
    auto monitor = std::make_unique<TrackerMonitor>(sim, interval);
    tracker = monitor.get();
    sim.addMonitor(std::move(monitor));
    check(sim.run());
  }
  // The history row at the time of an analysis.
  std::size_t stepAt(double t) const
  {
    std::size_t step = 0;
    while (step < history.time.size() && history.time[step] < t - 1e-12) ++step;
    return step;
  }
  DynamicHistory history;
  Simulation sim;
  TrackerMonitor *tracker = nullptr;
};

} // namespace

TEST(PayloadModes, TwoLowestFrequenciesMatchTheTwoDegreeOfFreedomModel)
{
  // The boom alone: tip stiffness and first frequency.
  const double P = 1000.0;
  const StaticOutcome loaded = runStatic(parseScene(boomAlone("static", P), "boom-alone.yaml"));
  ASSERT_TRUE(loaded.converged);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  double delta = rank == 0 ? -loaded.sensors[0].position.y() : 0;
  MPI_Bcast(&delta, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  const double kb = P / delta;
  Scene alone = parseScene(boomAlone("modal", 0.0) + "modal: {count: 1}\n", "boom-alone.yaml");
  const double f0 = staticModes(alone, 1).at(0), w0 = 2 * M_PI * f0, mb = kb / (w0 * w0);
  // The rope: unstretched length from the pretension m g over root -> tip -> payload.
  const double L0 = (Lb + l) / (1 + m * g / EA), kr = EA / L0;
  const double pendulum = std::sqrt(g / l) / (2 * M_PI);
  const auto [bounce, bending] = chainFrequencies(kb, mb, kr);

  const Scene scene = parseScene(withPayload("modal") + "modal: {count: 4}\n", "boom-payload.yaml");
  const std::vector<double> f = staticModes(scene, 4);
  ASSERT_GE(f.size(), 3u);
  const double e1 = std::abs(f[0] / pendulum - 1), e2 = std::abs(f[1] / bounce - 1), e3 = std::abs(f[2] / bending - 1);
  PetscPrintf(PETSC_COMM_WORLD,
              "  boom alone: k_b = %.6e N/m, f_0 = %.4f Hz, m_b = %.3f kg (%.4f rhoA Lb); rope k_r = %.6e N/m\n"
              "  mode 1 %.6f Hz vs pendulum %.6f Hz (rel. %.1e); mode 2 %.5f Hz vs chain %.5f Hz (rel. %.1e); "
              "mode 3 %.4f Hz vs chain %.4f Hz (rel. %.1e, not asserted)\n",
              kb, f0, mb, mb / (7850 * 6.944e-3 * Lb), kr, f[0], pendulum, e1, f[1], bounce, e2, f[2], bending, e3);
  EXPECT_LT(e1, 1e-2);
  EXPECT_LT(e2, 1e-2);
}

TEST(PayloadModes, TrackedPendulumMatchesTheZeroCrossingsOfTheSwing)
{
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "a few thousand steps of a small model: the tracker on 2 ranks is tested elsewhere";
  // Static start (rope, boom and payload in equilibrium, so that the
  // payload does not bounce on the rope and the tension stays m g: the
  // linearized pendulum frequency is sqrt(T / (m l))), the payload pushed
  // sideways by F = m g a / l, the push removed over 10 ms.
  const double a = 0.05, tEnd = 6.5;
  char push[256];
  std::snprintf(push, sizeof push,
                "loads:\n  - {type: point_force, body: payload, at: 0.1, force: [%.17g, 0], scale: {type: ramp, t0: 0, "
                "t1: 0.01, from: 1, to: 0}}\n",
                m * g * a / l);
  const Scene scene = parseScene(withPayload("dynamic") + push + "dynamic: {t_end: " + std::to_string(tEnd) +
                                     ", dt: 2.0e-3, rho_inf: 0.8, initial: static}\n",
                                 "boom-payload.yaml");
  TrackedRun run(scene, 0.1);
  ASSERT_TRUE(run.sim.summary().completed) << run.sim.summary().failure;
  const DynamicHistory &h = run.history;
  TrackerMonitor *tracker = run.tracker;
  // Zero crossings of the swing (payload x minus tip x).
  std::vector<double> crossings;
  for (std::size_t s = 1; s < h.time.size(); ++s) {
    const double u0 = h.sensors[s - 1][1].position.x() - h.sensors[s - 1][0].position.x();
    const double u1 = h.sensors[s][1].position.x() - h.sensors[s][0].position.x();
    if ((u0 > 0) != (u1 > 0)) crossings.push_back(h.time[s - 1] + (h.time[s] - h.time[s - 1]) * u0 / (u0 - u1));
  }
  ASSERT_GE(crossings.size(), 5u);
  const double swing = 0.5 * (crossings.size() - 1) / (crossings.back() - crossings.front());
  double tracked = 0, lowestMac = 1, spread = 0;
  int notLowest = 0;
  for (const TrackedModes &t : tracker->modes) tracked += t.trackedHz;
  tracked /= tracker->modes.size();
  for (std::size_t k = 1; k < tracker->modes.size(); ++k) lowestMac = std::min(lowestMac, tracker->modes[k].mac);
  for (const TrackedModes &t : tracker->modes) {
    spread = std::max(spread, std::abs(t.trackedHz / tracked - 1));
    notLowest += t.index != 0;
  }
  const double pendulum = std::sqrt(g / l) / (2 * M_PI);
  PetscPrintf(PETSC_COMM_WORLD,
              "  swing: %zu zero crossings, %.6f Hz; tracked (mean of %zu analyses) %.6f Hz (rel. %.1e, spread %.1e, "
              "lowest MAC %.6f); g/l pendulum %.6f Hz; second tracked-list frequency %.4f Hz\n",
              crossings.size(), swing, tracker->modes.size(), tracked, std::abs(tracked / swing - 1), spread, lowestMac,
              pendulum, tracker->modes.back().frequencyHz.at(1));
  EXPECT_EQ(notLowest, 0) << "the tracked mode must stay the pendulum (the lowest)";
  EXPECT_GT(lowestMac, 0.99);
  EXPECT_LT(std::abs(tracked / swing - 1), 1e-3);
}

// Two followed modes at once (tracking.follow): the payload of the boom
// above is hoisted by the winch from l = 1 m to 0.6 m below the tip (an
// acceleration-limited haul of 0.4 m from 0.2 s, static start), the tracker
// following the modes nearest 0.5 Hz (the pendulum) and 8.5 Hz (the payload
// bouncing on rope and boom) every 0.05 s. At every analysis, against the
// independent models of TwoLowestFrequencies... evaluated at the state of
// the analysis: the pendulum sqrt(T / (m l)) / 2 pi (T the rope tension, l
// the hanging length tip to payload; T = m g at rest) and the chain's lower
// root with k_r = EA / L0(t) (L0(t): the unstretched rope length, length -
// stretch, shortened by the winch). Both followed modes continuous (MAC >
// 0.9 between analyses) and within 1 % of their references.
TEST(PayloadModes, PendulumAndBounceFollowedTogetherWhileHoisting)
{
  PetscMPIInt ranks, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (ranks > 1) GTEST_SKIP() << "a small model over 1300 steps: the tracker on 2 ranks is tested elsewhere";
  // The boom alone: tip stiffness and modal mass (as TwoLowestFrequencies...).
  const double P = 1000.0;
  const StaticOutcome loaded = runStatic(parseScene(boomAlone("static", P), "boom-alone.yaml"));
  ASSERT_TRUE(loaded.converged);
  const double kb = P / -loaded.sensors[0].position.y();
  const double f0 = staticModes(parseScene(boomAlone("modal", 0.0) + "modal: {count: 1}\n", "boom-alone.yaml"), 1).at(0);
  const double mb = kb / std::pow(2 * M_PI * f0, 2);

  std::string text = withPayload("dynamic");
  const std::string pretension = "pretension: " + [] {
    char b[64];
    std::snprintf(b, sizeof b, "%.17g", m * g);
    return std::string(b);
  }();
  const std::size_t at = text.find(pretension);
  ASSERT_NE(at, std::string::npos);
  text.insert(at + pretension.size(), ", winch: {type: accel_limited, t0: 0.2, to: -0.4, speed: 0.25, accel: 0.5, jerk: 2.0}");
  const Scene scene = parseScene(text + "dynamic: {t_end: 2.6, dt: 2.0e-3, rho_inf: 0.8, initial: static}\n"
                                        "tracking: {interval: 0.05, count: 4, follow: [0.5, 8.5]}\n",
                                 "boom-payload-hoisted.yaml");
  TrackedRun run(scene, 0.05);
  ASSERT_TRUE(run.sim.summary().completed) << run.sim.summary().failure;
  const DynamicHistory &h = run.history;
  TrackerMonitor *tracker = run.tracker;
  ASSERT_GE(tracker->modes.size(), 40u);
  double worstPendulum = 0, worstBounce = 0, lowestMac = 1, lMin = 1e9, lMax = 0;
  for (const TrackedModes &t : tracker->modes) {
    ASSERT_EQ(t.followed.size(), 2u);
    const std::size_t step = run.stepAt(t.t);
    ASSERT_LT(step, h.time.size());
    ASSERT_NEAR(h.time[step], t.t, 1e-12);
    const std::vector<double> &out = h.outputs[step]; // tension, length, stretch, payout, winch_power
    const double T = out[0], L0 = out[1] - out[2];
    const double l = h.sensors[step][0].position.y() - h.sensors[step][1].position.y();
    lMin = std::min(lMin, l), lMax = std::max(lMax, l);
    const double pendulum = std::sqrt(T / (m * l)) / (2 * M_PI);
    const double bounce = chainFrequencies(kb, mb, EA / L0).first;
    worstPendulum = std::max(worstPendulum, std::abs(t.followed[0].hz / pendulum - 1));
    worstBounce = std::max(worstBounce, std::abs(t.followed[1].hz / bounce - 1));
    if (&t != &tracker->modes.front()) lowestMac = std::min({lowestMac, t.followed[0].mac, t.followed[1].mac});
    EXPECT_EQ(t.trackedHz, t.followed[0].hz); // the first followed mode is /tracking/tracked_hz
  }
  const TrackedModes &first = tracker->modes.front(), &last = tracker->modes.back();
  PetscPrintf(PETSC_COMM_WORLD,
              "  %zu analyses, hanging length %.4f ... %.4f m: pendulum %.5f -> %.5f Hz (worst rel. to sqrt(T/(m l)) "
              "%.1e), bounce %.4f -> %.4f Hz (worst rel. to the chain %.1e); lowest MAC %.6f\n",
              tracker->modes.size(), lMin, lMax, first.followed[0].hz, last.followed[0].hz, worstPendulum,
              first.followed[1].hz, last.followed[1].hz, worstBounce, lowestMac);
  EXPECT_LT(lMin, 0.61); // hoisted by 0.4 m
  EXPECT_GT(last.followed[0].hz, 1.25 * first.followed[0].hz);
  EXPECT_GT(lowestMac, 0.9);
  EXPECT_LT(worstPendulum, 1e-2);
  EXPECT_LT(worstBounce, 1e-2);
}

// A crossing: two pendulums from a rigid ceiling (uncoupled), A hoisted by
// its winch from 1.2 m to 0.6 m, B fixed at 0.9 m; `follow: 2` takes the two
// lowest at t = 0 (A 0.455 Hz, B 0.525 Hz). A's frequency rises through
// B's, so after the crossing the sorted order is B, A; each followed mode
// must keep its pendulum (MAC > 0.9 at every analysis; A's index 0 -> 1,
// B's 1 -> 0) and match sqrt(T / (m l)) / 2 pi of its own pendulum (T its
// rope tension, l its hanging length at the analysis) within 1e-3.
TEST(PayloadModes, FollowedPendulumsKeepTheirIdentityThroughACrossing)
{
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (ranks > 1) GTEST_SKIP() << "a small model over 1300 steps: the tracker on 2 ranks is tested elsewhere";
  const double mp = 100.0;
  const Scene scene = parseScene(R"(
name: two-pendulums
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: ceiling, type: rigid, length: 2.0, section: {rhoA: 1}}
  - {name: a, type: rigid, length: 0.2, origin: [-0.1, -1.2], section: {rhoA: 500}}
  - {name: b, type: rigid, length: 0.2, origin: [1.9, -0.9], section: {rhoA: 500}}
constraints:
  - {type: clamp, body: ceiling, at: start}
  - {type: angle_drive, body: a, at: 0.1, angle: 0}
  - {type: angle_drive, body: b, at: 0.1, angle: 0}
  - {type: elastic_rope, name: rope_a, from: ceiling, from_at: 0.0, to: a, to_at: 0.1, EA: 1.0e7, pretension: 981,
     winch: {type: accel_limited, t0: 0.1, to: -0.6, speed: 0.4, accel: 1.0, jerk: 5.0}}
  - {type: elastic_rope, name: rope_b, from: ceiling, from_at: end, to: b, to_at: 0.1, EA: 1.0e7, pretension: 981}
dynamic: {t_end: 2.3, dt: 2.0e-3, rho_inf: 0.8, initial: static}
tracking: {interval: 0.05, count: 4, follow: 2}
output:
  sensors:
    - {name: top_a, body: ceiling, at: start}
    - {name: a, body: a, at: 0.1}
    - {name: top_b, body: ceiling, at: end}
    - {name: b, body: b, at: 0.1}
)",
                                 "two-pendulums.yaml");
  TrackedRun run(scene, 0.05);
  ASSERT_TRUE(run.sim.summary().completed) << run.sim.summary().failure;
  const DynamicHistory &h = run.history;
  TrackerMonitor *tracker = run.tracker;
  double worst[2] = {0, 0}, lowestMac = 1;
  for (const TrackedModes &t : tracker->modes) {
    ASSERT_EQ(t.followed.size(), 2u);
    const std::size_t step = run.stepAt(t.t);
    ASSERT_LT(step, h.time.size());
    // Outputs: rope_a tension, length, stretch, payout, winch_power; rope_b tension, length, stretch.
    const std::vector<double> &out = h.outputs[step];
    const double T[2] = {out[0], out[5]};
    for (int j = 0; j < 2; ++j) {
      const double l = h.sensors[step][2 * j].position.y() - h.sensors[step][2 * j + 1].position.y();
      const double ref = std::sqrt(T[j] / (mp * l)) / (2 * M_PI);
      worst[j] = std::max(worst[j], std::abs(t.followed[j].hz / ref - 1));
    }
    if (&t != &tracker->modes.front()) lowestMac = std::min({lowestMac, t.followed[0].mac, t.followed[1].mac});
  }
  const TrackedModes &first = tracker->modes.front(), &last = tracker->modes.back();
  PetscPrintf(PETSC_COMM_WORLD,
              "  %zu analyses: A %.5f -> %.5f Hz (index %d -> %d, worst rel. %.1e), B %.5f -> %.5f Hz (index %d -> %d, "
              "worst rel. %.1e); lowest MAC %.6f\n",
              tracker->modes.size(), first.followed[0].hz, last.followed[0].hz, first.followed[0].index,
              last.followed[0].index, worst[0], first.followed[1].hz, last.followed[1].hz, first.followed[1].index,
              last.followed[1].index, worst[1], lowestMac);
  EXPECT_EQ(first.followed[0].index, 0);
  EXPECT_EQ(first.followed[1].index, 1);
  EXPECT_EQ(last.followed[0].index, 1); // crossed: A is now above B
  EXPECT_EQ(last.followed[1].index, 0);
  EXPECT_GT(last.followed[0].hz, last.followed[1].hz);
  EXPECT_GT(lowestMac, 0.9);
  EXPECT_LT(worst[0], 1e-3);
  EXPECT_LT(worst[1], 1e-3);
}
