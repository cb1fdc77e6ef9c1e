// Frequency tracking along a dynamic run (/tracking): an eigen-analysis at
// the first step at or after every tracking interval, and the tracked shape
// at the first analysis at or after each requested time.
#include "boomdyn/damped_eigen_solver.hpp"
#include "boomdyn/monitors.hpp"
#include "boomdyn/schedule.hpp"
#include "boomdyn/simulation.hpp"

#include <slepcsys.h>

#include <algorithm>
#include <cmath>

namespace boomdyn {

FrequencyTracking::FrequencyTracking(Simulation &sim, ResultsWriter &writer)
  : sim_(sim), writer_(writer), interval_(sim.scene().tracking.interval), shapeTimes_(sim.scene().tracking.shapesAt)
{
  std::sort(shapeTimes_.rbegin(), shapeTimes_.rend());
}

PetscErrorCode FrequencyTracking::setUp()
{
  PetscFunctionBeginUser;
  PetscCall(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  // -boom_tracking_full: a full eigen-solve (and for damped models a full
  // PEP solve) at every analysis instead of refining the previous modes (the
  // reference path; docs/model.md §5).
  const TrackingSpec &spec = sim_.scene().tracking;
  tracker_ = std::make_unique<FrequencyTracker>(sim_.assembler(), spec.count, sim_.options().trackingFullSolve,
                                                spec.follow, spec.followHz);
  tracker_->stop = sim_.stopRequest(); // SIGINT/SIGTERM inside a full eigen-solve
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracking::track(const RunState &s, double h)
{
  PetscFunctionBeginUser;
  if (s.t < next_ - 1e-9 * h) PetscFunctionReturn(0);
  TrackedModes modes;
  PetscCall(tracker_->analyze(s.t, s.q, s.lambda, &modes));
  // Stopped inside an eigen-solve: no row; the run ends after this step.
  if (modes.interrupted) PetscFunctionReturn(0);
  // Physical damping (Kelvin-Voigt sections, dampers) takes the damped
  // path; friction's velocity terms alone do not (WorkItem::physicalDamping).
  if (damped_ < 0) damped_ = sim_.model().hasPhysicalDamping();
  if (damped_) PetscCall(trackDamped(s, &modes));
  if (modes.interrupted) PetscFunctionReturn(0);
  bool shape = false;
  // shapeTimes_ is sorted latest first: the due times come off its back.
  while (!shapeTimes_.empty() && shapeTimes_.back() <= s.t + 1e-9 * h) {
    shapeTimes_.pop_back();
    shape = true;
  }
  PetscCall(writer_.appendTracking(modes, shape));
  next_ = nextScheduledTime(next_, interval_, s.t, 1e-9 * h);
  PetscFunctionReturn(0);
}

// The damped modes (docs/model.md §5, "Damped modes" and "Damped
// refinement") at the state of the analysis just made; each followed mode's
// damped mode is the one whose shape (real part of the coordinate part) has
// the largest MAC against its undamped shape (FrequencyTracker::analyzeDamped).
PetscErrorCode FrequencyTracking::trackDamped(const RunState &s, TrackedModes *modes)
{
  PetscFunctionBeginUser;
  PetscCall(tracker_->analyzeDamped(s.t, s.q, s.lambda, modes));
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracking::start(const RunState &s, bool restarted)
{
  PetscFunctionBeginUser;
  if (s.dynamic && !restarted) PetscCall(track(s, sim_.scene().dynamic.dt));
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracking::afterStep(const RunState &s, std::string *)
{
  PetscFunctionBeginUser;
  if (s.dynamic) PetscCall(track(s, s.h));
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracking::save(CheckpointWriter &out) const
{
  PetscFunctionBeginUser;
  out.addScalar("next_track", next_);
  out.addArray("shape_times", shapeTimes_);
  PetscCall(tracker_->save(out));
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracking::restore(const CheckpointReader &in)
{
  PetscFunctionBeginUser;
  next_ = in.scalar("next_track");
  shapeTimes_ = in.array("shape_times");
  std::sort(shapeTimes_.rbegin(), shapeTimes_.rend());
  PetscCall(tracker_->restore(in));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
