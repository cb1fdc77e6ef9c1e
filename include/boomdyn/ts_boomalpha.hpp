// The constrained generalized-alpha of GeneralizedAlpha as a PETSc TS type
// (-ts_type boomalpha) with its step-size controller as a TSAdapt type
// (-ts_adapt_type boomalpha).
//
// Why a TS type of our own: TSALPHA2 carries multipliers as second-order
// unknowns, enforces constraints at t_{n+alpha_f} and starts without
// consistent accelerations, which loses second order on index-3 systems
// (measured on a pendulum: first order with damping, oscillating
// multipliers without; docs/model.md has the scheme). The type drives
// GeneralizedAlpha::step(); the TS solution vector is the integrator's
// position vector (layout of x). Step-size control and final-time matching
// keep the numbers of the loop this replaced, bit for bit.
//
// The step (TSStep_BoomAlpha) retries a failed attempt inside one TSStep, as
// PETSc's own implicit types do:
//  - Newton failure: the step is scaled by -ts_adapt_scale_solve_failed
//    (default 0.5), counted against -ts_max_snes_failures (default
//    unlimited) and -ts_max_reject (per step, default unlimited);
//  - an error estimate above -boom_adaptive_tol: the TSAdapt rejects it and
//    chooses a smaller step;
//  - no step size below the adapt's minimum (-ts_adapt_dt_min, default the
//    scene's dt_min) is tried: the run fails with a message instead.
// With -ts_exact_final_time matchstep (default) a step that would leave less
// than a millionth of itself to go is stretched to end exactly on max_time.
#pragma once

#include "boomdyn/generalized_alpha.hpp"

#include <petscts.h>

#include <exception>
#include <functional>
#include <string>

namespace boomdyn {

inline constexpr const char *TSBOOMALPHA = "boomalpha";
inline constexpr const char *TSADAPTBOOMALPHA = "boomalpha";

// The step controller's state, carried across steps and through checkpoints.
struct StepperState {
  double h = 0;               // step to try next (0: the scene's dt)
  int successesSinceCut = 0;
  PetscInt steps = 0, rejected = 0, newtonIterations = 0;
};

// What the TS type works on; owned by the caller, attached with
// TSBoomAlphaSetRun() after TSSetType(ts, TSBOOMALPHA).
struct BoomAlphaRun {
  GeneralizedAlpha *integrator = nullptr;
  StepperState *state = nullptr;
  double dt = 0;          // nominal step: growth after cuts stops here (adapt's dt_max)
  double dtMin = 0;       // smallest step tried (adapt's dt_min)
  double endTolerance = 0; // a run within this of max_time has arrived
  // Results of the last TSStep.
  bool accepted = false;   // it took a step
  double attempt = 0;      // size of the last attempt
  StepResult last;         // result of the last attempt
  std::string failure;     // why the run cannot go on (ts->reason < 0)
  // Asked between the attempts of one step (a failing step may be cut many
  // times down to dt_min); true ends the step unaccepted, as interrupted.
  std::function<bool()> stop;
  bool interrupted = false;
  // An exception from the integrator or a callback, rethrown after TSSolve
  // (C++ exceptions must not unwind through PETSc's C frames).
  std::exception_ptr exception;
};

// Registers the TS and TSAdapt types (idempotent).
PetscErrorCode registerBoomAlpha();
PetscErrorCode TSBoomAlphaSetRun(TS ts, BoomAlphaRun *run);

} // namespace boomdyn
