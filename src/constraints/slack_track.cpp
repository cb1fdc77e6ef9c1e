#include "boomdyn/slack_track.hpp"

#include <algorithm>

namespace boomdyn {

bool slackLeavesElement(double s, double begin, double end, double length, double *clamped)
{
  const double sc = std::clamp(s, 0.0, length);
  *clamped = sc;
  const double band = kSlackRelocationHysteresis * (end - begin);
  return sc < begin - band || sc > end + band;
}

} // namespace boomdyn
