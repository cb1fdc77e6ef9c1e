#include "boomdyn/time_stepper.hpp"

#include <exception>
#include <memory>

namespace boomdyn {

namespace {

struct TSDestroyer {
  void operator()(TS ts) const { (void)TSDestroy(&ts); }
};
using TSHandle = std::unique_ptr<std::remove_pointer_t<TS>, TSDestroyer>;

// What integrate() hands to the post-step function (the TS's application context).
struct RunCallbacks {
  BoomAlphaRun run;
  const std::function<PetscErrorCode(const StepInfo &)> *onStep = nullptr;
  const std::function<bool()> *stop = nullptr;
  double tEnd = 0;
  std::string failure;      // from onStep
  bool interrupted = false; // stop() said so
};

// After every TSStep: the caller's onStep and stop() for an accepted step.
// Exceptions from them are kept and rethrown after TSSolve (they must not
// unwind through PETSc's C frames).
PetscErrorCode afterStep(TS ts)
{
  RunCallbacks *cb;
  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &cb));
  BoomAlphaRun &run = cb->run;
  if (!run.accepted || run.exception) PetscFunctionReturn(0);
  StepInfo info;
  info.step = run.state->steps;
  info.t = run.integrator->time();
  info.h = run.attempt;
  info.iterations = run.last.iterations;
  info.rejected = run.state->rejected;
  info.stepper = run.state;
  try {
    if (*cb->onStep) PetscCall((*cb->onStep)(info));
    if (!info.failure.empty()) {
      cb->failure = info.failure;
      PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
    } else if (*cb->stop && (*cb->stop)() && run.integrator->time() < cb->tEnd - run.endTolerance) {
      cb->interrupted = true;
      PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
    }
  } catch (...) {
    run.exception = std::current_exception();
    PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
  }
  PetscFunctionReturn(0);
}

// Options that have a meaning for PETSc's own adaptive types but none here.
PetscErrorCode rejectInapplicableOptions(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  for (const char *name : {"-ts_rtol", "-ts_atol"}) {
    PetscBool set;
    PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &set));
    PetscCheck(!set, comm, PETSC_ERR_USER_INPUT,
               "%s does not apply to -ts_type %s: its error control is -boom_adaptive_tol (a bound on the local "
               "position error)",
               name, TSBOOMALPHA);
  }
  PetscFunctionReturn(0);
}

