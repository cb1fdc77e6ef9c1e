// TimeFunction: values at known points, exact derivatives against finite
// differences, smoothness of the smooth step, extrapolation of tables.
#include "boomdyn/time_function.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using boomdyn::TimeFunction;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Central differences with step h have truncation error h^2/6 |f'''| (rate)
// and h^2/12 |f''''| (accel) plus round-off ~ eps |f| / h (rate) and
// eps |f| / h^2 (accel). With h = 1e-4 and the functions below (|f| <= 10,
// time scales >= 0.1 s) both stay below the tolerances used.
constexpr double kStep = 1e-4;
constexpr double kRateTol = 1e-5;
constexpr double kAccelTol = 1e-3;

double fdRate(const TimeFunction &f, double t)
{
  return (f.value(t + kStep) - f.value(t - kStep)) / (2 * kStep);
}

double fdAccel(const TimeFunction &f, double t)
{
  return (f.value(t + kStep) - 2 * f.value(t) + f.value(t - kStep)) / (kStep * kStep);
}

// Compares rate and accel with finite differences at n points spread over
// [a, b], skipping points within 2 h of a kink (where f is not smooth and a
// difference quotient straddles two pieces).
void expectDerivativesMatch(const TimeFunction &f, double a, double b, const std::vector<double> &kinks,
                            int n = 397)
{
  int checked = 0;
  for (int i = 0; i <= n; ++i) {
    const double t = a + (b - a) * i / n;
    bool near_kink = false;
    for (double k : kinks)
      near_kink = near_kink || std::abs(t - k) < 2 * kStep;
    if (near_kink)
      continue;
    ++checked;
    EXPECT_NEAR(f.rate(t), fdRate(f, t), kRateTol * (1 + std::abs(f.rate(t)))) << f.describe() << " at t = " << t;
    EXPECT_NEAR(f.accel(t), fdAccel(f, t), kAccelTol * (1 + std::abs(f.accel(t))))
        << f.describe() << " at t = " << t;
  }
  EXPECT_GT(checked, n / 2);
}

} // namespace

TEST(TimeFunction, DefaultIsZero)
{
  const TimeFunction f;
  EXPECT_EQ(f.kind(), TimeFunction::Kind::Constant);
  EXPECT_EQ(f.value(3.0), 0.0);
  EXPECT_EQ(f.rate(3.0), 0.0);
  EXPECT_EQ(f.accel(3.0), 0.0);
}

TEST(TimeFunction, ConstantValues)
{
  const auto f = TimeFunction::constant(2.5);
  EXPECT_EQ(f.kind(), TimeFunction::Kind::Constant);
  for (double t : {-1.0, 0.0, 1e6}) {
    EXPECT_EQ(f.value(t), 2.5);
    EXPECT_EQ(f.rate(t), 0.0);
    EXPECT_EQ(f.accel(t), 0.0);
  }
}

TEST(TimeFunction, RampValuesAndDerivatives)
{
  const auto f = TimeFunction::ramp(1.0, 3.0, 2.0, 6.0);
  EXPECT_EQ(f.kind(), TimeFunction::Kind::Ramp);
  EXPECT_DOUBLE_EQ(f.value(0.0), 2.0);
  EXPECT_DOUBLE_EQ(f.value(1.0), 2.0);
  EXPECT_DOUBLE_EQ(f.value(2.0), 4.0);
  EXPECT_DOUBLE_EQ(f.value(3.0), 6.0);
  EXPECT_DOUBLE_EQ(f.value(10.0), 6.0);
  EXPECT_DOUBLE_EQ(f.rate(2.0), 2.0);
  EXPECT_EQ(f.rate(0.5), 0.0);
  EXPECT_EQ(f.rate(3.5), 0.0);
  EXPECT_EQ(f.accel(2.0), 0.0);
  expectDerivativesMatch(f, -1.0, 5.0, {1.0, 3.0});
}

