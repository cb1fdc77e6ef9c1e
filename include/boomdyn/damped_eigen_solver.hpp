// Damped modes of the system linearized at a state (docs/model.md §5,
// "Damped modes"): the quadratic eigenproblem
//     (lambda^2 M + lambda D + K) x = 0
// with K = [K_T C_q^T; C_q 0] and M = [M 0; 0 0] as in the symmetric pencil
// (eigen_solver.hpp) and D = [D 0; 0 0] the damping matrix (Kelvin-Voigt
// damping of the elements, dampers of springs, and whatever else depends on
// the velocities), solved with SLEPc PEP (TOAR, shift-and-invert about a
// target, KLU/MUMPS). Each mode is one of a conjugate pair
// lambda = -zeta omega +- i omega_d.
#pragma once

#include "boomdyn/assembler.hpp"
#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/petsc_handle.hpp"

#include <array>
#include <complex>
#include <functional>
#include <vector>

namespace boomdyn {

struct DampedModalResult {
  std::vector<double> dampedOmega;  // omega_d = |Im lambda| (rad/s); 0 for an overdamped mode
  std::vector<double> omega;        // undamped-equivalent |lambda| (rad/s), ascending; overdamped: sqrt(l1 l2)
  std::vector<double> dampingRatio; // zeta = -Re lambda / |lambda|; overdamped: -(l1 + l2) / (2 sqrt(l1 l2)) > 1
  // Decay rates -Re of the mode's two eigenvalues (1/s), slower first: equal
  // for an oscillating pair, -l1 and -l2 for an overdamped mode (two real
  // eigenvalues). A lone real eigenvalue of the PEP path: (-l, NaN).
  std::vector<std::array<double, 2>> decayRates;
  // The modes are the damped versions of the undamped modes given in
  // DampedModalOptions::undamped (classical damping), entry k of mode k;
  // false: the `count` eigenvalues of smallest |lambda| of the PEP solve.
  bool classical = false;
  std::vector<double> residuals;    // relative residual norms of the pairs
  // Real parts of the coordinate parts of the eigenvectors, gathered on rank 0
  // (empty elsewhere), max-norm 1 (as ModalResult::shapes).
  std::vector<std::vector<double>> shapes;
  // With DampedModalOptions::keepVectors (DampedModeRefiner::keepVectors from refinement): the
  // eigenvectors x = real + i imag (layout of the pencil's x, all ranks),
  // of the eigenvalue with Im lambda > 0.
  std::vector<PetscHandle<Vec>> real, imag;
  // The solve was stopped by DampedModalOptions::stop: nothing else is filled.
  bool interrupted = false;
};

struct DampedModalOptions {
  // Eigenvalues lambda nearest the target (rad/s, real) are found. Slightly
  // negative by default so that K - target D + target^2 M stays nonsingular
  // when the mechanism has rigid-body modes. -modal_pep_target overrides it.
  double target = -1.0;
  // Return the modes of one solve for 2 count eigenvalues, possibly fewer
  // than count, and skip pairs that did not converge, instead of asking for
  // more and stopping with an error. For tracking: with heavy damping most
  // modes are overdamped and real (they cluster near lambda = -1/eta), and
  // asking for more ran to the whole spectrum (15 solves, 25 s on the paper
  // scene with damping_ratio 0.02 at 1 Hz) and then met a pair with backward
  // error 1.5e-8.
  bool allowFewer = false;
  bool keepVectors = false; // fill DampedModalResult::real, imag
  std::function<bool()> stop; // as ModalOptions::stop (asked at every PEP iteration)
  // The undamped modes of the same state with their vectors (solveModes with
  // keepVectors), or null. Given, each is tried first as an eigenvector of
  // the quadratic problem (classical damping: stiffness- or mass-proportional,
  // Rayleigh): the roots of x^T (lambda^2 M + lambda D + K) x = 0, with the
  // multipliers scaled by least squares, are accepted when the residual of
  // the full problem is below 1e-8 for every mode; entry k is then the damped
  // version of undamped mode k, oscillating or overdamped (docs/model.md §5).
  const ModalResult *undamped = nullptr;
};

// D at (t, q, lambda) into a matrix made by assembler.createMatrix(): the
// Jacobian with Kinematics{cQ = 0, cV = 1, cA = 0} at zero velocity, no
// constraint blocks. First-order states (LuGre z) keep zero rate and no
// D entry: as in the symmetric pencil they are algebraic (infinite modes).
// sigma > 0: the constraint scale of the pencil at the same state
// (assemblePencil's sigmaOut), not computed again; 0: computed here.
PetscErrorCode assembleDamping(Assembler &assembler, double t, Vec q, Vec lambda, Mat D, double sigma = 0);

// Appends the mode lambda, x = xr + i xi to *result: omega_d, omega, zeta,
// the residual, the vector (keepVector) and the shape on rank 0 (the real
// part after rotating the largest coordinate entry to the real axis).
PetscErrorCode appendDampedMode(Assembler &assembler, std::complex<double> lambda, Vec xr, Vec xi, double residual,
                                bool keepVector, DampedModalResult *result);

// The `count` lowest damped modes (by |lambda|, the undamped-equivalent
// frequency; for light damping the order of omega_d too) of the linearization
// at (t, q, lambda): one of each conjugate pair; infinite, non-finite and
// non-oscillating (real, overdamped) eigenvalues are dropped. Options prefix
// "modal_": -modal_pep_target, -modal_pep_view, -modal_st_ksp_...
PetscErrorCode solveDampedModes(Assembler &assembler, double t, Vec q, Vec lambda, int count,
                                DampedModalResult *result, const DampedModalOptions &options = DampedModalOptions{});

} // namespace boomdyn
