#include "boomdyn/frequency_tracker.hpp"

#include <cmath>

namespace boomdyn {

PetscErrorCode modalAssurance(Vec a, Vec b, double *mac)
{
  PetscScalar ab, aa, bb;
  PetscFunctionBeginUser;
  PetscCall(VecDot(a, b, &ab));
  PetscCall(VecDot(a, a, &aa));
  PetscCall(VecDot(b, b, &bb));
  *mac = (aa > 0 && bb > 0) ? ab * ab / (aa * bb) : 0.0;
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracker::save(StateWriter &out) const
{
  PetscFunctionBeginUser;
  out.addScalar("tracker.started", previous_ ? 1.0 : 0.0);
  out.addScalar("tracker.omega2", previousOmega2_);
  if (previous_) PetscCall(out.addVector("tracker.shape", previous_));
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracker::restore(const StateReader &in)
{
  PetscFunctionBeginUser;
  if (in.scalar("tracker.started") != 0.0) {
    if (!previous_) PetscCall(assembler_.createVector(previous_.address()));
    PetscCall(in.getVector("tracker.shape", previous_));
  }
  previousOmega2_ = in.scalar("tracker.omega2");
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracker::analyze(double t, Vec q, Vec lambda, TrackedModes *out)
{
  PetscFunctionBeginUser;
  ModalOptions options;
  options.keepVectors = true;
  if (previous_) {
    // Below the followed eigenvalue, so that it and its neighbours are the nearest.
    options.target = 0.5 * previousOmega2_;
    options.initialGuess = previous_;
  }
  ModalResult modes;
  PetscCall(solveModes(assembler_, t, q, lambda, count_, &modes, options));
  int pick = 0;
  double best = 1.0;
  if (!previous_) {
    // Skip rigid-body modes of a mechanism (omega^2 ~ 0 relative to the spectrum).
    const double scale = std::abs(modes.omega2.back());
    while (pick + 1 < (int)modes.omega2.size() && modes.omega2[pick] <= 1e-8 * scale) ++pick;
    PetscCall(VecDuplicate(modes.vectors[pick], previous_.address()));
  } else {
    best = -1.0;
    for (int k = 0; k < (int)modes.vectors.size(); ++k) {
      double mac;
      PetscCall(modalAssurance(previous_, modes.vectors[k], &mac));
      if (mac > best) best = mac, pick = k;
    }
  }
  PetscCall(VecCopy(modes.vectors[pick], previous_));
  previousOmega2_ = modes.omega2[pick];
  out->t = t;
  out->frequencyHz = modes.frequencyHz;
  out->trackedHz = modes.frequencyHz[pick];
  out->mac = best;
  out->index = pick;
  out->shape = modes.shapes.empty() ? std::vector<double>{} : modes.shapes[pick];
  PetscFunctionReturn(0);
}

} // namespace boomdyn
