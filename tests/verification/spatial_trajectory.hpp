// Running a spatial scene from its text and keeping every step (time,
// coordinates, total energy, gathered on every rank), with the helpers the
// spatial verification tests share: numbers written to full precision into
// scene text, and a frequency from zero crossings.
#pragma once

#include "support.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace boomdyn::testing {

struct Trajectory {
  std::vector<double> t, energy;
  std::vector<std::vector<double>> q;
  bool completed = false;
};

class TrajectoryRecorder : public Monitor {
public:
  TrajectoryRecorder(const Model &model, Trajectory &out) : model_(model), out_(out) {}
  PetscErrorCode start(const RunState &s, bool) override { return record(s); }
  PetscErrorCode afterStep(const RunState &s, std::string *) override { return record(s); }

private:
  PetscErrorCode record(const RunState &s)
  {
    PetscFunctionBeginUser;
    const std::vector<double> q = gatherAll(s.q);
    out_.t.push_back(s.t);
    out_.q.emplace_back(q.begin(), q.begin() + model_.numCoordinates());
    out_.energy.push_back(s.energy.kinetic + s.energy.strain + s.energy.potential);
    PetscFunctionReturn(0);
  }
  const Model &model_;
  Trajectory &out_;
};

// The scene `text` (named `file` in messages) run with the test options.
inline Trajectory runTrajectory(const std::string &text, const std::string &file)
{
  const Scene scene = parseScene(text, file);
  Trajectory out;
  Simulation sim(scene, PETSC_COMM_WORLD, testOptions());
  check(sim.setUp());
  sim.addMonitor(std::make_unique<TrajectoryRecorder>(sim.model(), out));
  check(sim.run());
  out.completed = sim.summary().completed;
  return out;
}

// A planar scene and its spatial embedding run with the same options, both
// with full Newton (spatial runs use it by default): the modified iteration
// stops anywhere within the Newton tolerance.
inline void runPlanarAndSpatial(const Scene &planar, const Scene &spatial, const SimulationOptions &options,
                                DynamicHistory &a, DynamicHistory &b)
{
  check(PetscOptionsSetValue(nullptr, "-boom_jacobian_reuse", "0"));
  a = runDynamicWith(planar, PETSC_COMM_WORLD, options);
  b = runDynamicWith(spatial, PETSC_COMM_WORLD, options);
  check(PetscOptionsClearValue(nullptr, "-boom_jacobian_reuse"));
}

// x with 17 significant digits, for scene text.
inline std::string number(double x)
{
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// Frequency (rad/s) of a signal from its zero crossings (linear
// interpolation between steps): pi per half period.
inline double crossingFrequency(const std::vector<double> &t, const std::vector<double> &x)
{
  constexpr double pi = 3.14159265358979323846;
  std::vector<double> crossings;
  for (std::size_t k = 1; k < x.size(); ++k)
    if ((x[k - 1] < 0) != (x[k] < 0)) crossings.push_back(t[k - 1] - x[k - 1] * (t[k] - t[k - 1]) / (x[k] - x[k - 1]));
  EXPECT_GE(crossings.size(), 4u);
  return pi * (crossings.size() - 1) / (crossings.back() - crossings.front());
}

} // namespace boomdyn::testing
