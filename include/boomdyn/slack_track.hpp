// What the planar and the spatial sliding joints share about their slack
// coordinate s (the arc length of the contact point on the track): when the
// contact point moves to another track element, and the post-step hook that
// moves it there or stops the run when the slider leaves its track.
#pragma once

#include "boomdyn/post_step_hook.hpp"

#include <algorithm>
#include <memory>
#include <sstream>

namespace boomdyn {

// A contact point stays with its element until it is more than this fraction
// of the element length past its end: the axis is C1 across nodes, so
// evaluating the element a little outside its span is accurate, and without
// this band a joint resting on a node would switch elements (and the solver
// its sparsity pattern) at every vibration.
constexpr double kSlackRelocationHysteresis = 1e-3;

// True when s, clamped to [0, length], lies outside the element
// [begin, end] by more than the hysteresis band; *clamped gets the clamped s.
inline bool slackLeavesElement(double s, double begin, double end, double length, double *clamped)
{
  const double sc = std::clamp(s, 0.0, length);
  *clamped = sc;
  const double band = kSlackRelocationHysteresis * (end - begin);
  return sc < begin - band || sc > end + band;
}

// After every converged step: stop when the slider left its track, else
// move the joint to the element that holds s (the pattern is rebuilt).
// Joint: name(), slackIndex(), onTrack(s), relocate(s), track() (name(),
// length()), trackLocation() (element, s), setTrackLocation(s).
template <class Joint>
PostStepHook followTrack(std::shared_ptr<Joint> joint)
{
  PostStepHook hook;
  hook.name = joint->name();
  hook.watched = {joint->slackIndex()};
  hook.afterStep = [joint](const double *s, double t, bool *changed, std::string *stop) -> PetscErrorCode {
    PetscFunctionBeginUser;
    if (!joint->onTrack(s[0])) {
      std::ostringstream os;
      os << "sliding joint '" << joint->name() << "' left its track '" << joint->track().name() << "' at t = " << t
         << " s (s = " << s[0] << " m, track length " << joint->track().length() << " m)";
      *stop = os.str();
      PetscFunctionReturn(0);
    }
    if (joint->relocate(s[0])) {
      *changed = true;
      PetscCall(PetscInfo(nullptr, "t = %g s: sliding joint '%s' moves to element %d of '%s' (s = %.12g m)\n", t,
                          joint->name().c_str(), joint->trackLocation().element, joint->track().name().c_str(), s[0]));
    }
    PetscFunctionReturn(0);
  };
  hook.location = [joint] { return joint->trackLocation().s; };
  hook.setLocation = [joint](double s) { joint->setTrackLocation(s); };
  return hook;
}

} // namespace boomdyn
