// The accel-limited move (TimeFunction::accelLimited): value, rate and
// acceleration against hand-computed closed forms (1e-10) for the
// trapezoidal and triangular rate profiles with unlimited jerk, and for the
// S-curve with limited jerk with and without reaching the acceleration
// limit; derivative consistency against central differences; scaling;
// invalid parameters.
#include "boomdyn/time_function.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

using boomdyn::TimeFunction;

namespace {

void expectState(const TimeFunction &f, double t, double x, double v, double a)
{
  EXPECT_NEAR(f.value(t), x, 1e-10) << "value at t = " << t;
  EXPECT_NEAR(f.rate(t), v, 1e-10) << "rate at t = " << t;
  EXPECT_NEAR(f.accel(t), a, 1e-10) << "accel at t = " << t;
}

} // namespace

TEST(AccelLimited, TrapezoidalRateWithUnlimitedJerk)
{
  // 1 -> 2 from t0 = 0.5, speed 0.5, accel 1: 0.5 s speeding up (0.125),
  // 1.5 s cruising (0.75), 0.5 s slowing down; ends at 3.0 s.
  const TimeFunction f = TimeFunction::accelLimited(0.5, 1.0, 2.0, 0.5, 1.0);
  EXPECT_NEAR(f.endTime(), 3.0, 1e-14);
  expectState(f, 0.2, 1.0, 0.0, 0.0);
  expectState(f, 0.75, 1.03125, 0.25, 1.0);
  expectState(f, 0.9, 1.08, 0.4, 1.0);
  expectState(f, 1.5, 1.375, 0.5, 0.0);
  expectState(f, 2.9, 1.995, 0.1, -1.0);
  expectState(f, 3.5, 2.0, 0.0, 0.0);
}

TEST(AccelLimited, TriangularRateWhenTooShortToReachSpeed)
{
  // 0 -> -0.5, speed 10 never reached: peak rate sqrt(accel d) = 1 at t = 0.5.
  const TimeFunction f = TimeFunction::accelLimited(0.0, 0.0, -0.5, 10.0, 2.0);
  EXPECT_NEAR(f.endTime(), 1.0, 1e-14);
  expectState(f, 0.25, -0.0625, -0.5, -2.0);
  // At the peak (t = 0.5) the acceleration jumps from -2 to +2: the slow-down side is used.
  expectState(f, 0.5, -0.25, -1.0, 2.0);
  expectState(f, 0.75, -0.4375, -0.5, 2.0);
}

TEST(AccelLimited, SCurveWithLimitedJerk)
{
  // 0 -> 10, speed 2, accel 1, jerk 2: the acceleration rises in 0.5 s,
  // holds 1.5 s, falls in 0.5 s (speed-up 2.5 s covering 2.5), cruise
  // 2.5 s, slow-down 2.5 s; ends at 7.5 s. Values by integrating the
  // acceleration by hand.
  const TimeFunction f = TimeFunction::accelLimited(0.0, 0.0, 10.0, 2.0, 1.0, 2.0);
  EXPECT_NEAR(f.endTime(), 7.5, 1e-14);
  expectState(f, 0.3, 0.009, 0.09, 0.6);
  expectState(f, 1.0, 0.25 / 6.0 + 0.25, 0.75, 1.0);
  expectState(f, 2.3, 2.5 - (0.4 - 0.016 / 6.0), 1.96, 0.4);
  expectState(f, 5.0, 7.5, 2.0, 0.0);
  expectState(f, 7.2, 10.0 - 0.009, 0.09, -0.6);
  // Short S-curve (accel 1 not reached): 0 -> 0.032 with jerk 2 peaks at
  // rate 0.08 and acceleration 0.4 after 0.2 s; ends at 0.8 s.
  const TimeFunction g = TimeFunction::accelLimited(0.0, 0.0, 0.032, 1.0, 1.0, 2.0);
  EXPECT_NEAR(g.endTime(), 0.8, 1e-14);
  expectState(g, 0.1, 0.002 / 6.0, 0.01, 0.2);
  expectState(g, 0.4, 0.016, 0.08, 0.0);
  // Short with the acceleration limit reached: vp Ta = d, both ends at rest.
  const TimeFunction h = TimeFunction::accelLimited(1.0, 0.0, 1.0, 10.0, 1.0, 2.0);
  const double vp = 0.5 * (-0.5 + std::sqrt(0.25 + 4.0)), Ta = vp + 0.5;
  EXPECT_NEAR(h.endTime(), 1.0 + 2.0 * Ta, 1e-12);
  expectState(h, 1.0 + Ta, 0.5, vp, 0.0);
  expectState(h, h.endTime(), 1.0, 0.0, 0.0);
}

