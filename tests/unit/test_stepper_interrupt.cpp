// A stop request (SIGINT, SIGTERM: Simulation's stop function) while a step
// is being cut after Newton failures ends the run before the next attempt,
// at the last accepted step, instead of after all the cuts down to dt_min
// (with dt = 2 s and dt_min = 1e-9 s, up to 31 attempts of max_newton
// iterations each).
#include "support.hpp"

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// The pendulum of tests/bad_model/newton_fails_dt_min.yaml, with room to cut:
// Newton cannot follow half a swing in one 2 s step.
Scene pendulum()
{
  return parseScene(R"(
name: pendulum
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - name: boom
    length: 2
    elements: 4
    section: {EA: 1.0e9, EI: 1.0e6, rhoA: 30}
constraints:
  - {type: pin, name: hinge, body: boom, at: start}
dynamic: {t_end: 2.0, dt: 2.0, max_newton: 5}
)",
                    "pendulum.yaml");
}

} // namespace

TEST(StepperInterrupt, StopBetweenCutsEndsTheRunAtTheLastAcceptedStep)
{
  const Scene scene = pendulum();
  // Without a stop request the first step is cut until Newton converges.
  {
    HandIntegration run(scene, PETSC_COMM_SELF);
    RunSummary summary;
    StepperState state;
    int asked = 0;
    check(integrate(*run.integrator, scene.dynamic, nullptr, &summary, &state, [&] {
      ++asked;
      return false;
    }));
    EXPECT_TRUE(summary.completed) << summary.failure;
    EXPECT_GE(summary.rejected, 4); // 2 s -> 0.125 s at least
    EXPECT_GT(asked, summary.steps); // asked between cuts as well as after steps
  }
  // With one, the run ends before the second attempt of the first step.
  {
    HandIntegration run(scene, PETSC_COMM_SELF);
    RunSummary summary;
    StepperState state;
    check(integrate(*run.integrator, scene.dynamic, nullptr, &summary, &state, [] { return true; }));
    EXPECT_TRUE(summary.interrupted);
    EXPECT_FALSE(summary.completed);
    EXPECT_TRUE(summary.failure.empty()) << summary.failure;
    EXPECT_EQ(summary.rejected, 1);
    EXPECT_EQ(summary.steps, 0);
    EXPECT_EQ(run.integrator->time(), 0.0);
    EXPECT_EQ(state.h, 1.0); // the cut a restart from here continues with
  }
}
