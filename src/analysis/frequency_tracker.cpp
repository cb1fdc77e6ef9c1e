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

std::vector<int> assignByMac(const std::vector<std::vector<double>> &mac, double floor)
{
  const std::size_t n = mac.size(), m = n ? mac[0].size() : 0;
  std::vector<int> pick(n, -1);
  std::vector<bool> taken(m, false);
  for (std::size_t round = 0; round < n; ++round) {
    double best = floor;
    int bj = -1, bk = -1;
    for (std::size_t j = 0; j < n; ++j) {
      if (pick[j] >= 0) continue;
      for (std::size_t k = 0; k < m; ++k)
        if (!taken[k] && mac[j][k] > best) best = mac[j][k], bj = (int)j, bk = (int)k;
    }
    if (bj < 0) break;
    pick[bj] = bk;
    taken[bk] = true;
  }
  return pick;
}

// Checkpoint names: the first followed mode keeps the names of the
// single-mode tracker, the others get a suffix.
static std::string followedName(const std::string &base, std::size_t j)
{
  return j == 0 ? base : base + "_" + std::to_string(j);
}

PetscErrorCode FrequencyTracker::save(StateWriter &out) const
{
  PetscFunctionBeginUser;
  out.addScalar("tracker.started", previous_.empty() ? 0.0 : 1.0);
  out.addScalar("tracker.followed", (double)previous_.size());
  out.addScalar("tracker.wanted", (double)wanted_);
  for (std::size_t j = 0; j < std::max<std::size_t>(1, previous_.size()); ++j)
    out.addScalar(followedName("tracker.omega2", j), j < previousOmega2_.size() ? previousOmega2_[j] : 0.0);
  for (std::size_t j = 0; j < previous_.size(); ++j)
    PetscCall(out.addVector(followedName("tracker.shape", j), previous_[j]));
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
  previous_.clear();
  previousOmega2_.clear();
  if (in.scalar("tracker.started") != 0.0) {
    const int n = in.hasScalar("tracker.followed") ? (int)in.scalar("tracker.followed") : 1;
    PetscCheck(n == follow_, assembler_.comm(), PETSC_ERR_USER_INPUT,
               "the checkpoint follows %d modes, the scene (tracking.follow) %d", n, follow_);
    for (int j = 0; j < n; ++j) {
      PetscHandle<Vec> v;
      PetscCall(assembler_.createVector(v.address()));
      PetscCall(in.getVector(followedName("tracker.shape", j), v));
      previous_.push_back(std::move(v));
      previousOmega2_.push_back(in.scalar(followedName("tracker.omega2", j)));
    }
  }
  wanted_ = in.hasScalar("tracker.wanted") ? (int)in.scalar("tracker.wanted") : count_;
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

PetscErrorCode FrequencyTracker::solveFully(double t, Vec q, Vec lambda, double target, Vec guess, int wanted,
                                            std::vector<double> *omega2, bool *interrupted)
{
  PetscFunctionBeginUser;
  ModalOptions options;
  options.stop = stop;
  options.keepVectors = true;
  options.target = target;
  options.initialGuess = guess;
  // Guard vectors for the next refinement: the modes just above the reported
  // ones converge in it at the rate (w_k - tau) / (w_m+1 - tau) only when
  // the subspace holds more than them.
  const PetscInt bound = finiteModeBound(assembler_.model());
  const int nev = fullSolve_ ? wanted : (int)std::min<PetscInt>(bound, wanted + std::max(2, wanted / 2));
  ModalResult modes;
  PetscCall(solveModes(assembler_, t, q, lambda, nev, &modes, options));
  *interrupted = modes.interrupted;
  if (*interrupted) PetscFunctionReturn(0); // the basis of the last analysis stays
  basis_ = std::move(modes.vectors);
  omega2->assign(modes.omega2.begin(), modes.omega2.begin() + std::min<std::size_t>(wanted, modes.omega2.size()));
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracker::firstPicks(double t, const std::vector<double> &omega2, std::vector<int> *picks) const
{
  PetscFunctionBeginUser;
  // Skip rigid-body modes of a mechanism (omega^2 ~ 0 relative to the spectrum).
  int first = 0;
  const double scale = std::abs(omega2.back());
  while (first + 1 < (int)omega2.size() && omega2[first] <= 1e-8 * scale) ++first;
  const auto hz = [&](int k) { return std::sqrt(std::max(omega2[k], 0.0)) / (2.0 * M_PI); };
  picks->clear();
  if (followHz_.empty()) {
    PetscCheck(first + follow_ <= (int)omega2.size(), assembler_.comm(), PETSC_ERR_USER_INPUT,
               "tracking.follow: the first analysis (t = %g s) found %d modes with omega^2 > 0, fewer than the %d "
               "to follow: raise tracking.count",
               t, (int)omega2.size() - first, follow_);
    for (int j = 0; j < follow_; ++j) picks->push_back(first + j);
    PetscFunctionReturn(0);
  }
  // The mode nearest each given frequency (in ratio), a different one each:
  // the same greedy assignment as by MAC, on the closeness 1 / (1 + |ln(f_k / f_j)|).
  std::vector<std::vector<double>> closeness(followHz_.size(), std::vector<double>(omega2.size(), -1.0));
  for (std::size_t j = 0; j < followHz_.size(); ++j)
    for (int k = first; k < (int)omega2.size(); ++k)
      closeness[j][k] = 1.0 / (1.0 + std::abs(std::log(hz(k) / followHz_[j])));
  *picks = assignByMac(closeness, 0.0);
  for (std::size_t j = 0; j < followHz_.size(); ++j) {
    const int k = (*picks)[j];
    // Within a factor of 2: otherwise the asked mode is evidently not among the modes found.
    PetscCheck(k >= 0 && std::abs(std::log(hz(k) / followHz_[j])) <= std::log(2.0), assembler_.comm(),
               PETSC_ERR_USER_INPUT,
               "tracking.follow: no mode within a factor of 2 of %g Hz among the %d modes of the first analysis "
               "(t = %g s, %g ... %g Hz): raise tracking.count or change tracking.follow",
               followHz_[j], (int)omega2.size(), t, hz(first), hz((int)omega2.size() - 1));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracker::analyze(double t, Vec q, Vec lambda, TrackedModes *out)
{
  PetscFunctionBeginUser;
  const bool started = !previous_.empty();
  // Below the lowest followed eigenvalue, so that the followed modes and
  // their neighbours are the nearest.
  const double target =
      started ? 0.5 * *std::min_element(previousOmega2_.begin(), previousOmega2_.end()) : ModalOptions{}.target;
  // Modes to find: count_, and at least one above every followed mode, so
  // that a mode crossing the highest followed one from above is seen.
  const int wanted = std::max(count_, (int)std::min<PetscInt>(finiteModeBound(assembler_.model()), wanted_));
  found_ = wanted;
  std::vector<double> omega2;
  bool refined = false;
  pencilCurrent_ = false;
  target_ = target;
  if (!fullSolve_ && started && (int)basis_.size() >= wanted) {
    RefinedModes r;
    PetscCall(refiner_.refine(t, q, lambda, target, wanted, basis_, &r, &refined));
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
  if (!refined) {
    bool interrupted = false;
    PetscCall(solveFully(t, q, lambda, target, started ? previous_[0].get() : nullptr, wanted, &omega2, &interrupted));
    if (interrupted) {
      out->interrupted = true;
      PetscFunctionReturn(0);
    }
  }

  // Candidates for the followed modes: the modes found, multipliers dropped.
  PetscHandle<Vec> zero, candidate;
  PetscCall(VecDuplicate(basis_[0], zero.address()));
  PetscCall(VecSet(zero, 0.0));
  PetscCall(VecDuplicate(basis_[0], candidate.address()));
  std::vector<int> picks;
  std::vector<double> macs(follow_, 1.0);
  if (!started) {
    PetscCall(firstPicks(t, omega2, &picks));
    for (int j = 0; j < follow_; ++j) {
      previous_.emplace_back();
      PetscCall(VecDuplicate(basis_[0], previous_.back().address()));
    }
    previousOmega2_.assign(follow_, 0.0);
  } else {
    std::vector<std::vector<double>> mac(follow_, std::vector<double>(omega2.size()));
    for (std::size_t k = 0; k < omega2.size(); ++k) {
      PetscCall(VecCopy(basis_[k], candidate));
      PetscCall(assembler_.copyMultipliers(zero, candidate, 0.0));
      for (int j = 0; j < follow_; ++j) PetscCall(modalAssurance(previous_[j], candidate, &mac[j][k]));
    }
    picks = assignByMac(mac, -1.0);
    for (int j = 0; j < follow_; ++j) {
      PetscCheck(picks[j] >= 0, assembler_.comm(), PETSC_ERR_PLIB,
                 "frequency tracking at t = %g s: %d modes found for %d followed modes", t, (int)omega2.size(), follow_);
      macs[j] = mac[j][picks[j]];
    }
  }
  out->t = t;
  out->frequencyHz.clear();
  out->energyShares.clear();
  double labelSigma = 0; // the labels' constraint scale, computed by the first mode's
  for (std::size_t k = 0; k < std::min<std::size_t>(count_, omega2.size()); ++k) {
    out->frequencyHz.push_back(std::sqrt(std::max(omega2[k], 0.0)) / (2.0 * M_PI));
    out->energyShares.emplace_back();
    PetscCall(modeEnergyShares(assembler_, t, q, lambda, basis_[k], &out->energyShares.back(), &labelSigma));
  }
  out->followed.assign(follow_, FollowedMode{});
  int highest = 0;
  for (int j = 0; j < follow_; ++j) {
    const int k = picks[j];
    PetscCall(VecCopy(basis_[k], previous_[j]));
    PetscCall(assembler_.copyMultipliers(zero, previous_[j], 0.0));
    previousOmega2_[j] = omega2[k];
    FollowedMode &f = out->followed[j];
    f.hz = std::sqrt(std::max(omega2[k], 0.0)) / (2.0 * M_PI);
    f.mac = macs[j];
    f.index = k;
    PetscCall(gatherShape(assembler_, previous_[j], &f.shape, &shapeGather_));
    // A followed mode beyond the reported ones gets its own pass.
    if (k < (int)out->energyShares.size()) f.energyShares = out->energyShares[k];
    else PetscCall(modeEnergyShares(assembler_, t, q, lambda, previous_[j], &f.energyShares, &labelSigma));
    highest = std::max(highest, k);
  }
  wanted_ = highest + 2;
  out->trackedHz = out->followed[0].hz;
  out->mac = out->followed[0].mac;
  out->index = out->followed[0].index;
  out->refined = refined;
  out->shape = out->followed[0].shape;
  PetscFunctionReturn(0);
}

std::vector<int> FrequencyTracker::dampedPicks(const TrackedModes &out, const DampedModalResult &dm,
                                               std::vector<std::vector<double>> *mac)
{
  const auto dot = [](const std::vector<double> &a, const std::vector<double> &b) {
    double d = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) d += a[i] * b[i];
    return d;
  };
  // Each followed mode gets the damped mode of largest MAC against its shape
  // (rank 0 holds the shapes), a different one each; none found: -1.
  mac->assign(out.followed.size(), std::vector<double>(dm.shapes.size()));
  for (std::size_t j = 0; j < out.followed.size(); ++j)
    for (std::size_t k = 0; k < dm.shapes.size(); ++k) {
      const std::vector<double> &x = out.followed[j].shape;
      const double ab = dot(dm.shapes[k], x);
      (*mac)[j][k] = ab * ab / (dot(dm.shapes[k], dm.shapes[k]) * dot(x, x));
    }
  return assignByMac(*mac, 0.0);
}

PetscErrorCode FrequencyTracker::picksStand(const std::vector<std::vector<double>> &mac, const std::vector<int> &picks,
                                            const std::vector<bool> &exact, bool *stand) const
{
  // Decided on rank 0 (it holds the shapes, so the MACs) and broadcast, so
  // that every rank repeats the refinement or none.
  int ok = 1;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(assembler_.comm(), &rank));
  if (rank == 0)
    for (std::size_t j = 0; j < picks.size() && ok; ++j) {
      const int k = picks[j];
      if (k < 0 || !exact[k]) ok = 0;
      for (std::size_t i = 0; ok && i < exact.size(); ++i)
        if (!exact[i] && mac[j][i] > mac[j][k] - dampedMacMargin) ok = 0;
    }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, assembler_.comm()));
  *stand = ok != 0;
  PetscFunctionReturn(0);
}

PetscErrorCode FrequencyTracker::analyzeDamped(double t, Vec q, Vec lambda, TrackedModes *out, DampedModalResult *modes)
{
  DampedModalResult dm;
  bool refined = false;
  std::vector<std::vector<double>> mac;
  std::vector<int> picks;
  bool picked = false; // mac and picks are those of dm
  PetscFunctionBeginUser;
  if (!fullSolve_ && !basis_.empty()) {
    bool factored = pencilCurrent_;
    if (!factored) PetscCall(refiner_.prepare(t, q, lambda, target_, &factored));
    pencilCurrent_ = factored;
    DampedRefinementInfo info;
    dampedRefiner_.keepVectors = modes != nullptr;
    dampedRefiner_.pencilScale = refiner_.pencilScale(); // K and M of this state (prepare() above or in analyze())
    dampedRefiner_.norms = &refiner_.norms();
    // Only the followed modes' damped counterparts are reported: the other
    // pairs stop at the provisional tolerance (enough to compare shapes),
    // unless the caller wants all the modes.
    dampedRefiner_.needed.clear();
    if (!modes)
      for (const FollowedMode &f : out->followed) dampedRefiner_.needed.push_back(f.index);
    if (factored)
      PetscCall(dampedRefiner_.refine(t, q, lambda, refiner_.stiffness(), refiner_.mass(), refiner_.damping(),
                                      refiner_.shiftedSolver(), basis_, found_, &dm, &info, &refined));
    // The picks must stand with every pair exact: a followed mode must get a
    // needed pair, and no provisional pair may come within dampedMacMargin of
    // its MAC (their MAC errors are below 0.014 for modes 15 % apart:
    // DampedModeRefiner::provisionalTolerance).
    // Otherwise every pair is refined to the tolerance and picked again.
    bool stand = true;
    if (refined && !dampedRefiner_.needed.empty()) {
      picks = dampedPicks(*out, dm, &mac);
      picked = true;
      PetscCall(picksStand(mac, picks, info.exact, &stand));
    }
    if (!stand) {
      ++dampedRepeats_;
      picked = false;
      dampedRefiner_.needed.clear();
      PetscCall(dampedRefiner_.refine(t, q, lambda, refiner_.stiffness(), refiner_.mass(), refiner_.damping(),
                                      refiner_.shiftedSolver(), basis_, found_, &dm, &info, &refined));
    }
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
    options.stop = stop;
    PetscCall(solveDampedModes(assembler_, t, q, lambda, found_, &dm, options));
    if (dm.interrupted) {
      out->interrupted = true;
      PetscFunctionReturn(0);
    }
  }
  out->damped = true;
  out->dampedRefined = refined;
  if (!picked) picks = dampedPicks(*out, dm, &mac);
  for (std::size_t j = 0; j < out->followed.size(); ++j) {
    FollowedMode &f = out->followed[j];
    const int k = picks[j];
    f.dampedHz = k < 0 ? std::nan("") : dm.dampedOmega[k] / (2.0 * M_PI);
    f.dampingRatio = k < 0 ? std::nan("") : dm.dampingRatio[k];
    f.dampedMac = k < 0 ? 0.0 : mac[j][k];
  }
  out->trackedDampedHz = out->followed[0].dampedHz;
  out->trackedDampingRatio = out->followed[0].dampingRatio;
  out->dampedMac = out->followed[0].dampedMac;
  if (modes) *modes = std::move(dm);
  PetscFunctionReturn(0);
}

} // namespace boomdyn