TEST(TimeFunction, SmoothStepValuesAndDerivatives)
{
  const auto f = TimeFunction::smoothStep(0.5, 2.5, -1.0, 3.0);
  EXPECT_EQ(f.kind(), TimeFunction::Kind::SmoothStep);
  EXPECT_DOUBLE_EQ(f.value(0.0), -1.0);
  EXPECT_DOUBLE_EQ(f.value(0.5), -1.0);
  EXPECT_DOUBLE_EQ(f.value(1.5), 1.0); // h(1/2) = 1/2 by symmetry
  EXPECT_DOUBLE_EQ(f.value(2.5), 3.0);
  EXPECT_DOUBLE_EQ(f.value(9.0), 3.0);
  // h(1/4) = 10/64 - 15/256 + 6/1024 = 0.103515625
  EXPECT_NEAR(f.value(1.0), -1.0 + 4.0 * 0.103515625, 1e-14);
  // Peak rate at the middle: 30/16 * (v1 - v0) / T = 30/16 * 4 / 2
  EXPECT_NEAR(f.rate(1.5), 3.75, 1e-13);
  EXPECT_NEAR(f.accel(1.5), 0.0, 1e-12);
  // Whole range including the ends: the function is C2, so even the
  // differences across t0 and t1 match the exact derivatives.
  expectDerivativesMatch(f, -0.5, 3.5, {});
}

TEST(TimeFunction, SmoothStepIsC2AtBothEnds)
{
  const double t0 = 0.0, t1 = 5.7;
  const auto f = TimeFunction::smoothStep(t0, t1, 0.0, 35.0);
  for (double end : {t0, t1}) {
    for (double eps : {1e-3, 1e-5, 1e-7}) {
      // Value continuous, and rate ~ eps^2, accel ~ eps on both sides.
      EXPECT_NEAR(f.value(end - eps), f.value(end + eps), 1e-6);
      EXPECT_LT(std::abs(f.rate(end - eps)), 30 * 35.0 * eps * eps / (t1 * t1 * t1) * 1.01);
      EXPECT_LT(std::abs(f.rate(end + eps)), 30 * 35.0 * eps * eps / (t1 * t1 * t1) * 1.01);
      EXPECT_LT(std::abs(f.accel(end - eps)), 60 * 35.0 * eps / (t1 * t1 * t1) * 1.01);
      EXPECT_LT(std::abs(f.accel(end + eps)), 60 * 35.0 * eps / (t1 * t1 * t1) * 1.01);
    }
    EXPECT_EQ(f.rate(end), 0.0);
    EXPECT_EQ(f.accel(end), 0.0);
  }
}

TEST(TimeFunction, TableInterpolatesAndExtrapolatesConstant)
{
  const auto f = TimeFunction::table({0.0, 1.0, 3.0, 4.0}, {0.0, 2.0, -2.0, -2.0});
  EXPECT_EQ(f.kind(), TimeFunction::Kind::Table);
  EXPECT_DOUBLE_EQ(f.value(0.5), 1.0);
  EXPECT_DOUBLE_EQ(f.value(1.0), 2.0);
  EXPECT_DOUBLE_EQ(f.value(2.0), 0.0);
  EXPECT_DOUBLE_EQ(f.value(3.5), -2.0);
  EXPECT_DOUBLE_EQ(f.rate(0.5), 2.0);
  EXPECT_DOUBLE_EQ(f.rate(2.0), -2.0);
  EXPECT_DOUBLE_EQ(f.rate(3.5), 0.0);
  // Constant extrapolation on both sides, with zero derivatives.
  EXPECT_DOUBLE_EQ(f.value(-10.0), 0.0);
  EXPECT_DOUBLE_EQ(f.value(100.0), -2.0);
  EXPECT_EQ(f.rate(-10.0), 0.0);
  EXPECT_EQ(f.rate(100.0), 0.0);
  for (double t : {-1.0, 0.5, 2.0, 5.0})
    EXPECT_EQ(f.accel(t), 0.0);
  expectDerivativesMatch(f, -1.0, 5.0, {0.0, 1.0, 3.0, 4.0});
}

