// TimeFunction: closed-form value, rate and acceleration of each kind.
//
// Storage per kind (members of the header):
//   Constant:   v0_ = value
//   Ramp:       (t0_, v0_) -> (t1_, v1_)
//   SmoothStep: (t0_, v0_) -> (t1_, v1_)
//   Table:      times_, values_
//   Sine:       v0_ = offset, amplitude_, frequency_ (Hz), phase_ (rad), t0_
//   AccelLimited: (t0_, v0_) -> (t1_, v1_), amplitude_ = +-1 (direction,
//               times the factor of scaled()), move_ its shape on |v1 - v0|
#include "boomdyn/time_function.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace boomdyn {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Quintic step h(s) = 10 s^3 - 15 s^4 + 6 s^5 on s in [0, 1] and its first
// two derivatives; h' and h'' vanish at both ends, which makes it C2.
double stepShape(double s) { return s * s * s * (10.0 + s * (-15.0 + 6.0 * s)); }
double stepShapeRate(double s) { return 30.0 * s * s * (1.0 - s) * (1.0 - s); }
double stepShapeAccel(double s) { return 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s); }

// Compact number formatting for describe(): 6 significant digits.
std::string fmt(double x)
{
  std::ostringstream out;
  out.precision(6);
  out << x;
  return out.str();
}

} // namespace

TimeFunction TimeFunction::constant(double value)
{
  TimeFunction f;
  f.kind_ = Kind::Constant;
  f.v0_ = value;
  return f;
}

TimeFunction TimeFunction::ramp(double t0, double t1, double v0, double v1)
{
  // A zero-length ramp would be a jump with an infinite rate.
  if (!(t1 > t0))
    throw std::invalid_argument("TimeFunction::ramp: t1 must be > t0");
  TimeFunction f;
  f.kind_ = Kind::Ramp;
  f.t0_ = t0;
  f.t1_ = t1;
  f.v0_ = v0;
  f.v1_ = v1;
  return f;
}

TimeFunction TimeFunction::smoothStep(double t0, double t1, double v0, double v1)
{
  if (!(t1 > t0))
    throw std::invalid_argument("TimeFunction::smoothStep: t1 must be > t0");
  TimeFunction f = ramp(t0, t1, v0, v1);
  f.kind_ = Kind::SmoothStep;
  return f;
}

TimeFunction TimeFunction::table(std::vector<double> t, std::vector<double> v)
{
  if (t.size() != v.size() || t.size() < 2)
    throw std::invalid_argument("TimeFunction::table: needs >= 2 points and as many values as times");
  for (std::size_t k = 1; k < t.size(); ++k)
    if (!(t[k] > t[k - 1]))
      throw std::invalid_argument("TimeFunction::table: times must be strictly increasing");
  TimeFunction f;
  f.kind_ = Kind::Table;
  f.times_ = std::move(t);
  f.values_ = std::move(v);
  return f;
}

TimeFunction TimeFunction::sine(double amplitude, double frequency, double phase, double offset,
                                double t0)
{
  if (!(frequency >= 0))
    throw std::invalid_argument("TimeFunction::sine: frequency must be >= 0");
  TimeFunction f;
  f.kind_ = Kind::Sine;
  f.amplitude_ = amplitude;
  f.frequency_ = frequency;
  f.phase_ = phase;
  f.v0_ = offset;
  f.t0_ = t0;
  return f;
}

