// Frequencies and mode shapes of the system linearized at a state
// (docs/model.md §5): the constrained pencil
//     A = [K_T  C_q^T; C_q 0],   B = [M 0; 0 0]
// with K_T the tangent of the internal, external and constraint forces
// (geometric terms from the multipliers included), solved with SLEPc
// Krylov-Schur, shift-and-invert around a target and MUMPS. Only scenes that
// ask for it create this object, so others never initialize SLEPc.
#pragma once

#include "boomdyn/assembler.hpp"
#include "boomdyn/gather.hpp"
#include "boomdyn/mode_labels.hpp"
#include "boomdyn/petsc_handle.hpp"

#include <functional>
#include <vector>

namespace boomdyn {

struct ModalResult {
  std::vector<double> omega2;            // eigenvalues omega^2 (rad^2/s^2), ascending
  std::vector<double> frequencyHz;       // sqrt(max(omega2,0)) / 2 pi
  std::vector<std::vector<double>> shapes; // coordinates part, gathered on rank 0 (empty elsewhere), max-norm 1
  std::vector<double> residuals;         // relative residual norms ||A x - w B x|| / ||x||
  // Damped modes (damped_eigen_solver.hpp), only when the model has damping;
  // the k lowest by |lambda|, solved independently of the undamped ones
  // (for light damping entry k is the damped version of undamped mode k).
  std::vector<double> dampedFrequencyHz; // omega_d / 2 pi
  std::vector<double> undampedEquivalentHz; // |lambda| / 2 pi
  std::vector<double> dampingRatio;      // -Re lambda / |lambda|; > 1: overdamped
  std::vector<double> decayRates;        // two per damped mode, 1/s, slower first (row-major, k x 2)
  // Energy-split labels (ModalOptions::energyShares; all ranks): per mode
  // the share of each ModeEnergyKind in its strain energy (mode_labels.hpp).
  std::vector<EnergyShares> energyShares;
  // Eigenvectors in the layout of x with the multiplier part zeroed (only
  // when asked for; owned here).
  std::vector<PetscHandle<Vec>> vectors;
  // The solve was stopped by ModalOptions::stop: nothing else is filled.
  bool interrupted = false;
};

struct ModalOptions {
  // Eigenvalues (omega^2) nearest the target are found. Slightly negative by
  // default: A - target B stays nonsingular when the mechanism has
  // rigid-body modes (omega = 0). -modal_eps_target overrides it.
  double target = -1.0;
  Vec initialGuess = nullptr; // warm start (layout of x), e.g. the previous mode
  bool keepVectors = false;   // return the eigenvectors in ModalResult::vectors
  bool energyShares = false;  // fill ModalResult::energyShares (one pass over the items per mode)
  // Asked at every iteration of the eigen-solver (SLEPc's stopping test), so
  // that SIGINT/SIGTERM end a long solve within one iteration; collective,
  // must answer alike on every rank. True: the solve ends at once and the
  // result says interrupted (no modes).
  std::function<bool()> stop;
};

// Linearize at coordinates q (layout of x, multiplier part ignored) with
// unscaled multipliers lambda (layout of x, coordinate part ignored) at time
// t, and find the `count` eigenvalues nearest the target, in ascending order
// (options prefix "modal_": -modal_eps_target, -modal_eps_view, -modal_st_ksp_... ).
PetscErrorCode solveModes(Assembler &assembler, double t, Vec q, Vec lambda, int count, ModalResult *result,
                          const ModalOptions &options = ModalOptions{});

// The number of finite eigenvalues of the pencil (docs/model.md §5):
// coordinates - constraint rows - first-order states.
PetscInt finiteModeBound(const Model &model);

// A and B of the pencil at (t, q, lambda) into matrices made by
// assembler.createMatrix() (same pattern). Leaves the assembler's offsets at q.
// sigmaOut (optional): the scale of the constraint blocks used (pencilState).
// D (optional): the damping matrix at the same state as well, in the same
// pass over the items (Assembler::evaluatePencil; equal to assembleDamping's).
// work (optional): a vector of assembler.createVector()'s layout for the
// state x (every entry is written), kept by a caller that assembles at
// every analysis instead of one made and destroyed per call.
PetscErrorCode assemblePencil(Assembler &assembler, double t, Vec q, Vec lambda, Mat A, Mat B,
                              double *sigmaOut = nullptr, Mat D = nullptr, Vec work = nullptr);

// The state x = [q | lambda / sigma] at which the pencil is assembled
// (x made by assembler.createVector()), and sigma, the scale of the
// constraint blocks (a typical stiffness diagonal). With *sigma > 0 on
// entry that scale is used as given (the same state's pencil computed it
// already: one pass over the elements less per analysis).
PetscErrorCode pencilState(Assembler &assembler, Vec q, Vec lambda, Vec x, double *sigma);

// Coordinate part of v on rank 0 (empty elsewhere), divided by its entry of
// largest magnitude (as ModalResult::shapes). Collective. `gather` keeps
// its scatter for the next call (the tracking gathers at every analysis);
// null: one made for this call.
PetscErrorCode gatherShape(Assembler &assembler, Vec v, std::vector<double> *shape, ZeroGather *gather = nullptr);

// Divides a mode shape by its entry of largest magnitude, so that shapes
// from runs on any number of ranks compare directly (sign and scale fixed).
void normalizeShape(std::vector<double> &shape);

} // namespace boomdyn