TEST(TimeFunction, SineValuesAndDerivatives)
{
  // 2 + 3 sin(2 pi 0.5 (t - 1) + pi/6) for t >= 1.
  const auto f = TimeFunction::sine(3.0, 0.5, kPi / 6, 2.0, 1.0);
  EXPECT_EQ(f.kind(), TimeFunction::Kind::Sine);
  EXPECT_NEAR(f.value(1.0), 2.0 + 1.5, 1e-14);
  EXPECT_NEAR(f.value(2.0), 2.0 + 3.0 * std::sin(kPi + kPi / 6), 1e-14);
  EXPECT_NEAR(f.rate(1.0), 3.0 * kPi * std::cos(kPi / 6), 1e-13);
  EXPECT_NEAR(f.accel(1.0), -3.0 * kPi * kPi * std::sin(kPi / 6), 1e-13);
  // Before t0: frozen at the t0 value.
  EXPECT_NEAR(f.value(0.0), 3.5, 1e-14);
  EXPECT_EQ(f.rate(0.5), 0.0);
  EXPECT_EQ(f.accel(0.5), 0.0);
  expectDerivativesMatch(f, -1.0, 6.0, {1.0});
}

TEST(TimeFunction, SineWithZeroFrequencyIsConstant)
{
  const auto f = TimeFunction::sine(2.0, 0.0, kPi / 2, 1.0);
  EXPECT_NEAR(f.value(7.0), 3.0, 1e-14);
  EXPECT_EQ(f.rate(7.0), 0.0);
  EXPECT_EQ(f.accel(7.0), 0.0);
}

TEST(TimeFunction, ScaledMultipliesValuesAndDerivatives)
{
  const double factor = kPi / 180;
  const std::vector<TimeFunction> functions{
      TimeFunction::constant(10.0), TimeFunction::ramp(0.0, 2.0, 5.0, 25.0),
      TimeFunction::smoothStep(0.0, 5.7, 0.0, 35.0), TimeFunction::table({0.0, 1.0, 2.0}, {1.0, 4.0, 2.0}),
      TimeFunction::sine(10.0, 0.7, 0.3, 5.0, 0.2)};
  for (const auto &f : functions) {
    const auto g = f.scaled(factor);
    EXPECT_EQ(g.kind(), f.kind());
    for (double t : {-0.5, 0.1, 0.5, 1.3, 2.7, 4.0, 8.0}) {
      EXPECT_NEAR(g.value(t), factor * f.value(t), 1e-14) << f.describe();
      EXPECT_NEAR(g.rate(t), factor * f.rate(t), 1e-14) << f.describe();
      EXPECT_NEAR(g.accel(t), factor * f.accel(t), 1e-13) << f.describe();
    }
  }
}

TEST(TimeFunction, DescribeIsOneLineAndNamesTheKind)
{
  const std::vector<std::pair<TimeFunction, std::string>> cases{
      {TimeFunction::constant(1.5), "constant"},
      {TimeFunction::ramp(0, 1, 0, 2), "ramp"},
      {TimeFunction::smoothStep(0, 5.7, 0, 35), "smooth step"},
      {TimeFunction::table({0, 1}, {0, 1}), "table"},
      {TimeFunction::sine(1, 2, 0, 0), "sine"}};
  for (const auto &[f, word] : cases) {
    const std::string text = f.describe();
    EXPECT_NE(text.find(word), std::string::npos) << text;
    EXPECT_EQ(text.find('\n'), std::string::npos) << text;
  }
  EXPECT_NE(TimeFunction::smoothStep(0, 5.7, 0, 35).describe().find("5.7"), std::string::npos);
}