TimeFunction TimeFunction::accelLimited(double t0, double from, double to, double speed, double accel, double jerk)
{
  if (!std::isfinite(t0) || !std::isfinite(from) || !std::isfinite(to))
    throw std::invalid_argument("TimeFunction::accelLimited: t0, from and to must be finite");
  if (!(speed > 0) || !std::isfinite(speed))
    throw std::invalid_argument("TimeFunction::accelLimited: speed must be > 0");
  if (!(accel > 0) || !std::isfinite(accel))
    throw std::invalid_argument("TimeFunction::accelLimited: accel must be > 0");
  if (!(jerk >= 0) || !std::isfinite(jerk))
    throw std::invalid_argument("TimeFunction::accelLimited: jerk must be >= 0 (0: unlimited)");
  TimeFunction f;
  f.kind_ = Kind::AccelLimited;
  f.t0_ = f.t1_ = t0;
  f.v0_ = from;
  f.v1_ = to;
  f.amplitude_ = to >= from ? 1.0 : -1.0;
  Move &m = f.move_;
  m.distance = std::abs(to - from);
  m.jerk = jerk;
  if (m.distance == 0) return f;
  // The speed-up phase to a peak speed vp: with unlimited jerk it takes
  // vp / accel; with jerk j the acceleration ramps up and down in accel / j
  // each (or, below vp = accel^2 / j, never reaches accel: ap = sqrt(vp j)).
  // The phase is point-symmetric about its middle, so it covers vp Ta / 2.
  const auto shape = [&](double vp) {
    m.peakSpeed = vp;
    if (jerk == 0) {
      m.peakAccel = accel, m.jerkTime = 0, m.accelTime = vp / accel;
    } else if (vp * jerk >= accel * accel) {
      m.peakAccel = accel, m.jerkTime = accel / jerk, m.accelTime = vp / accel + accel / jerk;
    } else {
      m.peakAccel = std::sqrt(vp * jerk), m.jerkTime = m.peakAccel / jerk, m.accelTime = 2.0 * m.jerkTime;
    }
  };
  shape(speed);
  if (m.peakSpeed * m.accelTime > m.distance) {
    // Too short to reach `speed`: speed up and slow down without cruising,
    // vp Ta(vp) = distance solved for vp.
    double vp;
    if (jerk == 0) {
      vp = std::sqrt(accel * m.distance);
    } else {
      vp = std::cbrt(m.distance * m.distance * jerk / 4.0); // accel never reached
      if (vp * jerk > accel * accel) {
        const double c = accel / jerk;
        vp = 0.5 * accel * (-c + std::sqrt(c * c + 4.0 * m.distance / accel));
      }
    }
    shape(vp);
  }
  const double cruise = std::max(m.distance / m.peakSpeed - m.accelTime, 0.0);
  f.t1_ = t0 + 2.0 * m.accelTime + cruise;
  return f;
}

void TimeFunction::speedUp(double tau, double out[3]) const
{
  const Move &m = move_;
  // First half: jerk segment (a = j tau), then constant acceleration.
  const auto firstHalf = [&](double u, double r[3]) {
    if (u < m.jerkTime) {
      r[0] = m.jerk * u * u * u / 6.0, r[1] = 0.5 * m.jerk * u * u, r[2] = m.jerk * u;
      return;
    }
    const double Tj = m.jerkTime, v1 = 0.5 * m.peakAccel * Tj, x1 = m.peakAccel * Tj * Tj / 6.0, w = u - Tj;
    r[0] = x1 + v1 * w + 0.5 * m.peakAccel * w * w, r[1] = v1 + m.peakAccel * w, r[2] = m.peakAccel;
  };
  if (tau <= 0.5 * m.accelTime) {
    firstHalf(tau, out);
    return;
  }
  // Second half by point symmetry about (Ta/2, vp/2): v(tau) = vp - v(Ta - tau).
  const double sigma = m.accelTime - tau;
  double r[3];
  firstHalf(sigma, r);
  out[0] = 0.5 * m.peakSpeed * m.accelTime - (m.peakSpeed * sigma - r[0]);
  out[1] = m.peakSpeed - r[1];
  out[2] = r[2];
}

// The phases are chosen by comparing t with the same doubles that
// accelerationBreakpoints() reports (t0 + Ta, t1 - Ta), not tau with Ta:
// at a breakpoint t_k, (t_k - t0) may round below Ta, and the acceleration
// would then be the left limit where the restart there needs the right one.
void TimeFunction::moveState(double t, double out[3]) const
{
  const Move &m = move_;
  const double tau = t - t0_;
  if (t < t0_ || m.distance == 0) { // at t0 the speed-up's right limit (f'' = accel without a jerk limit)
    out[0] = out[1] = out[2] = 0;
  } else if (t >= t1_) {
    out[0] = m.distance, out[1] = out[2] = 0;
  } else if (t < t0_ + m.accelTime) {
    speedUp(std::min(tau, m.accelTime), out); // the differences may round past the phase's end
  } else if (t < t1_ - m.accelTime) { // right limits at the phase changes, like ramp and table
    out[0] = 0.5 * m.peakSpeed * m.accelTime + m.peakSpeed * (tau - m.accelTime), out[1] = m.peakSpeed, out[2] = 0;
  } else { // slowing down: the speed-up run backwards from the end
    speedUp(std::min(t1_ - t, m.accelTime), out);
    out[0] = m.distance - out[0], out[2] = -out[2];
  }
}

// For Ramp and Table the derivative at a knot is taken from the segment that
// starts there (right derivative), so f'(t0) is the ramp slope and f'(t1) = 0.

