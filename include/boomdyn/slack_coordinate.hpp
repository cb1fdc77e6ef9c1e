// The build steps the planar and the spatial sliding joint types share: the
// slack coordinate s of a sliding joint, and the post-step hook that moves
// the contact point between track elements.
#pragma once

#include "boomdyn/model_builder.hpp"
#include "boomdyn/post_step_hook.hpp"

#include <memory>
#include <sstream>

namespace boomdyn {

// Adds s at s0 (where the slider point projects onto the initial track) and
// keeps it in the joint's scratch ("s0", "slack": an extraction drive reads
// them); a ModelError when the slider point lies outside its track.
void addSlackCoordinate(const ComponentSpec &spec, ModelBuilder &b, const BodyBase &track, double s0);

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
