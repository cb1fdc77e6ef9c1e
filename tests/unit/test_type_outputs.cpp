// State-derived output channels and the generic event log of the types
// (output_channel.hpp, type_event.hpp), on a rigid body in free fall: a
// channel that reads the height and one that reads the fall speed from the
// watched coordinates, and an event source that reports when the body's
// centre passes a level, against y(t) = y0 - g t^2 / 2.
#include "support.hpp"

#include "boomdyn/model_builder.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

TEST(TypeOutputs, StateChannelsAndEventsOfAFallingBody)
{
  const double g = 9.81, y0 = 1.0, level = 0.8, dt = 0.01;
  const Scene scene = parseScene(R"(
name: free-fall
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: block, type: rigid, length: 0.5, origin: [-0.25, 1.0], section: {rhoA: 20}}
dynamic: {t_end: 0.3, dt: 1.0e-2, rho_inf: 0.8}
)",
                                 "free-fall.yaml");
  Simulation sim(scene, PETSC_COMM_WORLD, testOptions());
  // What a type's builder does (ModelBuilder); here added to the built Model
  // before setUp, which gathers the watched coordinates.
  ModelBuilder b(const_cast<Model &>(sim.model()));
  const PetscInt y = sim.model().bodies()[0]->firstCoordinate() + 1;
  b.addOutputChannel(OutputChannel::ofState("fall", "block", "height", "m", {y},
                                            [](const double *q, const double *) { return q[0]; }));
  b.addOutputChannel(OutputChannel::ofState("fall", "block", "speed", "m/s", {y},
                                            [](const double *, const double *v) { return -v[0]; }));
  auto below = std::make_shared<bool>(false);
  auto previous = std::make_shared<double>(0.0);
  EventSource source{"block", {"below", "above"}, {y}, nullptr};
  source.detect = [=](double t, double h, const double *q, const double *, bool first, std::vector<TypeEvent> &out) {
    const bool now = q[0] < level;
    if (!first && now != *below) // linear interpolation of the crossing inside the step
      out.push_back({t - h * (q[0] - level) / (q[0] - *previous), "block", now ? "below" : "above", now ? -1 : 1});
    *below = now, *previous = q[0];
  };
  b.addEventSource(source);

  DynamicHistory h;
  check(sim.setUp());
  sim.addMonitor(std::make_unique<HistoryRecorder>(sim, h));
  auto monitor = std::make_unique<TypeEventsOutput>(sim, nullptr, true);
  const TypeEventsOutput &events = *monitor;
  sim.addMonitor(std::move(monitor));
  check(sim.run());
  ASSERT_TRUE(sim.summary().completed);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return; // the channels and events live on rank 0
  ASSERT_EQ(h.outputs.size(), h.time.size());
  double worst = 0;
  for (std::size_t k = 0; k < h.time.size(); ++k) {
    const double t = h.time[k];
    ASSERT_EQ(h.outputs[k].size(), 2u);
    // Constant gravity: generalized-alpha integrates the parabola exactly.
    worst = std::max({worst, std::abs(h.outputs[k][0] - (y0 - 0.5 * g * t * t)), std::abs(h.outputs[k][1] - g * t)});
  }
  EXPECT_LT(worst, 1e-10);
  ASSERT_EQ(events.events().size(), 1u);
  const TypeEvent &e = events.events()[0];
  EXPECT_EQ(e.component, "block");
  EXPECT_EQ(e.kind, "below");
  EXPECT_EQ(e.direction, -1);
  // Linear interpolation of a parabola over one step: error below g h^2 / 8 / (g t) in time.
  const double exact = std::sqrt(2 * (y0 - level) / g);
  EXPECT_NEAR(e.t, exact, dt * dt / (8 * exact));
  EXPECT_GT(e.t, exact - dt); // and it falls into the step that crossed
}