TEST(TimeFunction, InvalidParametersThrow)
{
  EXPECT_THROW(TimeFunction::ramp(1.0, 1.0, 0, 1), std::invalid_argument);
  EXPECT_THROW(TimeFunction::smoothStep(2.0, 1.0, 0, 1), std::invalid_argument);
  EXPECT_THROW(TimeFunction::table({0.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(TimeFunction::table({0.0, 1.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(TimeFunction::table({0.0, 0.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(TimeFunction::sine(1.0, -1.0, 0, 0), std::invalid_argument);
}

// Velocity breakpoints (kink restart, docs/model.md §1.6 and §4.8): where
// the rate jumps, and only there.
TEST(TimeFunction, VelocityBreakpointsAreWhereTheRateJumps)
{
  std::vector<double> b;
  TimeFunction::ramp(2.0, 7.0, 0.0, 1.25).velocityBreakpoints(b);
  EXPECT_EQ(b, (std::vector<double>{2.0, 7.0}));
  b.clear();
  TimeFunction::ramp(2.0, 7.0, 1.0, 1.0).velocityBreakpoints(b); // flat: no kink
  EXPECT_TRUE(b.empty());
  b.clear();
  // Knot 1 is collinear (no kink), the first knot starts a slope, the last ends one.
  TimeFunction::table({0.0, 0.5, 1.0, 1.5, 2.0}, {0.0, 1.0, 2.0, 2.0, 0.0}).scaled(0.1).velocityBreakpoints(b);
  EXPECT_EQ(b, (std::vector<double>{0.0, 1.0, 1.5, 2.0}));
  b.clear();
  TimeFunction::table({0.0, 1.0, 2.0}, {3.0, 3.0, 4.0}).velocityBreakpoints(b); // flat start: first knot no kink
  EXPECT_EQ(b, (std::vector<double>{1.0, 2.0}));
  b.clear();
  TimeFunction::sine(1.0, 2.0, 0.0, 0.0, 0.3).velocityBreakpoints(b); // starts with rate 4 pi
  EXPECT_EQ(b, (std::vector<double>{0.3}));
  b.clear();
  TimeFunction::smoothStep(0.0, 1.0, 0.0, 1.0).velocityBreakpoints(b);
  TimeFunction::accelLimited(0.0, 0.0, 1.0, 0.5, 1.0).velocityBreakpoints(b);
  TimeFunction::constant(2.0).velocityBreakpoints(b);
  EXPECT_TRUE(b.empty()) << "smooth step, accel-limited move and constant have no kinks";
  // Every reported kink is a jump of the rate: left and right derivatives differ.
  const TimeFunction f = TimeFunction::table({0.0, 0.5, 1.0, 1.5}, {0.0, 12.0, 12.0, 0.0});
  b.clear();
  f.velocityBreakpoints(b);
  ASSERT_EQ(b, (std::vector<double>{0.0, 0.5, 1.0, 1.5}));
  for (double t : b) EXPECT_NE(f.rate(t - 1e-9), f.rate(t)) << t;
}

namespace {

// The extremes of f over [ta, tb] by dense sampling (2e5 points and both
// ends): an independent reference for bounds(), which must enclose every
// sample and lie within the sampling's resolution of the extremes.
void expectBoundsMatchSampling(const TimeFunction &f, double ta, double tb, const char *what)
{
  double lo, hi;
  f.bounds(ta, tb, &lo, &hi);
  double sampledLo = f.value(ta), sampledHi = sampledLo, worstSlope = 0;
  const int n = 200000;
  for (int k = 0; k <= n; ++k) {
    const double t = ta + (tb - ta) * k / n;
    sampledLo = std::min(sampledLo, f.value(t)), sampledHi = std::max(sampledHi, f.value(t));
    worstSlope = std::max(worstSlope, std::abs(f.rate(t)));
  }
  // Between samples an extreme can hide by at most |f'| dt (f' = 0 there: far less).
  const double resolution = worstSlope * (tb - ta) / n + 1e-12;
  EXPECT_LE(lo, sampledLo + 1e-12) << what;
  EXPECT_GE(hi, sampledHi - 1e-12) << what;
  EXPECT_GE(lo, sampledLo - resolution) << what;
  EXPECT_LE(hi, sampledHi + resolution) << what;
}

} // namespace

// bounds(): the least and largest value over an interval, in closed form,
// against dense sampling, for every kind; the sine and the table have their
// extremes inside the interval, where the end points do not see them.
TEST(TimeFunction, BoundsAreTheExtremesOverTheInterval)
{
  expectBoundsMatchSampling(TimeFunction::constant(-2.5), 0, 3, "constant");
  expectBoundsMatchSampling(TimeFunction::ramp(0.2, 1.2, 1.0, -4.0), 0, 3, "ramp");
  expectBoundsMatchSampling(TimeFunction::ramp(0.2, 1.2, 1.0, -4.0), 0.5, 0.7, "ramp, inside");
  expectBoundsMatchSampling(TimeFunction::smoothStep(0.1, 0.9, 0.0, 2.0), 0, 1, "smooth step");
  expectBoundsMatchSampling(TimeFunction::accelLimited(0.1, 0.0, -1.0, 0.5, 2.0, 10.0), 0, 5, "accel-limited");
  expectBoundsMatchSampling(TimeFunction::table({0, 0.5, 1, 2}, {0, -1.5, 0.3, 0.1}), 0, 2.5, "table");
  expectBoundsMatchSampling(TimeFunction::table({0, 0.5, 1, 2}, {0, -1.5, 0.3, 0.1}), 0.6, 1.7, "table, inside");
  expectBoundsMatchSampling(TimeFunction::sine(2.0, 1.0, 0.0, 0.0), 0, 1, "sine, one period");
  expectBoundsMatchSampling(TimeFunction::sine(2.0, 1.0, 0.3, -0.5, 0.2), 0, 0.6, "sine, late start, part of a period");
  expectBoundsMatchSampling(TimeFunction::sine(-1.5, 3.0, 1.0, 0.0), 0.1, 0.15, "sine, no crest inside");
  expectBoundsMatchSampling(TimeFunction::sine(1.0, 50.0, 0.0, 0.0), 0, 100, "sine, 5000 periods");
  // The sine's trough hauls in 2 m at t = 0.75 s, while both ends are 0.
  double lo, hi;
  TimeFunction::sine(2.0, 1.0, 0.0, 0.0).bounds(0, 1, &lo, &hi);
  EXPECT_DOUBLE_EQ(lo, -2.0);
  EXPECT_DOUBLE_EQ(hi, 2.0);
  TimeFunction::table({0, 0.5, 1}, {0, -1.5, 0}).bounds(0, 1, &lo, &hi);
  EXPECT_EQ(lo, -1.5);
  EXPECT_EQ(hi, 0.0);
}

// rateBefore(): the left derivative, against a backward difference, and
// equal to rate() wherever the rate does not jump.
TEST(TimeFunction, RateBeforeIsTheLeftDerivative)
{
  const TimeFunction ramp = TimeFunction::ramp(0.2, 1.2, 1.0, -4.0), table = TimeFunction::table({0, 0.5, 1}, {0, -1.5, 0}),
                     sine = TimeFunction::sine(2.0, 1.0, 0.5, 0.0, 0.1);
  const double h = 1e-7;
  for (const TimeFunction *f : {&ramp, &table, &sine})
    for (double t : {0.0, 0.1, 0.2, 0.35, 0.5, 0.8, 1.0, 1.2, 1.5}) {
      const double backward = (f->value(t) - f->value(t - h)) / h;
      EXPECT_NEAR(f->rateBefore(t), backward, 1e-5 * (1 + std::abs(backward))) << f->describe() << " at t = " << t;
    }
  EXPECT_EQ(ramp.rateBefore(1.2), -5.0); // the ramp's end: the slope of the segment that ends there
  EXPECT_EQ(ramp.rate(1.2), 0.0);
  EXPECT_EQ(ramp.rateBefore(0.2), 0.0);
  EXPECT_EQ(ramp.rate(0.2), -5.0);
  EXPECT_EQ(ramp.rateBefore(0.7), ramp.rate(0.7));
  EXPECT_EQ(table.rateBefore(0.5), -3.0);
  EXPECT_EQ(table.rate(0.5), 3.0);
}