TEST(AccelLimited, DerivativesMatchDifferencesAndLimitsHold)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double jerk : {0.0, 3.0}) {
    const TimeFunction f = TimeFunction::accelLimited(0.2, -1.0, 2.0, 1.5, 2.0, jerk);
    const double h = 1e-5;
    for (int k = 0; k < 200; ++k) {
      const double t = 0.1 + u(rng) * (f.endTime() + 0.2);
      EXPECT_NEAR(f.rate(t), (f.value(t + h) - f.value(t - h)) / (2 * h), 1e-6) << "t = " << t;
      EXPECT_LE(std::abs(f.rate(t)), 1.5 + 1e-12);
      EXPECT_LE(std::abs(f.accel(t)), 2.0 + 1e-12);
      if (jerk > 0) // continuous acceleration: its differences follow the jerk
        EXPECT_NEAR(f.accel(t), (f.rate(t + h) - f.rate(t - h)) / (2 * h), 1e-4) << "t = " << t;
    }
  }
}

TEST(AccelLimited, ScaledAndDescribed)
{
  const TimeFunction f = TimeFunction::accelLimited(0.0, 0.0, 1.0, 0.5, 1.0).scaled(-2.0);
  expectState(f, 0.25, -0.0625, -0.5, -2.0);
  EXPECT_NEAR(f.value(10.0), -2.0, 1e-14);
  EXPECT_NE(f.describe().find("accel-limited move"), std::string::npos) << f.describe();
  const TimeFunction still = TimeFunction::accelLimited(0.0, 3.0, 3.0, 1.0, 1.0);
  expectState(still, 0.5, 3.0, 0.0, 0.0);
}

TEST(AccelLimited, InvalidParametersThrow)
{
  EXPECT_THROW(TimeFunction::accelLimited(0, 0, 1, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(TimeFunction::accelLimited(0, 0, 1, 1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(TimeFunction::accelLimited(0, 0, 1, 1.0, 1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(TimeFunction::accelLimited(0, 0, INFINITY, 1.0, 1.0), std::invalid_argument);
}

// Acceleration breakpoints (docs/model.md §1.6): where f'' jumps and f' does
// not. The trapezoid above: t0, the end of the speed-up, the start of the
// slow-down, the end; the triangle: three (no cruise); an S-curve and a
// smooth step: none; a sine that starts with f'' != 0: its t0. At each
// breakpoint accel() is the right limit even where (t_k - t0) rounds below
// the phase length (t0 = 0.7, phase 0.2: 0.7 + 0.2 - 0.7 < 0.2).
TEST(AccelLimited, AccelerationBreakpointsAndRightLimits)
{
  std::vector<double> b;
  TimeFunction::accelLimited(0.5, 1.0, 2.0, 0.5, 1.0).accelerationBreakpoints(b);
  ASSERT_EQ(b.size(), 4u);
  EXPECT_DOUBLE_EQ(b[0], 0.5);
  EXPECT_DOUBLE_EQ(b[1], 1.0);
  EXPECT_DOUBLE_EQ(b[2], 2.5);
  EXPECT_DOUBLE_EQ(b[3], 3.0);
  b.clear();
  const TimeFunction triangle = TimeFunction::accelLimited(0.0, 0.0, 0.25, 1.0, 1.0); // peak speed 0.5 at 0.5 s
  triangle.accelerationBreakpoints(b);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_NEAR(b[1], 0.5, 1e-14);
  EXPECT_EQ(triangle.accel(b[1]), -1.0) << "right limit at the turn";
  b.clear();
  TimeFunction::accelLimited(0.0, 0.0, 1.0, 0.5, 1.0, 4.0).accelerationBreakpoints(b);
  TimeFunction::smoothStep(0.0, 1.0, 0.0, 1.0).accelerationBreakpoints(b);
  TimeFunction::sine(1.0, 2.0, 0.0, 0.0, 0.3).accelerationBreakpoints(b); // f''(t0) = 0
  EXPECT_TRUE(b.empty());
  TimeFunction::sine(1.0, 2.0, M_PI / 2, 0.0, 0.3).accelerationBreakpoints(b);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_DOUBLE_EQ(b[0], 0.3);
  b.clear();
  // Right limits where the subtraction rounds down: speed-up of 0.2 s from t0 = 0.7.
  const TimeFunction f = TimeFunction::accelLimited(0.7, 0.0, 1.0, 0.2, 1.0);
  f.accelerationBreakpoints(b);
  ASSERT_EQ(b.size(), 4u);
  ASSERT_LT(b[1] - 0.7, 0.2) << "the case this checks: (t0 + Ta) - t0 rounds below Ta";
  EXPECT_EQ(f.accel(b[0]), 1.0);
  EXPECT_EQ(f.accel(b[1]), 0.0);
  EXPECT_EQ(f.accel(b[2]), -1.0);
  EXPECT_EQ(f.accel(b[3]), 0.0);
  EXPECT_EQ(f.accel(std::nextafter(b[1], 0.0)), 1.0);
  EXPECT_EQ(f.accel(std::nextafter(b[2], 0.0)), 0.0);
}
