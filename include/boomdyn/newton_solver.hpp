// SNES on the assembled saddle-point system, shared by statics, dynamics and
// the consistent-acceleration solve. Defaults: Newton with a basic (full)
// step, KSPPREONLY + LU from MUMPS; every one of them can be changed with
// the usual -snes_/-ksp_/-pc_ options under the solver's prefix.
#pragma once

#include "boomdyn/assembler.hpp"

#include <petscsnes.h>

namespace boomdyn {

class NewtonSolver {
public:
  NewtonSolver() = default;
  ~NewtonSolver();
  NewtonSolver(const NewtonSolver &) = delete;
  NewtonSolver &operator=(const NewtonSolver &) = delete;

  // prefix may be null (then -snes_monitor etc. apply directly).
  PetscErrorCode setUp(Assembler &assembler, const char *prefix, PetscInt maxIterations);
  // Solve from the initial guess in x; the solution overwrites x.
  PetscErrorCode solve(Vec x, PetscInt *iterations, SNESConvergedReason *reason);

  AssemblyContext ctx; // set by the caller before solve()
  SNES snes() const { return snes_; }
  Mat jacobian() const { return J_; }

private:
  static PetscErrorCode formFunction(SNES, Vec x, Vec F, void *self);
  static PetscErrorCode formJacobian(SNES, Vec x, Mat J, Mat P, void *self);

  Assembler *assembler_ = nullptr;
  int patternVersion_ = 0;
  SNES snes_ = nullptr;
  Mat J_ = nullptr;
  Vec F_ = nullptr;
};

} // namespace boomdyn
