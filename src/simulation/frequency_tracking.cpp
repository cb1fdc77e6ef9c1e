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
  // -boom_tracking_full: a full eigen-solve at every analysis instead of
  // refining the previous modes (the reference path; docs/model.md §5).
  tracker_ = std::make_unique<FrequencyTracker>(sim_.assembler(), sim_.scene().tracking.count,
                                                sim_.options().trackingFullSolve);
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracking::track(const RunState &s, double h)
{
  PetscFunctionBeginUser;
  if (s.t < next_ - 1e-9 * h) PetscFunctionReturn(0);
  TrackedModes modes;
  PetscCall(tracker_->analyze(s.t, s.q, s.lambda, &modes));
  // Physical damping (Kelvin-Voigt sections, dampers) takes the damped
  // path; friction's velocity terms alone do not (WorkItem::physicalDamping).
  if (damped_ < 0) damped_ = sim_.model().hasPhysicalDamping();
  if (damped_) PetscCall(trackDamped(s, &modes));
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

// A full damped eigen-solve (docs/model.md §5, "Damped modes") per analysis;
// the damped mode is the one whose shape (real part of the coordinate part)
// has the largest MAC against the followed undamped shape.
PetscErrorCode FrequencyTracking::trackDamped(const RunState &s, TrackedModes *modes)
{
  DampedModalResult dm;
  PetscFunctionBeginUser;
  DampedModalOptions options;
  options.allowFewer = true; // heavy damping: few oscillating modes (damped_eigen_solver.hpp)
  PetscCall(solveDampedModes(sim_.assembler(), s.t, s.q, s.lambda, sim_.scene().tracking.count, &dm, options));
  modes->damped = true;
  // No oscillating damped mode found: NaN in the file.
  modes->trackedDampedHz = modes->trackedDampingRatio = std::nan("");
  const auto dot = [](const std::vector<double> &a, const std::vector<double> &b) {
    double d = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) d += a[i] * b[i];
    return d;
  };
  for (std::size_t k = 0; k < dm.shapes.size(); ++k) { // rank 0 holds the shapes
    const double ab = dot(dm.shapes[k], modes->shape);
    const double mac = ab * ab / (dot(dm.shapes[k], dm.shapes[k]) * dot(modes->shape, modes->shape));
    if (mac > modes->dampedMac) {
      modes->dampedMac = mac;
      modes->trackedDampedHz = dm.dampedOmega[k] / (2.0 * M_PI);
      modes->trackedDampingRatio = dm.dampingRatio[k];
    }
  }
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
