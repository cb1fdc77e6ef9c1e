// The next time of a periodic schedule (state snapshots, checkpoints,
// frequency tracking). The schedule moves by whole intervals past the
// current time; an interval below the resolution of the time (1e-90 s at
// t = 1 s, which made the schedule loop spin forever) or so small that it
// would take more than a few additions moves in one step, so that no
// schedule loop can spin (issue 17): such an interval fires at every step.
#pragma once

#include <cmath>
#include <limits>

namespace boomdyn {

// The first time next + k interval (k >= 0) after t + slack, or, when that
// is not representable above t + slack, the next double after t + slack.
inline double nextScheduledTime(double next, double interval, double t, double slack)
{
  const double limit = t + slack;
  // The usual case (one or a few intervals per step) adds interval by
  // interval, as the schedule always did, so that results do not move.
  for (int k = 0; k < 64 && next <= limit; ++k) next += interval;
  if (next > limit) return next;
  const double jumped = next + (std::floor((limit - next) / interval) + 1) * interval;
  return std::isfinite(jumped) && jumped > limit ? jumped
                                                 : std::nextafter(limit, std::numeric_limits<double>::infinity());
}

} // namespace boomdyn
