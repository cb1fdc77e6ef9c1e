// Scalar functions of time with exact first and second derivatives, shared by
// loads and drives (driving constraints need f, f' and f'' for C_t and C_tt).
#pragma once

#include <string>
#include <vector>

namespace boomdyn {

class TimeFunction {
public:
  enum class Kind { Constant, Ramp, SmoothStep, Table, Sine, AccelLimited };

  TimeFunction() = default; // constant 0

  static TimeFunction constant(double value);
  // Linear from (t0, v0) to (t1, v1); constant before and after.
  static TimeFunction ramp(double t0, double t1, double v0, double v1);
  // Quintic 10s^3 - 15s^4 + 6s^5 from (t0, v0) to (t1, v1): C2, so drives
  // built on it start and stop without an acceleration jump.
  static TimeFunction smoothStep(double t0, double t1, double v0, double v1);
  // Piecewise linear through (t_k, v_k), t strictly increasing; constant
  // outside. f'' is zero between knots (the kinks carry no impulse here).
  static TimeFunction table(std::vector<double> t, std::vector<double> v);
  // offset + amplitude sin(2 pi frequency (t - t0) + phase) for t >= t0, offset + amplitude sin(phase) before.
  static TimeFunction sine(double amplitude, double frequency, double phase, double offset, double t0 = 0.0);

  // A point-to-point move from `from` (until t0) to `to` whose rate rises
  // from 0 with at most `accel`, cruises at most at `speed` and falls back
  // to 0 with at most `accel`: a trapezoidal rate profile (or triangular
  // when the distance is too short to reach `speed`). With jerk > 0 the
  // acceleration itself rises and falls at most at that rate (S-curve: f''
  // continuous); jerk = 0 means unlimited (f'' jumps between 0 and
  // +-accel). speed, accel > 0, jerk >= 0 (throws std::invalid_argument
  // otherwise). endTime() tells when it arrives.
  static TimeFunction accelLimited(double t0, double from, double to, double speed, double accel, double jerk = 0.0);
  // The end of a ramp, smooth step or accel-limited move (t0 for the others).
  double endTime() const { return t1_; }

  // Times at which the rate jumps (ramp start and end, table knots where
  // the slope changes, a sine's start with nonzero rate), appended to out.
  // The time stepper lands a step on each and restarts there (velocity
  // projection and consistent accelerations, docs/model.md §4.8). Smooth
  // steps and accel-limited moves have a continuous rate: none.
  void velocityBreakpoints(std::vector<double> &out) const;
  // Times at which the rate is continuous but f'' jumps (an accel-limited
  // move without jerk limit: the start and end of each speed change; a
  // sine that starts with nonzero f''), appended to out. The time stepper
  // lands on these too and restarts with consistent accelerations
  // (docs/model.md §4.8); jerk jumps (S-curves, smooth steps) are not
  // breakpoints.
  void accelerationBreakpoints(std::vector<double> &out) const;

  double value(double t) const;
  double rate(double t) const;  // df/dt
  double accel(double t) const; // d2f/dt2
  // df/dt from the left: the rate of the segment that ends at t (rate() is
  // the right derivative). Differs from rate() only where the rate jumps
  // (velocityBreakpoints()): the power of a load or winch over a step that
  // lands on such a time is that of the step's own segment.
  double rateBefore(double t) const;
  // The smallest and largest value over [ta, tb] (ta <= tb), in closed form
  // for every kind: ramps, smooth steps and accel-limited moves are
  // monotone, tables take their extremes at knots, a sine at its crests.
  void bounds(double ta, double tb, double *lo, double *hi) const;
  Kind kind() const { return kind_; }
  std::string describe() const;

  // The same function with every value multiplied by factor (derivatives
  // follow); used to turn angles given in degrees into radians.
  TimeFunction scaled(double factor) const;

private:
  Kind kind_ = Kind::Constant;
  double t0_ = 0, t1_ = 0, v0_ = 0, v1_ = 0;
  double amplitude_ = 0, frequency_ = 0, phase_ = 0;
  // AccelLimited: the move's shape on its distance (>= 0), times amplitude_ (+-1, scaled).
  struct Move {
    double peakSpeed = 0, peakAccel = 0, jerk = 0; // reached values; jerk 0: unlimited
    double accelTime = 0, jerkTime = 0;            // length of the speed-up phase and of its jerk parts
    double distance = 0;                           // |to - from|
  } move_;
  // Position, rate and acceleration along the move at time t (from t0 on).
  void moveState(double t, double out[3]) const;
  // The speed-up phase (0 <= tau <= accelTime): distance, rate, acceleration.
  void speedUp(double tau, double out[3]) const;
  std::vector<double> times_, values_;
};

} // namespace boomdyn