double TimeFunction::value(double t) const
{
  switch (kind_) {
  case Kind::Constant:
    return v0_;
  case Kind::Ramp: {
    if (t <= t0_)
      return v0_;
    if (t >= t1_)
      return v1_;
    return v0_ + (v1_ - v0_) * (t - t0_) / (t1_ - t0_);
  }
  case Kind::SmoothStep: {
    if (t <= t0_)
      return v0_;
    if (t >= t1_)
      return v1_;
    return v0_ + (v1_ - v0_) * stepShape((t - t0_) / (t1_ - t0_));
  }
  case Kind::Table: {
    if (t <= times_.front())
      return values_.front();
    if (t >= times_.back())
      return values_.back();
    // First knot strictly greater than t: segment [k-1, k] contains t.
    const auto k = std::upper_bound(times_.begin(), times_.end(), t) - times_.begin();
    const double ta = times_[k - 1], tb = times_[k];
    return values_[k - 1] + (values_[k] - values_[k - 1]) * (t - ta) / (tb - ta);
  }
  case Kind::Sine: {
    // Frozen at its t0 value before t0 so that a late start does not run
    // the oscillation backwards in time.
    const double tau = std::max(t - t0_, 0.0);
    return v0_ + amplitude_ * std::sin(kTwoPi * frequency_ * tau + phase_);
  }
  case Kind::AccelLimited: {
    double x[3];
    moveState(t, x);
    return v0_ + amplitude_ * x[0];
  }
  }
  return 0.0;
}

void TimeFunction::velocityBreakpoints(std::vector<double> &out) const
{
  switch (kind_) {
  case Kind::Ramp:
    if (v1_ != v0_) out.insert(out.end(), {t0_, t1_});
    return;
  case Kind::Table: {
    // Slope before the first knot and after the last is zero.
    double before = 0.0;
    for (std::size_t k = 0; k < times_.size(); ++k) {
      const double after =
        k + 1 < times_.size() ? (values_[k + 1] - values_[k]) / (times_[k + 1] - times_[k]) : 0.0;
      if (after != before) out.push_back(times_[k]);
      before = after;
    }
    return;
  }
  case Kind::Sine:
    if (rate(t0_) != 0.0) out.push_back(t0_);
    return;
  case Kind::Constant:
  case Kind::SmoothStep:
  case Kind::AccelLimited:
    return;
  }
}

void TimeFunction::accelerationBreakpoints(std::vector<double> &out) const
{
  switch (kind_) {
  case Kind::AccelLimited:
    // Unlimited jerk: f'' jumps to +-accel at the start and the end of each
    // speed change (a jerk-limited move has a continuous f'': none).
    if (move_.distance == 0 || move_.jerk > 0) return;
    out.insert(out.end(), {t0_, t0_ + move_.accelTime});
    if (t1_ - move_.accelTime > t0_ + move_.accelTime) out.push_back(t1_ - move_.accelTime); // cruise in between
    out.push_back(t1_);
    return;
  case Kind::Sine:
    if (accel(t0_) != 0.0) out.push_back(t0_); // starts with -A w^2 sin(phase) after f'' = 0 before t0
    return;
  case Kind::Constant:
  case Kind::Ramp:
  case Kind::Table:
  case Kind::SmoothStep:
    return;
  }
}

double TimeFunction::rate(double t) const
{
  switch (kind_) {
  case Kind::Constant:
    return 0.0;
  case Kind::Ramp:
    return (t >= t0_ && t < t1_) ? (v1_ - v0_) / (t1_ - t0_) : 0.0;
  case Kind::SmoothStep: {
    if (t <= t0_ || t >= t1_)
      return 0.0;
    const double T = t1_ - t0_;
    return (v1_ - v0_) * stepShapeRate((t - t0_) / T) / T;
  }
  case Kind::Table: {
    if (t < times_.front() || t >= times_.back())
      return 0.0;
    const auto k = std::upper_bound(times_.begin(), times_.end(), t) - times_.begin();
    return (values_[k] - values_[k - 1]) / (times_[k] - times_[k - 1]);
  }
  case Kind::Sine: {
    if (t < t0_)
      return 0.0;
    const double w = kTwoPi * frequency_;
    return amplitude_ * w * std::cos(w * (t - t0_) + phase_);
  }
  case Kind::AccelLimited: {
    double x[3];
    moveState(t, x);
    return amplitude_ * x[1];
  }
  }
  return 0.0;
}

double TimeFunction::accel(double t) const
{
  switch (kind_) {
  case Kind::Constant:
  case Kind::Ramp:
  case Kind::Table:
    return 0.0; // piecewise linear: kinks carry no impulse (see header)
  case Kind::SmoothStep: {
    if (t <= t0_ || t >= t1_)
      return 0.0;
    const double T = t1_ - t0_;
    return (v1_ - v0_) * stepShapeAccel((t - t0_) / T) / (T * T);
  }
  case Kind::Sine: {
    if (t < t0_)
      return 0.0;
    const double w = kTwoPi * frequency_;
    return -amplitude_ * w * w * std::sin(w * (t - t0_) + phase_);
  }
  case Kind::AccelLimited: {
    double x[3];
    moveState(t, x);
    return amplitude_ * x[2];
  }
  }
  return 0.0;
}

