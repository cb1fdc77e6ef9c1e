// TS type boomalpha and TSAdapt type boomalpha: see ts_boomalpha.hpp.
// PETSc's private headers give the type access to ts->ops and the TS fields
// (time, step, counters, limits), as PETSc's own TS implementations use them.
#include "boomdyn/ts_boomalpha.hpp"

#include <petsc/private/tsimpl.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace boomdyn {

namespace {

BoomAlphaRun *runOf(TS ts) { return static_cast<BoomAlphaRun *>(ts->data); }

// Ends the run: ts->reason < 0 and the message the caller reports.
void fail(TS ts, TSConvergedReason reason, const std::string &message)
{
  ts->reason = reason;
  runOf(ts)->failure = message;
}

// Before another attempt of a rejected step: a stop request (SIGINT, SIGTERM)
// ends the run now, at the last accepted step, rather than after all the
// cuts down to dt_min.
bool stopBeforeRetry(TS ts)
{
  BoomAlphaRun *run = runOf(ts);
  if (!run->stop || !run->stop()) return false;
  run->interrupted = true;
  ts->reason = TS_CONVERGED_USER;
  return true;
}

PetscErrorCode stepBody(TS ts)
{
  BoomAlphaRun *run = runOf(ts);
  TSAdapt adapt;
  PetscBool ours;
  PetscFunctionBeginUser;
  GeneralizedAlpha &integrator = *run->integrator;
  StepperState &st = *run->state;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(PetscObjectTypeCompare((PetscObject)adapt, TSADAPTBOOMALPHA, &ours));
  run->accepted = false;
  PetscInt rejections = 0; // in this TSStep, for -ts_max_reject
  for (;;) {
    // A step that would leave less than a hundredth of itself before max_time
    // or a drive's kink is stretched (by at most 1 %) to end there: what it
    // leaves is a sliver step, and a sliver of h gives forces and multipliers
    // of order m/sliver^2. The sum of many steps misses max_time by rounding
    // (a last step of 1e-12 s gave MN forces and nonsense in the last output
    // row), and an adaptive step can end just short of a kink (a landing
    // step of 1e-6 h whose Newton failure was then blamed on dt_min).
    const double sliver = 1e-2;
    const double h = st.h;
    const double remaining = ts->max_time - integrator.time();
    const bool match = ts->exact_final_time == TS_EXACTFINALTIME_MATCHSTEP;
    // A drive's kink within this step (or the sliver beyond it) ends the
    // step, and the integrator restarts there (-boom_kink_restart); one at
    // t_end is left to the final-time matching.
    const double kink = integrator.nextBreakpoint();
    const bool land = kink < ts->max_time - run->endTolerance && kink - integrator.time() <= h * (1.0 + sliver);
    const double attempt = land ? kink - integrator.time() : match && remaining <= h * (1.0 + sliver) ? remaining : h;
    StepResult &r = run->last;
    r = StepResult{};
    run->attempt = attempt;
    if (land) PetscCall(integrator.stepToBreakpoint(&r));
    else PetscCall(integrator.step(attempt, &r));
    ts->snes_its += r.iterations;
    if (!r.event.empty()) { // no step size helps: stop and say why
      fail(ts, TS_DIVERGED_STEP_REJECTED, r.event);
      break;
    }
    if (!r.converged && !r.errorRejected) {
      // Newton failed: retry with a smaller step (what TSAdaptCheckStage
      // does for PETSc's types, with the message boomdyn users know).
      ++st.rejected, ++ts->reject, ++ts->num_snes_failures;
      st.h = attempt * adapt->scale_solve_failed;
      st.successesSinceCut = 0;
      // Reported even in quiet runs: a rejected step is something the user should know about.
      PetscCall(PetscPrintf(PetscObjectComm((PetscObject)ts),
                            "warning: step at t = %g s with h = %g s rejected (%s after %" PetscInt_FMT
                            " Newton iterations); retrying with h = %g s\n",
                            integrator.time(), attempt, SNESConvergedReasons[r.reason], r.iterations, st.h));
      std::ostringstream os;
      os << "Newton failed at t = " << integrator.time() << " s (" << SNESConvergedReasons[r.reason] << ")";
      if (ts->max_snes_failures > 0 && ts->num_snes_failures >= ts->max_snes_failures) {
        os << "; -ts_max_snes_failures " << ts->max_snes_failures << " reached";
        fail(ts, TS_DIVERGED_NONLINEAR_SOLVE, os.str());
        break;
      }
      if (st.h < run->dtMin) {
        os << " and the step would fall below dt_min = " << run->dtMin << " s";
        fail(ts, TS_DIVERGED_NONLINEAR_SOLVE, os.str());
        break;
      }
      if (ts->max_reject >= 0 && ++rejections > ts->max_reject) {
        os << " after " << rejections << " rejected attempts of this step, more than -ts_max_reject " << ts->max_reject;
        fail(ts, TS_DIVERGED_STEP_REJECTED, os.str());
        break;
      }
      if (stopBeforeRetry(ts)) break;
      ts->time_step = st.h;
      continue;
    }
    // Converged: the adapt accepts the step or asks for a smaller one
    // (boomalpha: from the error estimate; it also sets the next step).
    PetscReal next = attempt;
    PetscBool accept = PETSC_FALSE;
    ts->time_step = attempt; // TSAdaptChoose reads the step just taken here
    PetscCall(TSAdaptChoose(adapt, ts, attempt, nullptr, &next, &accept));
    PetscCheck(accept == (r.errorRejected ? PETSC_FALSE : PETSC_TRUE), PetscObjectComm((PetscObject)ts),
               PETSC_ERR_USER_INPUT,
               "-boom_adaptive_tol needs -ts_adapt_type %s: the error estimate decides whether a step is taken",
               TSADAPTBOOMALPHA);
    if (!ours) st.h = next; // the boomalpha adapt sets st.h itself (PETSc may shorten next to hit max_time)
    // A step shortened to land on a kink does not shorten the next one.
    if (accept && land) st.h = std::max(st.h, h);
    if (!accept) {
      ++st.rejected, ++ts->reject;
      if (st.h < run->dtMin) {
        std::ostringstream os;
        os << "the error estimate " << r.errorEstimate << " at t = " << integrator.time()
           << " s stays above -boom_adaptive_tol " << integrator.errorTolerance() << " down to dt_min = " << run->dtMin
           << " s";
        fail(ts, TS_DIVERGED_STEP_REJECTED, os.str());
        break;
      }
      if (ts->max_reject >= 0 && ++rejections > ts->max_reject) {
        std::ostringstream os;
        os << "the error estimate at t = " << integrator.time() << " s rejected " << rejections
           << " attempts of this step, more than -ts_max_reject " << ts->max_reject;
        fail(ts, TS_DIVERGED_STEP_REJECTED, os.str());
        break;
      }
      if (stopBeforeRetry(ts)) break;
      ts->time_step = st.h;
      continue;
    }
    ++st.steps;
    st.newtonIterations += r.iterations;
    ts->ptime = integrator.time();
    ts->time_step = st.h;
    run->accepted = true;
    if (ts->ptime >= ts->max_time - run->endTolerance) ts->reason = TS_CONVERGED_TIME;
    break;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TSStep_BoomAlpha(TS ts)
{
  PetscFunctionBeginUser;
  try {
    PetscCall(stepBody(ts));
  } catch (...) {
    runOf(ts)->exception = std::current_exception();
    ts->reason = TS_DIVERGED_STEP_REJECTED;
    runOf(ts)->accepted = false;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TSSetUp_BoomAlpha(TS ts)
{
  TSAdapt adapt;
  PetscBool ours, none;
  PetscFunctionBeginUser;
  MPI_Comm comm = PetscObjectComm((PetscObject)ts);
  PetscCheck(runOf(ts), comm, PETSC_ERR_ORDER, "TS type %s needs TSBoomAlphaSetRun() before TSSetUp()", TSBOOMALPHA);
  PetscCheck(ts->exact_final_time != TS_EXACTFINALTIME_INTERPOLATE, comm, PETSC_ERR_USER_INPUT,
             "-ts_exact_final_time interpolate is not supported by -ts_type %s (the index-3 state has no "
             "interpolant that keeps the constraints): use matchstep (default) or stepover",
             TSBOOMALPHA);
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(PetscObjectTypeCompare((PetscObject)adapt, TSADAPTBOOMALPHA, &ours));
  PetscCall(PetscObjectTypeCompare((PetscObject)adapt, TSADAPTNONE, &none));
  PetscCheck(ours || none, comm, PETSC_ERR_USER_INPUT,
             "-ts_adapt_type %s is not supported by -ts_type %s: use %s (step cuts and regrowth, and the "
             "Zienkiewicz-Xie error estimate with -boom_adaptive_tol) or none (fixed steps, cut only when Newton fails)",
             ((PetscObject)adapt)->type_name, TSBOOMALPHA, TSADAPTBOOMALPHA);
  PetscCheck(ours || !(runOf(ts)->integrator->errorTolerance() > 0), comm, PETSC_ERR_USER_INPUT,
             "-boom_adaptive_tol needs -ts_adapt_type %s, not %s", TSADAPTBOOMALPHA, ((PetscObject)adapt)->type_name);
  // PETSc accepts a factor of exactly 1; a step that Newton cannot solve would
  // then be retried at the same h forever, never reaching dt_min.
  PetscCheck(adapt->scale_solve_failed < 1, comm, PETSC_ERR_USER_INPUT,
             "-ts_adapt_scale_solve_failed %g must be less than 1: a step that Newton cannot solve is retried with h "
             "times this factor until it converges or falls below dt_min, and at 1 it never shrinks",
             (double)adapt->scale_solve_failed);
  PetscFunctionReturn(0);
}

PetscErrorCode TSView_BoomAlpha(TS ts, PetscViewer viewer)
{
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  const BoomAlphaRun *run = runOf(ts);
  if (!ascii || !run) PetscFunctionReturn(0);
  const GeneralizedAlpha &integrator = *run->integrator;
  const AlphaParameters &p = integrator.parameters();
  PetscCall(PetscViewerASCIIPrintf(viewer, "  index-3 constrained generalized-alpha (Arnold & Bruls 2007), scaled "
                                           "multipliers, constraints at t_{n+1}\n"));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  alpha_m=%g alpha_f=%g beta=%g gamma=%g\n", p.alpha_m, p.alpha_f, p.beta,
                                   p.gamma));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  step limits: dt_min=%g dt=%g; error tolerance (-boom_adaptive_tol) %g\n",
                                   run->dtMin, run->dt, integrator.errorTolerance()));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(SNESView(const_cast<GeneralizedAlpha &>(integrator).newton().snes(), viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode TSDestroy_BoomAlpha(TS ts)
{
  PetscFunctionBeginUser;
  ts->data = nullptr; // the run belongs to the caller
  PetscFunctionReturn(0);
}

PetscErrorCode TSCreate_BoomAlpha(TS ts)
{
  PetscFunctionBeginUser;
  ts->ops->step = TSStep_BoomAlpha;
  ts->ops->setup = TSSetUp_BoomAlpha;
  ts->ops->view = TSView_BoomAlpha;
  ts->ops->destroy = TSDestroy_BoomAlpha;
  ts->default_adapt_type = TSADAPTBOOMALPHA;
  ts->data = nullptr;
  PetscFunctionReturn(0);
}

// The step controller: after a converged attempt of size h, accept it or
// not and choose the next step (stored in the run's StepperState).
PetscErrorCode TSAdaptChoose_BoomAlpha(TSAdapt adapt, TS ts, PetscReal h, PetscInt *next_sc, PetscReal *next_h,
                                       PetscBool *accept, PetscReal *wlte, PetscReal *wltea, PetscReal *wlter)
{
  PetscBool boom;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSBOOMALPHA, &boom));
  PetscCheck(boom && runOf(ts), PetscObjectComm((PetscObject)adapt), PETSC_ERR_USER_INPUT,
             "-ts_adapt_type %s works only with -ts_type %s", TSADAPTBOOMALPHA, TSBOOMALPHA);
  const BoomAlphaRun &run = *runOf(ts);
  const StepResult &r = run.last;
  StepperState &st = *run.state;
  const double tol = run.integrator->errorTolerance();
  // Step-size factor from the error estimate (third-order local error in h).
  auto factor = [&](double err) { return err > 0 ? 0.9 * std::cbrt(tol / err) : 2.0; };
  *next_sc = 0;
  *wlte = tol > 0 ? r.errorEstimate / tol : -1.0;
  *wltea = *wlter = -1.0;
  if (r.errorRejected) {
    // Adaptive steps: too large an error is a normal rejection, not a warning.
    *accept = PETSC_FALSE;
    st.h = h * std::clamp(factor(r.errorEstimate), 0.2, 0.9);
    PetscCall(PetscInfo(nullptr, "t = %g s: step %g s rejected, error estimate %g > %g; retrying with %g s\n",
                        run.integrator->time(), h, r.errorEstimate, tol, st.h));
  } else {
    *accept = PETSC_TRUE;
    if (tol > 0) {
      // Adaptive: the next step from the error estimate, at most the nominal
      // dt. An accepted step is never followed by a smaller one, and h grows
      // only by 1.5x or more, so that a reused Jacobian (keyed to h) stays
      // valid over runs of steps.
      const double f = factor(r.errorEstimate);
      if (f >= 1.5) st.h = std::min(run.dt, h * std::min(f, 2.0));
    } else if (st.h < run.dt && ++st.successesSinceCut >= 4) {
      // Grow back towards the nominal dt after a few successes at a cut step.
      st.h = std::min(run.dt, 2.0 * st.h);
      st.successesSinceCut = 0;
    }
  }
  *next_h = st.h;
  PetscFunctionReturn(0);
}

PetscErrorCode TSAdaptCreate_BoomAlpha(TSAdapt adapt)
{
  PetscFunctionBeginUser;
  adapt->ops->choose = TSAdaptChoose_BoomAlpha;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode registerBoomAlpha()
{
  static bool registered = false;
  PetscFunctionBeginUser;
  if (registered) PetscFunctionReturn(0);
  PetscCall(TSRegister(TSBOOMALPHA, TSCreate_BoomAlpha));
  PetscCall(TSAdaptRegister(TSADAPTBOOMALPHA, TSAdaptCreate_BoomAlpha));
  registered = true;
  PetscFunctionReturn(0);
}

PetscErrorCode TSBoomAlphaSetRun(TS ts, BoomAlphaRun *run)
{
  PetscBool boom;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSBOOMALPHA, &boom));
  PetscCheck(boom, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG, "TSBoomAlphaSetRun() needs a TS of type %s",
             TSBOOMALPHA);
  ts->data = run;
  PetscFunctionReturn(0);
}

} // namespace boomdyn
