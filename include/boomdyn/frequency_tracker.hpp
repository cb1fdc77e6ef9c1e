// Frequencies along a trajectory (docs/model.md §5): at each call the system is
// linearized at the given state and the modes nearest half the lowest
// followed omega^2 are found (shift-and-invert, warm-started from the first
// followed shape). Each followed mode is carried by mode continuity, i.e. the
// mode with the largest MAC against its previous shape, not by sorting; two
// followed modes never take the same mode (greedy assignment on the largest
// MAC), so a followed mode keeps its identity through crossings.
// At the first call the followed modes are the lowest `follow` modes with
// omega^2 > 0, or the modes nearest the given frequencies (followHz).
// After the first analysis the modes are refined from the previous ones
// (mode_refinement.hpp) instead of solved afresh; the full solve runs at the
// first analysis, after a restart, when refinement fails (said once), and at
// every analysis with fullSolve (-boom_tracking_full). The same holds for the
// damped modes of a damped model (analyzeDamped, damped_mode_refinement.hpp).
#pragma once

#include "boomdyn/state_archive.hpp"
#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/damped_mode_refinement.hpp"
#include "boomdyn/mode_refinement.hpp"
#include "boomdyn/petsc_handle.hpp"

namespace boomdyn {

// One followed mode at one analysis.
struct FollowedMode {
  double hz = 0;             // its frequency
  double mac = 1;            // MAC against its previous shape (1 at the first analysis)
  int index = 0;             // its position among the modes of the analysis (ascending)
  std::vector<double> shape; // its shape (rank 0), max-norm 1
  // Damped models: the damped mode assigned to it by MAC (rank 0; NaN, 0: none).
  double dampedHz = 0, dampingRatio = 0, dampedMac = 0;
  // The share of each kind in its strain energy (mode_labels.hpp; all ranks).
  EnergyShares energyShares{};
};

struct TrackedModes {
  double t = 0;
  std::vector<double> frequencyHz; // the `count` lowest modes found, ascending
  std::vector<EnergyShares> energyShares; // their energy shares (mode_labels.hpp; all ranks)
  std::vector<FollowedMode> followed; // every followed mode, in the order of tracking.follow
  // The first followed mode (= followed[0]), the fields of /tracking/tracked_hz etc.
  double trackedHz = 0;            // the followed mode
  double mac = 1;                  // MAC of the followed mode against the previous one (1 at the start)
  int index = 0;                   // its position in frequencyHz
  std::vector<double> shape;       // its shape (rank 0), max-norm 1
  bool refined = false;            // from refinement (false: full eigen-solve)
  // Damped models (FrequencyTracking): the damped mode (SLEPc PEP) whose
  // shape has the largest MAC against the followed shape; rank 0 only.
  bool damped = false;
  double trackedDampedHz = 0;      // its damped frequency omega_d / 2 pi
  double trackedDampingRatio = 0;  // its damping ratio
  double dampedMac = 0;            // MAC of its shape (real part) against the followed shape
  bool dampedRefined = false;      // damped modes from refinement (false: SLEPc PEP solve)
  // A full eigen-solve of this analysis was stopped by FrequencyTracker::stop:
  // nothing else is filled, and the tracker's state is that of the last analysis.
  bool interrupted = false;
};

class FrequencyTracker {
public:
  // follow, followHz: the followed modes (TrackingSpec): the lowest `follow`
  // modes with omega^2 > 0 at the first analysis, or the modes nearest the
  // frequencies followHz (Hz; then follow is their number).
  FrequencyTracker(Assembler &assembler, int count, bool fullSolve = false, int follow = 1,
                   std::vector<double> followHz = {})
    : assembler_(assembler), count_(count), fullSolve_(fullSolve), follow_(followHz.empty() ? follow : (int)followHz.size()),
      followHz_(std::move(followHz)), refiner_(assembler), dampedRefiner_(assembler)
  {
    // A damped model's analyses assemble D with A and B (analyzeDamped).
    refiner_.withDamping = assembler.model().hasPhysicalDamping();
  }

