// The static (and modal) analysis of a Simulation: equilibrium under the
// loads at statics.time by load stepping, a monitor call after every
// converged increment, the scene's modes at the start or at equilibrium.
#include "boomdyn/simulation.hpp"

namespace boomdyn {

PetscErrorCode Simulation::runStatic(const std::function<bool()> &stop)
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
  const double t = scene().statics.time;
  const bool modal = options_.modal && scene().modal.count > 0;
  const bool modesAtStart = modal && scene().modal.at == "start";
  // Interrupts are honoured between load increments, before an
  // eigen-analysis and at every iteration of its solver.
  bool interrupted = false;
  auto stopRequested = [&] { return interrupted = interrupted || (stop && stop()); };
  if (modesAtStart && !stopRequested()) {
    bool stopped = false;
    PetscCall(modalAnalysis(t, x_, noMultipliers, stopRequested, &stopped));
    interrupted = interrupted || stopped;
  }

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
    state.last = s.loadFactor >= 1.0 - 1e-14; // the solver's own end test (ten increments of 0.1 end at 1 - 1e-16)
    state.lambda = statics_->multipliers(); // of this increment (output channels)
    std::string unused; // static runs have no checks that end them
    PetscCall(afterStep(state, &unused));
    if (!state.last && s.stop) *s.stop = stopRequested();
    PetscFunctionReturn(0);
  };
  PetscBool converged = PETSC_TRUE;
  if (!interrupted) PetscCall(statics_->solve(t, scene().statics.load_steps, x_, onLoadStep, &converged));
  if (!converged) outcome_.status = "failed: " + statics_->failure();
  else if (interrupted || (modal && !modesAtStart && stopRequested()))
    outcome_.status = "interrupted", converged = PETSC_FALSE; // no modes after an interrupt
  state.t = t;
  state.lambda = statics_->multipliers();
  outcome_.endTime = t;
  if (converged && modal && !modesAtStart) {
    bool stopped = false;
    PetscCall(modalAnalysis(t, x_, statics_->multipliers(), stopRequested, &stopped));
    if (stopped) outcome_.status = "interrupted";
  }
  PetscCall(finish(state));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
