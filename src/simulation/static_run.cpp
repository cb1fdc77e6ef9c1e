// The static (and modal) analysis of a Simulation: equilibrium under the
// loads at statics.time by load stepping, a monitor call after every
// converged increment, the scene's modes at the start or at equilibrium.
#include "boomdyn/simulation.hpp"

namespace boomdyn {

PetscErrorCode Simulation::runStatic()
{
  RunState state;
  PetscHandle<Vec> noMultipliers;
  PetscFunctionBeginUser;
  PetscCall(assembler_.createVector(noMultipliers.address()));
  state.dynamic = false;
  state.q = x_;
  state.v = zero_;
  state.lambda = noMultipliers;
  for (auto &m : monitors_) PetscCall(m->start(state, false));
  const double t = scene_.statics.time;
  const bool modal = options_.modal && scene_.modal.count > 0;
  const bool modesAtStart = modal && scene_.modal.at == "start";
  if (modesAtStart) PetscCall(modalAnalysis(t, x_, noMultipliers));

  auto onLoadStep = [&](const LoadStepInfo &s) -> PetscErrorCode {
    AssemblyContext ctx;
    PetscReal violation;
    PetscFunctionBeginUser;
    ctx.t = t;
    ctx.loadFactor = s.loadFactor;
    PetscCall(assembler_.setOffsets(nullptr, nullptr, nullptr));
    PetscCall(assembler_.diagnostics(ctx, x_, &state.energy, &violation));
    state.violation = violation;
    state.t = s.loadFactor;
    state.iterations = s.iterations;
    state.step = ++outcome_.steps;
    state.last = s.loadFactor >= 1;
    state.lambda = statics_->multipliers(); // of this increment (output channels)
    std::string unused; // static runs have no checks that end them
    PetscCall(afterStep(state, &unused));
    PetscFunctionReturn(0);
  };
  PetscBool converged = PETSC_TRUE;
  PetscCall(statics_->solve(t, scene_.statics.load_steps, x_, onLoadStep, &converged));
  if (!converged) outcome_.status = "failed: " + statics_->failure();
  state.t = t;
  state.lambda = statics_->multipliers();
  outcome_.endTime = t;
  if (converged && modal && !modesAtStart) PetscCall(modalAnalysis(t, x_, statics_->multipliers()));
  PetscCall(finish(state));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