// A TS of type boomalpha on the integrator, with boomdyn's defaults, then
// the user's -ts_ options (which are checked: no other TS or adapt type).
PetscErrorCode createTS(RunCallbacks &cb, const DynamicSpec &spec, TSHandle *out)
{
  TS ts;
  TSAdapt adapt;
  PetscBool boom;
  PetscFunctionBeginUser;
  GeneralizedAlpha &integrator = *cb.run.integrator;
  const StepperState &st = *cb.run.state;
  MPI_Comm comm = PetscObjectComm((PetscObject)integrator.positions());
  PetscCall(registerBoomAlpha());
  PetscCall(TSCreate(comm, &ts));
  out->reset(ts);
  PetscCall(TSSetType(ts, TSBOOMALPHA));
  PetscCall(TSBoomAlphaSetRun(ts, &cb.run));
  PetscCall(TSSetApplicationContext(ts, &cb));
  PetscCall(TSSetPostStep(ts, afterStep));
  // The solution is the integrator's own position vector: always current, no copies.
  PetscCall(TSSetSolution(ts, integrator.positions()));
  PetscCall(TSSetMaxTime(ts, spec.t_end));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  // Cuts are bounded by dt_min, not by counts (PETSc's defaults stop at the
  // first Newton failure); failures are reported, not raised as errors.
  PetscCall(TSSetMaxSNESFailures(ts, -1));
  PetscCall(TSSetMaxStepRejections(ts, -1));
  PetscCall(TSSetErrorIfStepFails(ts, PETSC_FALSE));
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptSetType(adapt, TSADAPTBOOMALPHA));
  PetscCall(TSAdaptSetScaleSolveFailed(adapt, 0.5));
  // The scene's limits, shown by -ts_view (PETSc wants dt_min < dt_max
  // strictly; a scene may forbid cuts with dt_min = dt).
  if (spec.dt_min < spec.dt) PetscCall(TSAdaptSetStepLimits(adapt, spec.dt_min, spec.dt));
  PetscCall(rejectInapplicableOptions(comm));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSBOOMALPHA, &boom));
  if (!boom) {
    TSType type;
    PetscCall(TSGetType(ts, &type));
    SETERRQ(comm, PETSC_ERR_USER_INPUT,
            "-ts_type %s is not supported: boomdyn integrates its index-3 constrained equations only with -ts_type %s "
            "(PETSc's implicit types, TSALPHA2 included, treat multipliers as differential unknowns and lose "
            "second order)",
            type, TSBOOMALPHA);
  }
  // Time, step and end come from the integrator and the scene (where
  // -ts_dt and -ts_max_time have been applied) and from a restored stepper.
  PetscCall(TSSetTime(ts, integrator.time()));
  PetscCall(TSSetStepNumber(ts, st.steps));
  PetscCall(TSSetTimeStep(ts, st.h));
  PetscCall(TSSetMaxTime(ts, spec.t_end));
  // -ts_adapt_dt_min and -ts_adapt_dt_max override the scene's dt_min and
  // the ceiling of regrowth (the scene's dt).
  PetscReal dtMin, dtMax;
  PetscBool setMin, setMax;
  const char *prefix;
  PetscCall(TSAdaptGetStepLimits(adapt, &dtMin, &dtMax));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)adapt, &prefix));
  PetscCall(PetscOptionsHasName(nullptr, prefix, "-ts_adapt_dt_min", &setMin));
  PetscCall(PetscOptionsHasName(nullptr, prefix, "-ts_adapt_dt_max", &setMax));
  cb.run.dtMin = setMin ? dtMin : spec.dt_min;
  cb.run.dt = setMax ? dtMax : spec.dt;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode integrate(GeneralizedAlpha &integrator, const DynamicSpec &spec,
                         const std::function<PetscErrorCode(const StepInfo &)> &onStep, RunSummary *summary,
                         StepperState *state, const std::function<bool()> &stop)
{
  PetscFunctionBeginUser;
  StepperState local;
  StepperState &st = state ? *state : local;
  if (st.h <= 0) st.h = spec.dt;
  *summary = RunSummary{};
  RunCallbacks cb;
  cb.run.integrator = &integrator;
  cb.run.state = &st;
  // Stop within a hair of t_end rather than take a sliver of a step.
  cb.run.endTolerance = 1e-9 * spec.dt;
  cb.onStep = &onStep;
  cb.stop = &stop;
  cb.run.stop = stop;
  cb.tEnd = spec.t_end;
  TSConvergedReason reason = TS_CONVERGED_TIME;
  if (integrator.time() < spec.t_end - cb.run.endTolerance) {
    TSHandle ts;
    PetscCall(createTS(cb, spec, &ts));
    PetscCall(TSSolve(ts.get(), nullptr));
    PetscCall(TSGetConvergedReason(ts.get(), &reason));
  }
  if (cb.run.exception) std::rethrow_exception(cb.run.exception);
  summary->steps = st.steps;
  summary->rejected = st.rejected;
  summary->newtonIterations = st.newtonIterations;
  if (!cb.failure.empty()) {
    summary->failure = cb.failure;
  } else if (cb.interrupted || cb.run.interrupted) {
    summary->interrupted = true;
  } else if (reason < 0) {
    summary->failure = cb.run.failure.empty() ? TSConvergedReasons[reason] : cb.run.failure;
  } else {
    summary->completed = true;
    summary->stepLimit = integrator.time() < spec.t_end - cb.run.endTolerance;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode saveStepper(StateWriter &out, const StepperState &state)
{
  PetscFunctionBeginUser;
  out.addScalar("stepper.h", state.h);
  out.addScalar("stepper.successes", state.successesSinceCut);
  out.addScalar("stepper.steps", state.steps);
  out.addScalar("stepper.rejected", state.rejected);
  out.addScalar("stepper.newton", state.newtonIterations);
  PetscFunctionReturn(0);
}

PetscErrorCode restoreStepper(const StateReader &in, StepperState *state)
{
  PetscFunctionBeginUser;
  state->h = in.scalar("stepper.h");
  state->successesSinceCut = static_cast<int>(in.scalar("stepper.successes"));
  state->steps = static_cast<PetscInt>(in.scalar("stepper.steps"));
  state->rejected = static_cast<PetscInt>(in.scalar("stepper.rejected"));
  state->newtonIterations = static_cast<PetscInt>(in.scalar("stepper.newton"));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