TimeFunction TimeFunction::scaled(double factor) const
{
  TimeFunction f = *this;
  f.v0_ *= factor; // constant value, ramp/step start, sine offset
  f.v1_ *= factor;
  f.amplitude_ *= factor; // sine amplitude; direction and units of an accel-limited move
  for (double &v : f.values_)
    v *= factor;
  return f;
}

std::string TimeFunction::describe() const
{
  switch (kind_) {
  case Kind::Constant:
    return "constant " + fmt(v0_);
  case Kind::Ramp:
    return "ramp " + fmt(v0_) + " -> " + fmt(v1_) + " over t in [" + fmt(t0_) + ", " + fmt(t1_) + "] s";
  case Kind::SmoothStep:
    return "smooth step " + fmt(v0_) + " -> " + fmt(v1_) + " over t in [" + fmt(t0_) + ", " + fmt(t1_) +
           "] s";
  case Kind::Table:
    return "table of " + std::to_string(times_.size()) + " points over t in [" + fmt(times_.front()) + ", " +
           fmt(times_.back()) + "] s, values " + fmt(*std::min_element(values_.begin(), values_.end())) +
           " .. " + fmt(*std::max_element(values_.begin(), values_.end()));
  case Kind::Sine:
    return "sine " + fmt(v0_) + " + " + fmt(amplitude_) + " sin(2 pi " + fmt(frequency_) + " Hz (t - " + fmt(t0_) +
           " s) + " + fmt(phase_) + " rad) for t >= " + fmt(t0_) + " s";
  case Kind::AccelLimited: {
    const double u = std::abs(amplitude_);
    return "accel-limited move " + fmt(v0_) + " -> " + fmt(v1_) + " over t in [" + fmt(t0_) + ", " + fmt(t1_) +
           "] s, peak rate " + fmt(u * move_.peakSpeed) + ", peak acceleration " + fmt(u * move_.peakAccel) +
           (move_.jerk > 0 ? ", jerk " + fmt(u * move_.jerk) : std::string(", unlimited jerk"));
  }
  }
  return "unknown";
}

double TimeFunction::rateBefore(double t) const
{
  switch (kind_) {
  case Kind::Ramp:
    return (t > t0_ && t <= t1_) ? (v1_ - v0_) / (t1_ - t0_) : 0.0;
  case Kind::Table: {
    if (t <= times_.front() || t > times_.back())
      return 0.0;
    // First knot not less than t: segment [k-1, k] ends at or after t.
    const auto k = std::lower_bound(times_.begin(), times_.end(), t) - times_.begin();
    return (values_[k] - values_[k - 1]) / (times_[k] - times_[k - 1]);
  }
  case Kind::Sine:
    return t <= t0_ ? 0.0 : rate(t);
  case Kind::Constant:
  case Kind::SmoothStep:
  case Kind::AccelLimited:
    return rate(t); // continuous rate
  }
  return 0.0;
}

void TimeFunction::bounds(double ta, double tb, double *lo, double *hi) const
{
  // The values at both ends, then the interior extremes of each kind.
  double a = value(ta), b = value(tb);
  *lo = std::min(a, b), *hi = std::max(a, b);
  const auto include = [&](double x) { *lo = std::min(*lo, x), *hi = std::max(*hi, x); };
  switch (kind_) {
  case Kind::Constant:
  case Kind::Ramp:
  case Kind::SmoothStep:
  case Kind::AccelLimited:
    return; // monotone in t
  case Kind::Table:
    for (std::size_t k = 0; k < times_.size(); ++k)
      if (times_[k] > ta && times_[k] < tb) include(values_[k]);
    return;
  case Kind::Sine: {
    // Crests and troughs where 2 pi f (t - t0) + phase = pi/2 + k pi, t > t0.
    const double w = kTwoPi * frequency_, from = std::max(ta, t0_);
    if (!(w > 0) || !(tb > from)) return;
    const double pi = 0.5 * kTwoPi, first = std::ceil((w * (from - t0_) + phase_ - 0.5 * pi) / pi);
    for (double k = first; k <= first + 1; ++k) { // one crest and one trough, if inside
      const double t = t0_ + (0.5 * pi + k * pi - phase_) / w;
      if (t >= from && t <= tb) include(v0_ + (std::fmod(std::abs(k), 2.0) == 0 ? amplitude_ : -amplitude_));
    }
    return;
  }
  }
}

} // namespace boomdyn