  PetscErrorCode analyze(double t, Vec q, Vec lambda, TrackedModes *out);
  // Asked at every iteration of the full eigen-solves (ModalOptions::stop);
  // true ends the analysis with TrackedModes::interrupted.
  std::function<bool()> stop;
  // After analyze() at the same state: the damped modes (`count` lowest
  // oscillating, solveDampedModes with allowFewer) and, in out, for each
  // followed mode the one whose shape (real part) has the largest MAC against
  // its undamped shape (rank 0; greedy assignment like the undamped modes). Refined from the undamped modes of analyze() unless
  // fullSolve; a full PEP solve when refinement fails (said once). modes:
  // optional, receives the damped modes with their vectors.
  PetscErrorCode analyzeDamped(double t, Vec q, Vec lambda, TrackedModes *out, DampedModalResult *modes = nullptr);
  // The followed shape and eigenvalue, for checkpoints.
  PetscErrorCode save(StateWriter &out) const;
  PetscErrorCode restore(const StateReader &in);

  // analyzeDamped() without `modes` refines only the followed modes' damped
  // counterparts to the full tolerance; the pick stands when every other
  // damped mode's MAC against a followed shape is below the picked one's by
  // this much, else all are refined (dampedRepeats() counts those analyses).
  double dampedMacMargin = 0.05;
  int dampedRepeats() const { return dampedRepeats_; }

  // The modes of the last analysis, all m = count + guard Ritz vectors
  // (empty after a full solve with fullSolve); for tests.
  const std::vector<PetscHandle<Vec>> &basis() const { return basis_; }

private:
  // Full eigen-solve; basis_ = the vectors; the first `wanted` omega^2 returned.
  PetscErrorCode solveFully(double t, Vec q, Vec lambda, double target, Vec guess, int wanted,
                            std::vector<double> *omega2, bool *interrupted);
  // The damped mode assigned to each followed mode (largest MAC against its
  // shape, greedy; -1: none) and the MACs (rank 0: it holds the shapes).
  static std::vector<int> dampedPicks(const TrackedModes &out, const DampedModalResult &dm,
                                      std::vector<std::vector<double>> *mac);
  // Whether the picks (dampedPicks()) of refined damped modes, some
  // provisional, are those of the exact ones (analyzeDamped); exact: per
  // damped mode, refined to the tolerance (DampedRefinementInfo). Collective.
  PetscErrorCode picksStand(const std::vector<std::vector<double>> &mac, const std::vector<int> &picks,
                            const std::vector<bool> &exact, bool *stand) const;
  // The followed modes at the first analysis (positions in omega2).
  PetscErrorCode firstPicks(double t, const std::vector<double> &omega2, std::vector<int> *picks) const;

  Assembler &assembler_;
  int count_;
  bool fullSolve_;
  int follow_;                    // number of followed modes
  std::vector<double> followHz_;  // their frequencies at the first analysis (empty: the lowest)
  ModeRefiner refiner_;
  DampedModeRefiner dampedRefiner_;
  std::vector<PetscHandle<Vec>> basis_; // the last analysis' vectors (refinement's start)
  bool fallbackReported_ = false, dampedFallbackReported_ = false;
  int dampedRepeats_ = 0; // damped refinements repeated with every pair exact (picksStand)
  bool pencilCurrent_ = false; // refiner_ holds the pencil and factorization of the last analysis' state
  double target_ = 0;          // the last analysis' shift
  int wanted_ = 0;                // modes for the next analysis besides count_: one above every followed mode
  int found_ = 0;                 // modes of the last analysis (the damped analysis finds as many)
  std::vector<PetscHandle<Vec>> previous_; // the followed shapes (none before the first analysis)
  std::vector<double> previousOmega2_;
  ZeroGather shapeGather_; // the followed shapes to rank 0 (its scatter kept between analyses)
};

// Greedy assignment on the largest MAC: mac[j][k] of followed mode j against
// candidate k; each j gets a different k (the pair of largest MAC first, ties
// to the lower j, k), -1 when no candidate with MAC > floor is left.
std::vector<int> assignByMac(const std::vector<std::vector<double>> &mac, double floor);

// MAC = (a.b)^2 / ((a.a)(b.b)), collective.
PetscErrorCode modalAssurance(Vec a, Vec b, double *mac);

} // namespace boomdyn
