// Frequencies and mode shapes of the system linearized at a state
// (model.md §5): the constrained pencil
//     A = [K_T  C_q^T; C_q 0],   B = [M 0; 0 0]
// with K_T the tangent of the internal, external and constraint forces
// (geometric terms from the multipliers included), solved with SLEPc
// Krylov-Schur, shift-and-invert around a target and MUMPS. Only scenes that
// ask for it create this object, so others never initialize SLEPc.
#pragma once

#include "boomdyn/assembler.hpp"

#include <vector>

namespace boomdyn {

struct ModalResult {
  std::vector<double> omega2;            // eigenvalues omega^2 (rad^2/s^2), ascending
  std::vector<double> frequencyHz;       // sqrt(max(omega2,0)) / 2 pi
  std::vector<std::vector<double>> shapes; // coordinates part, gathered on rank 0 (empty elsewhere), max-norm 1
  std::vector<double> residuals;         // relative residual norms ||A x - w B x|| / ||x||
};

// Linearize at coordinates q (layout of x, multiplier part ignored) with
// unscaled multipliers lambda (layout of x, coordinate part ignored) at time
// t, and find the `count` eigenvalues nearest the target (options prefix
// "modal_": -modal_eps_target, -modal_eps_view, -modal_st_ksp_... ).
PetscErrorCode solveModes(Assembler &assembler, double t, Vec q, Vec lambda, int count, ModalResult *result);

} // namespace boomdyn
