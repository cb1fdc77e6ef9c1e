#include "boomdyn/static_solver.hpp"

#include "boomdyn/log_events.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace boomdyn {

PetscErrorCode StaticSolver::setUp()
{
  PetscFunctionBeginUser;
  for (const auto &b : assembler_.model().bodies()) structureSize_ = std::max(structureSize_, b->length());
  firstOrder_ = assembler_.model().firstOrderCoordinates();
  std::sort(firstOrder_.begin(), firstOrder_.end());
  PetscCall(assembler_.createVector(lambda_.address()));
  PetscCall(assembler_.createVector(backup_.address()));
  PetscCall(newton_.setUp(assembler_, "static_", 50, false));
  PetscCall(charts_.setUp(backup_));
  PetscFunctionReturn(0);
}

PetscErrorCode StaticSolver::solve(double t, int loadSteps, Vec x,
                                   const std::function<PetscErrorCode(const LoadStepInfo &)> &onStep,
                                   PetscBool *converged)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().statics, 0, 0, 0, 0));
  PetscReal mass, stiffness;
  PetscCall(assembler_.characteristicScales(x, &mass, &stiffness));
  sigma_ = stiffness > 0 ? stiffness : 1.0;
  newton_.ctx = AssemblyContext{};
  newton_.ctx.t = t;
  newton_.ctx.kin = {1.0, 0.0, 0.0};
  newton_.ctx.sigma = sigma_;
  PetscCall(assembler_.setOffsets(nullptr, nullptr, nullptr));

  const double nominal = 1.0 / loadSteps, minIncrement = nominal / 1024.0;
  double done = 0.0, increment = nominal;
  int successes = 0;
  *converged = PETSC_TRUE;
  while (done < 1.0 - 1e-14) {
    const double target = std::min(1.0, done + increment);
    newton_.ctx.loadFactor = target;
    PetscCall(VecCopy(x, backup_));
    PetscInt its;
    SNESConvergedReason reason;
    PetscCall(newton_.solve(x, &its, &reason));
    // A singular stiffness (a mechanism without supports, redundant
    // constraints) can let Newton "converge" to absurd displacements: a
    // solution a million times the structure's size is no equilibrium.
    // First-order states are left out: a cylinder's pressures (Pa) are no
    // displacements.
    PetscReal size = 0;
    {
      PetscInt lo, hi;
      const PetscScalar *xa;
      PetscCall(VecGetOwnershipRange(x, &lo, &hi));
      PetscCall(VecGetArrayRead(x, &xa));
      std::size_t k = 0;
      for (PetscInt g = lo; g < hi; ++g) {
        while (k < firstOrder_.size() && firstOrder_[k] < g) ++k;
        if (k < firstOrder_.size() && firstOrder_[k] == g) continue;
        size = std::max(size, std::abs(xa[g - lo]));
      }
      PetscCall(VecRestoreArrayRead(x, &xa));
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &size, 1, MPIU_REAL, MPI_MAX, assembler_.comm()));
    }
    if (reason > 0 && !(size < 1e6 * (1.0 + structureSize_))) {
      *converged = PETSC_FALSE;
      char grown[32];
      std::snprintf(grown, sizeof grown, "%.3g", (double)size);
      failure_ = std::string("no static equilibrium: the solution grew to ") + grown +
                 " (singular stiffness: a body or motion without support, or redundant constraints)";
      PetscCall(VecCopy(backup_, x));
      break;
    }
    if (reason > 0) {
      done = target;
      PetscCall(charts_.rechart(x, done));
      // Unscaled multipliers of this increment, for the caller's outputs.
      PetscCall(VecSet(lambda_, 0.0));
      PetscCall(assembler_.copyMultipliers(x, lambda_, sigma_));
      bool stop = false;
      if (onStep) PetscCall(onStep({done, its, &stop}));
      if (stop) break; // interrupted: x holds the last converged increment
      // After a cut, grow back towards the nominal increment.
      if (increment < nominal && ++successes >= 2) increment = std::min(nominal, 2.0 * increment), successes = 0;
      continue;
    }
    successes = 0;
    PetscCall(VecCopy(backup_, x));
    increment *= 0.5;
    PetscCall(PetscInfo(nullptr, "load increment to %g failed (%s); halving to %g\n", (double)target,
                        SNESConvergedReasons[reason], increment));
    if (increment < minIncrement) {
      *converged = PETSC_FALSE;
      failure_ = "static solve failed at load factor " + std::to_string(done + 2 * increment) + " (" +
                 SNESConvergedReasons[reason] + ")";
      break;
    }
  }
  // Unscaled multipliers.
  PetscCall(VecSet(lambda_, 0.0));
  PetscCall(assembler_.copyMultipliers(x, lambda_, sigma_));
  PetscCall(PetscLogEventEnd(logEvents().statics, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
