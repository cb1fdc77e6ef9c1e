// The periodic schedules of a run (include/boomdyn/schedule.hpp): the usual
// intervals give the times the schedule always gave (interval added to
// interval, so results do not move), and intervals far below the step or
// below the resolution of t end in bounded work (they spun forever, issue 17).
#include "boomdyn/schedule.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

using namespace boomdyn;

TEST(Schedule, UsualIntervalsAddIntervalByInterval)
{
  double next = 0.01, reference = 0.01;
  for (int step = 1; step <= 2000; ++step) {
    const double t = step * 1e-3, slack = 1e-12;
    if (t < next - slack) continue;
    next = nextScheduledTime(next, 0.01, t, slack);
    while (reference <= t + slack) reference += 0.01; // the loop the monitors had
    ASSERT_EQ(next, reference) << "at t = " << t;
  }
}

TEST(Schedule, TinyIntervalsFireAtEveryStepInBoundedTime)
{
  const auto start = std::chrono::steady_clock::now();
  for (double interval : {1e-20, 1e-90, 1e-300, 4.9e-324}) {
    double next = interval;
    for (int step = 1; step <= 1000; ++step) {
      const double t = step * 1e-3;
      ASSERT_GE(t, next - 1e-12) << "interval " << interval << ": the schedule must fire at every step";
      next = nextScheduledTime(next, interval, t, 1e-12);
      ASSERT_GT(next, t + 1e-12);
      ASSERT_TRUE(std::isfinite(next));
    }
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

TEST(Schedule, LargeGapsJumpInOneStep)
{
  // 1e6 intervals behind (a restart much later, a tiny interval with a long
  // step): one division instead of 1e6 additions; the result is a time of the
  // schedule after t.
  const double next = nextScheduledTime(0.0, 1e-6, 1.0, 0.0);
  EXPECT_GT(next, 1.0);
  EXPECT_LE(next, 1.0 + 1e-6 * (1 + 1e-9));
}
