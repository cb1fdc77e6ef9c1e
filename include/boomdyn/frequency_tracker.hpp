// Frequencies along a trajectory (docs/model.md §5): at each call the system is
// linearized at the given state and the modes nearest half the last tracked
// omega^2 are found (shift-and-invert, warm-started from the last tracked
// shape); the first bending mode is followed by mode continuity, i.e. the
// mode with the largest MAC against the previous shape, not by sorting.
// At the first call the lowest mode with omega^2 > 0 is taken.
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

struct TrackedModes {
  double t = 0;
  std::vector<double> frequencyHz; // every mode found, ascending
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
};

class FrequencyTracker {
public:
  FrequencyTracker(Assembler &assembler, int count, bool fullSolve = false)
    : assembler_(assembler), count_(count), fullSolve_(fullSolve), refiner_(assembler), dampedRefiner_(assembler)
  {
  }

  PetscErrorCode analyze(double t, Vec q, Vec lambda, TrackedModes *out);
  // After analyze() at the same state: the damped modes (`count` lowest
  // oscillating, solveDampedModes with allowFewer) and, in out, the one whose
  // shape (real part) has the largest MAC against the followed undamped
  // shape (rank 0). Refined from the undamped modes of analyze() unless
  // fullSolve; a full PEP solve when refinement fails (said once). modes:
  // optional, receives the damped modes with their vectors.
  PetscErrorCode analyzeDamped(double t, Vec q, Vec lambda, TrackedModes *out, DampedModalResult *modes = nullptr);
  // The followed shape and eigenvalue, for checkpoints.
  PetscErrorCode save(StateWriter &out) const;
  PetscErrorCode restore(const StateReader &in);

  // The modes of the last analysis, all m = count + guard Ritz vectors
  // (empty after a full solve with fullSolve); for tests.
  const std::vector<PetscHandle<Vec>> &basis() const { return basis_; }

private:
  // Full eigen-solve for nev pairs; basis_ = their vectors; the first count_ reported.
  PetscErrorCode solveFully(double t, Vec q, Vec lambda, double target, Vec guess, std::vector<double> *omega2);

  Assembler &assembler_;
  int count_;
  bool fullSolve_;
  ModeRefiner refiner_;
  DampedModeRefiner dampedRefiner_;
  std::vector<PetscHandle<Vec>> basis_; // the last analysis' vectors (refinement's start)
  bool fallbackReported_ = false, dampedFallbackReported_ = false;
  bool pencilCurrent_ = false; // refiner_ holds the pencil and factorization of the last analysis' state
  double target_ = 0;          // the last analysis' shift
  PetscHandle<Vec> previous_; // the followed shape (none before the first analysis)
  double previousOmega2_ = 0;
};

// MAC = (a.b)^2 / ((a.a)(b.b)), collective.
PetscErrorCode modalAssurance(Vec a, Vec b, double *mac);

} // namespace boomdyn
