#include "boomdyn/frequency_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <string>

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
  // The refinement's start, so that a restarted run refines from the same
  // vectors as the uninterrupted one (bitwise equal results on one rank).
  out.addScalar("tracker.basis_size", (double)basis_.size());
  for (std::size_t k = 0; k < basis_.size(); ++k)
    PetscCall(out.addVector("tracker.basis_" + std::to_string(k), basis_[k]));
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
  basis_.clear();
  const int m = static_cast<int>(in.scalar("tracker.basis_size"));
  for (int k = 0; k < m; ++k) {
    PetscHandle<Vec> v;
    PetscCall(assembler_.createVector(v.address()));
    PetscCall(in.getVector("tracker.basis_" + std::to_string(k), v));
    basis_.push_back(std::move(v));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracker::solveFully(double t, Vec q, Vec lambda, double target, Vec guess,
                                            std::vector<double> *omega2)
{
  PetscFunctionBeginUser;
  ModalOptions options;
  options.keepVectors = true;
  options.target = target;
  options.initialGuess = guess;
  // Guard vectors for the next refinement: the modes just above the reported
  // ones converge in it at the rate (w_k - tau) / (w_m+1 - tau) only when
  // the subspace holds more than them.
  const PetscInt bound = finiteModeBound(assembler_.model());
  const int nev = fullSolve_ ? count_ : (int)std::min<PetscInt>(bound, count_ + std::max(2, count_ / 2));
  ModalResult modes;
  PetscCall(solveModes(assembler_, t, q, lambda, nev, &modes, options));
  basis_ = std::move(modes.vectors);
  omega2->assign(modes.omega2.begin(), modes.omega2.begin() + count_);
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracker::analyze(double t, Vec q, Vec lambda, TrackedModes *out)
{
  PetscFunctionBeginUser;
  // Below the followed eigenvalue, so that it and its neighbours are the nearest.
  const double target = previous_ ? 0.5 * previousOmega2_ : ModalOptions{}.target;
  std::vector<double> omega2;
  bool refined = false;
  pencilCurrent_ = false;
  target_ = target;
  if (!fullSolve_ && previous_ && (int)basis_.size() >= count_) {
    RefinedModes r;
    PetscCall(refiner_.refine(t, q, lambda, target, count_, basis_, &r, &refined));
    pencilCurrent_ = refiner_.factoredAtLastPrepare();
    if (refined) {
      omega2 = r.omega2;
    } else if (!fallbackReported_) {
      fallbackReported_ = true;
      PetscCall(PetscPrintf(assembler_.comm(),
                            "warning: frequency tracking: refining the previous modes at t = %g s did not converge "
                            "(relative residual %.2g after %d iterations); the full eigen-solve runs instead (said once)\n",
                            t, r.worstResidual, r.iterations));
    }
  }
  if (!refined) PetscCall(solveFully(t, q, lambda, target, previous_ ? previous_.get() : nullptr, &omega2));

  // Candidates for the followed mode: the reported modes, multipliers dropped.
  PetscHandle<Vec> zero, candidate;
  PetscCall(VecDuplicate(basis_[0], zero.address()));
  PetscCall(VecSet(zero, 0.0));
  PetscCall(VecDuplicate(basis_[0], candidate.address()));
  int pick = 0;
  double best = 1.0;
  if (!previous_) {
    // Skip rigid-body modes of a mechanism (omega^2 ~ 0 relative to the spectrum).
    const double scale = std::abs(omega2.back());
    while (pick + 1 < (int)omega2.size() && omega2[pick] <= 1e-8 * scale) ++pick;
    PetscCall(VecDuplicate(basis_[0], previous_.address()));
  } else {
    best = -1.0;
    for (int k = 0; k < count_; ++k) {
      double mac;
      PetscCall(VecCopy(basis_[k], candidate));
      PetscCall(assembler_.copyMultipliers(zero, candidate, 0.0));
      PetscCall(modalAssurance(previous_, candidate, &mac));
      if (mac > best) best = mac, pick = k;
    }
  }
  PetscCall(VecCopy(basis_[pick], previous_));
  PetscCall(assembler_.copyMultipliers(zero, previous_, 0.0));
  previousOmega2_ = omega2[pick];
  out->t = t;
  out->frequencyHz.clear();
  for (double w : omega2) out->frequencyHz.push_back(std::sqrt(std::max(w, 0.0)) / (2.0 * M_PI));
  out->trackedHz = out->frequencyHz[pick];
  out->mac = best;
  out->index = pick;
  out->refined = refined;
  PetscCall(gatherShape(assembler_, previous_, &out->shape));
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracker::analyzeDamped(double t, Vec q, Vec lambda, TrackedModes *out, DampedModalResult *modes)
{
  DampedModalResult dm;
  bool refined = false;
  PetscFunctionBeginUser;
  if (!fullSolve_ && !basis_.empty()) {
    bool factored = pencilCurrent_;
    if (!factored) PetscCall(refiner_.prepare(t, q, lambda, target_, &factored));
    pencilCurrent_ = factored;
    DampedRefinementInfo info;
    if (factored)
      PetscCall(dampedRefiner_.refine(t, q, lambda, refiner_.stiffness(), refiner_.mass(), refiner_.shiftedSolver(),
                                      basis_, count_, &dm, &info, &refined));
    if (!refined && !dampedFallbackReported_) {
      dampedFallbackReported_ = true;
      PetscCall(PetscPrintf(assembler_.comm(),
                            "warning: frequency tracking: refining the damped modes at t = %g s did not converge "
                            "(relative residual %.2g after %d projections, subspace %d); the full damped eigen-solve "
                            "runs instead (said once)\n",
                            t, info.worstResidual, info.iterations, info.subspace));
    }
  }
  if (!refined) {
    DampedModalOptions options;
    options.allowFewer = true; // heavy damping: few oscillating modes (damped_eigen_solver.hpp)
    options.keepVectors = modes != nullptr;
    PetscCall(solveDampedModes(assembler_, t, q, lambda, count_, &dm, options));
  }
  out->damped = true;
  out->dampedRefined = refined;
  // No oscillating damped mode found: NaN in the file.
  out->trackedDampedHz = out->trackedDampingRatio = std::nan("");
  out->dampedMac = 0;
  const auto dot = [](const std::vector<double> &a, const std::vector<double> &b) {
    double d = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) d += a[i] * b[i];
    return d;
  };
  for (std::size_t k = 0; k < dm.shapes.size(); ++k) { // rank 0 holds the shapes
    const double ab = dot(dm.shapes[k], out->shape);
    const double mac = ab * ab / (dot(dm.shapes[k], dm.shapes[k]) * dot(out->shape, out->shape));
    if (mac > out->dampedMac) {
      out->dampedMac = mac;
      out->trackedDampedHz = dm.dampedOmega[k] / (2.0 * M_PI);
      out->trackedDampingRatio = dm.dampingRatio[k];
    }
  }
  if (modes) *modes = std::move(dm);
  PetscFunctionReturn(0);
}

} // namespace boomdyn
