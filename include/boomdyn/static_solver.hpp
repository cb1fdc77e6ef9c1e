// Static equilibrium f_int(q) - load * Q_ext + C_q^T lambda = 0, C(q, t) = 0 by
// Newton (SNES) with load stepping: the load factor goes from 0 to 1 in equal
// increments; an increment that fails is halved and retried (up to a limit),
// and a final failure is reported, never accepted. After every converged
// increment the spatial beams rebase their node references (a change of
// chart, PostStepHook::changesChartOnly).
#pragma once

#include "boomdyn/newton_solver.hpp"
#include "boomdyn/petsc_handle.hpp"
#include "boomdyn/slider_tracker.hpp"

#include <functional>
#include <string>
#include <vector>

namespace boomdyn {

struct LoadStepInfo {
  double loadFactor;
  PetscInt iterations;
  bool *stop = nullptr; // onStep sets *stop: the solve ends after this increment (an interrupt)
};

class StaticSolver {
public:
  explicit StaticSolver(Assembler &assembler) : assembler_(assembler), charts_(assembler) {}
  StaticSolver(const StaticSolver &) = delete;
  StaticSolver &operator=(const StaticSolver &) = delete;

  PetscErrorCode setUp();
  // Solve from the coordinates in x (layout of x) at time t. On return x
  // holds [q | lambda_hat] and multipliers() the unscaled multipliers.
  // onStep (optional) is called after every converged load increment.
  PetscErrorCode solve(double t, int loadSteps, Vec x, const std::function<PetscErrorCode(const LoadStepInfo &)> &onStep,
                       PetscBool *converged);
  Vec multipliers() const { return lambda_; }
  // Why the last solve failed (empty when it converged).
  const std::string &failure() const { return failure_; }
  double sigma() const { return sigma_; }

private:
  Assembler &assembler_;
  SliderTracker charts_; // runs the chart-changing hooks (beam rebasing) after each converged increment
  NewtonSolver newton_;
  PetscHandle<Vec> lambda_, backup_;
  double sigma_ = 1, structureSize_ = 0;
  std::vector<PetscInt> firstOrder_; // sorted: left out of the size test
  std::string failure_;
};

} // namespace boomdyn
