#include "boomdyn/time_stepper.hpp"

#include <algorithm>
#include <sstream>

namespace boomdyn {

PetscErrorCode integrate(GeneralizedAlpha &integrator, const DynamicSpec &spec,
                         const std::function<PetscErrorCode(const StepInfo &)> &onStep, RunSummary *summary,
                         StepperState *state, const std::function<bool()> &stop)
{
  PetscFunctionBeginUser;
  StepperState local;
  StepperState &st = state ? *state : local;
  if (st.h <= 0) st.h = spec.dt;
  *summary = RunSummary{};
  double &h = st.h;
  int &successesSinceCut = st.successesSinceCut;
  summary->rejected = st.rejected;
  summary->newtonIterations = st.newtonIterations;
  StepInfo info;
  info.step = st.steps;
  // Stop within a hair of t_end rather than take a sliver of a step.
  const double tolerance = 1e-9 * spec.dt;
  while (integrator.time() < spec.t_end - tolerance) {
    // A step that would leave less than a millionth of itself to go is
    // stretched to end on t_end: the sum of many steps misses t_end by
    // rounding, and a last step of 1e-12 s gave forces and multipliers of
    // order m/h^2 (MN) and nonsense in the last output row.
    const double remaining = spec.t_end - integrator.time();
    const double attempt = remaining <= h * (1.0 + 1e-6) ? remaining : h;
    StepResult r;
    PetscCall(integrator.step(attempt, &r));
    if (!r.event.empty()) { // no step size helps: stop and say why
      summary->failure = r.event;
      summary->steps = info.step;
      PetscFunctionReturn(0);
    }
    const double tol = integrator.errorTolerance();
    // Step-size factor from the error estimate (third-order local error in h).
    auto factor = [&](double err) { return err > 0 ? 0.9 * std::cbrt(tol / err) : 2.0; };
    if (r.errorRejected) {
      // Adaptive steps: too large an error is a normal rejection, not a warning.
      ++summary->rejected;
      st.rejected = summary->rejected;
      h = attempt * std::clamp(factor(r.errorEstimate), 0.2, 0.9);
      PetscCall(PetscInfo(nullptr, "t = %g s: step %g s rejected, error estimate %g > %g; retrying with %g s\n",
                          integrator.time(), attempt, r.errorEstimate, tol, h));
      if (h < spec.dt_min) {
        std::ostringstream os;
        os << "the error estimate " << r.errorEstimate << " at t = " << integrator.time()
           << " s stays above -boom_adaptive_tol " << tol << " down to dt_min = " << spec.dt_min << " s";
        summary->failure = os.str();
        summary->steps = info.step;
        PetscFunctionReturn(0);
      }
      continue;
    }
    if (!r.converged) {
      ++summary->rejected;
      h = 0.5 * attempt;
      successesSinceCut = 0;
      // Reported even in quiet runs: a rejected step is something the user should know about.
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "warning: step at t = %g s with h = %g s rejected (%s after %" PetscInt_FMT
                            " Newton iterations); retrying with h = %g s\n",
                            integrator.time(), attempt, SNESConvergedReasons[r.reason], r.iterations, h));
      st.rejected = summary->rejected;
      if (h < spec.dt_min) {
        std::ostringstream os;
        os << "Newton failed at t = " << integrator.time() << " s (" << SNESConvergedReasons[r.reason]
           << ") and the step would fall below dt_min = " << spec.dt_min << " s";
        summary->failure = os.str();
        summary->steps = info.step;
        PetscFunctionReturn(0);
      }
      continue;
    }
    ++info.step;
    info.t = integrator.time();
    info.h = attempt;
    info.iterations = r.iterations;
    info.rejected = summary->rejected;
    summary->newtonIterations += r.iterations;
    if (tol > 0) {
      // Adaptive: the next step from the error estimate, at most the scene's
      // dt. An accepted step is never followed by a smaller one, and h grows
      // only by 1.5x or more, so that a reused Jacobian (keyed to h) stays
      // valid over runs of steps.
      const double f = factor(r.errorEstimate);
      if (f >= 1.5) h = std::min(spec.dt, attempt * std::min(f, 2.0));
    } else if (h < spec.dt && ++successesSinceCut >= 4) {
      // Grow back towards the scene's dt after a few successes at a cut step.
      h = std::min(spec.dt, 2.0 * h);
      successesSinceCut = 0;
    }
    st.steps = info.step, st.rejected = summary->rejected, st.newtonIterations = summary->newtonIterations;
    info.stepper = &st;
    if (onStep) PetscCall(onStep(info));
    if (!info.failure.empty()) {
      summary->failure = info.failure;
      summary->steps = info.step;
      PetscFunctionReturn(0);
    }
    if (stop && stop() && integrator.time() < spec.t_end - tolerance) {
      summary->interrupted = true;
      summary->steps = info.step;
      PetscFunctionReturn(0);
    }
  }
  summary->completed = true;
  summary->steps = info.step;
  PetscFunctionReturn(0);
}

PetscErrorCode saveStepper(CheckpointWriter &out, const StepperState &state)
{
  PetscFunctionBeginUser;
  out.addScalar("stepper.h", state.h);
  out.addScalar("stepper.successes", state.successesSinceCut);
  out.addScalar("stepper.steps", state.steps);
  out.addScalar("stepper.rejected", state.rejected);
  out.addScalar("stepper.newton", state.newtonIterations);
  PetscFunctionReturn(0);
}

PetscErrorCode restoreStepper(const CheckpointReader &in, StepperState *state)
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
