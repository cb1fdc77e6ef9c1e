// The dynamic analysis of a Simulation: generalized-alpha from the initial
// state (or a checkpoint) to t_end through integrate() (time_stepper.hpp),
// with every monitor called at the start, after every accepted step and at
// the end.
#include "boomdyn/simulation.hpp"

#include "boomdyn/monitors.hpp"
#include "boomdyn/schema.hpp"
#include "boomdyn/slider_tracker.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace boomdyn {

PetscErrorCode Simulation::dynamicState(RunState *state)
{
  PetscReal violation;
  PetscFunctionBeginUser;
  state->dynamic = true;
  state->t = integrator_->time();
  state->q = integrator_->positions();
  state->v = integrator_->velocities();
  state->lambda = integrator_->multipliers();
  // The energy check's damping forces come from the same pass as the energy.
  const bool forces = energy_ && energy_->wantsDampingForces();
  PetscCall(integrator_->diagnostics(&state->energy, &violation, true, forces ? &dampingForces_ : nullptr));
  state->dampingForces = forces ? &dampingForces_ : nullptr;
  state->violation = violation;
  state->stepper = &stepper_;
  PetscFunctionReturn(0);
}

// Everything a checkpoint holds, in the order it was saved. Throws
// std::runtime_error naming the file when a value is missing.
PetscErrorCode Simulation::restore(RunState *state)
{
  PetscFunctionBeginUser;
  CheckpointReader in(comm_);
  PetscCall(in.read(options_.restartPath));
  PetscCheck(in.sceneText() == scene().text, comm_, PETSC_ERR_USER_INPUT,
             "restart file %s was written for another scene text than %s", options_.restartPath.c_str(),
             scene().file.c_str());
  // The options that change the equations or the sequence of steps must be
  // those of the run that wrote the checkpoint (docs/reliability.md lists
  // them; older checkpoints do not hold the later ones). Options that only
  // change how the same equations are solved (Newton's start, Jacobian
  // reuse, linear solvers, partition, ranks) may differ.
  const char *file = options_.restartPath.c_str();
  static const char *const axialNames[] = {"full", "reduced", "assumed"};
  struct Defining {
    std::string key, option;
    double value;
    const char *const *names; // the option's words by value, or null for a number
  };
  std::vector<Defining> defining = {
      {"option_dt", "-ts_dt (dynamic.dt)", scene().dynamic.dt, nullptr},
      {"option_rho_inf", "-boom_rho_inf (dynamic.rho_inf)", scene().dynamic.rho_inf, nullptr},
      {"option_adaptive_tol", "-boom_adaptive_tol", options_.adaptiveTolerance, nullptr},
      {"option_kink_restart", "-boom_kink_restart", options_.kinkRestart ? 1.0 : 0.0, nullptr},
      {"option_filtered_start", "-boom_filtered_start", options_.filteredStart ? 1.0 : 0.0, nullptr}};
  for (const BodySpec &b : scene().bodies)
    if (b.type == BodySpec::Type::AncfBeam) {
      defining.push_back({"option_elements_" + b.name, "-boom_elements (elements of beam '" + b.name + "')",
                          static_cast<double>(b.elements), nullptr});
      defining.push_back({"option_axial_integration_" + b.name, "-boom_axial_integration (beam '" + b.name + "')",
                          static_cast<double>(b.section.axialIntegration), axialNames});
    }
  for (const auto &d : defining) {
    if (!in.hasScalar(d.key) || in.scalar(d.key) == d.value) continue;
    const double saved = in.scalar(d.key);
    const bool named = d.names && (saved == 0 || saved == 1 || saved == 2);
    const std::string was = named ? d.names[static_cast<int>(saved)] : numberText(saved);
    const std::string now = d.names ? d.names[static_cast<int>(d.value)] : numberText(d.value);
    SETERRQ(comm_, PETSC_ERR_USER_INPUT,
            "restart file %s was written with %s = %s, this run has %s: restart with the options of that run", file,
            d.option.c_str(), was.c_str(), now.c_str());
  }
  PetscCall(integrator_->restore(in));
  PetscCall(restoreStepper(in, &stepper_));
  PetscCall(dynamicState(state));
  PetscCheck(integrator_->time() < scene().dynamic.t_end, comm_, PETSC_ERR_USER_INPUT,
             "restart file %s is at t = %s s, not before the end time %s s (-ts_max_time, dynamic.t_end)", file,
             numberText(integrator_->time()).c_str(), numberText(scene().dynamic.t_end).c_str());
  // A state edited or damaged so that it violates the constraints would
  // run on from a wrong configuration.
  outcome_.maxViolation = in.scalar("max_violation");
  const double allowed = std::max(1e-6, 10 * outcome_.maxViolation);
  PetscCheck(state->violation <= allowed, comm_, PETSC_ERR_USER_INPUT,
             "restart file %s: the saved state violates the constraints by %s (the run that wrote it reached at "
             "most %s): the checkpoint is damaged",
             file, numberText(state->violation).c_str(), numberText(outcome_.maxViolation).c_str());
  for (auto &m : monitors_) PetscCall(m->restore(in));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::runDynamic(const std::function<bool()> &stop)
{
  RunState state;
  PetscFunctionBeginUser;
  const bool restarted = !options_.restartPath.empty();
  if (restarted) {
    // The checkpoint reader reports a missing or foreign file by exception.
    PetscErrorCode ierr = 0;
    PetscCallCXX(ierr = restore(&state));
    PetscCall(ierr);
    if (!options_.quiet)
      PetscCall(PetscPrintf(comm_, "restarted from %s at t = %g s (step %" PetscInt_FMT ")\n",
                            options_.restartPath.c_str(), integrator_->time(), stepper_.steps));
  } else {
    stepper_ = StepperState{};
    if (scene().dynamic.startStatic) PetscCall(staticInitialState());
    // A mechanism without consistent accelerations is reported by exception.
    PetscErrorCode ierr = 0;
    PetscCallCXX(ierr = integrator_->initialize(0.0, x_, scene().dynamic.startStatic ? zero_ : v0_));
    PetscCall(ierr);
    PetscCall(dynamicState(&state));
    outcome_.maxViolation = state.violation;
  }
  for (auto &m : monitors_) PetscCall(m->start(state, restarted));

  const double tEnd = scene().dynamic.t_end;
  auto onStep = [&](const StepInfo &s) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(dynamicState(&state));
    state.t = s.t;
    state.h = s.h;
    state.step = s.step;
    state.iterations = s.iterations;
    state.rejected = s.rejected;
    state.last = s.t >= tEnd * (1 - 1e-12);
    PetscCall(afterStep(state, &s.failure));
    PetscFunctionReturn(0);
  };
  // A step that cannot go on (a singular system, a projection at a kink that
  // does not converge, ...) is reported by exception, which must become a
  // PETSc error here and not unwind through main.
  {
    PetscErrorCode ierr = 0;
    PetscCallCXX(ierr = integrate(*integrator_, scene().dynamic, onStep, &summary_, &stepper_, stop));
    PetscCall(ierr);
  }

  outcome_.steps = summary_.steps;
  outcome_.rejected = summary_.rejected;
  outcome_.newtonIterations = summary_.newtonIterations;
  if (summary_.interrupted) outcome_.status = "interrupted";
  else if (!summary_.completed) {
    std::string details;
    PetscCall(failureDetails(summary_.failure, &details));
    outcome_.status = "failed: " + details;
  }
  else if (summary_.stepLimit) outcome_.status = RunOutcome::kStepLimit; // what the user asked for: exit 0
  // The final state for the monitors' finish(); its diagnostics are those
  // of the last accepted step, already seen.
  state.t = integrator_->time();
  state.h = 0;
  state.q = integrator_->positions();
  state.v = integrator_->velocities();
  state.lambda = integrator_->multipliers();
  outcome_.endTime = integrator_->time();
  if (!options_.quiet)
    PetscCall(PetscPrintf(comm_,
                          "%s: %" PetscInt_FMT " steps, %" PetscInt_FMT " rejected, %.2f Newton iterations/step, max "
                          "constraint violation %.2e, %.2f s\n",
                          outcome_.status.c_str(), outcome_.steps, outcome_.rejected,
                          outcome_.steps ? (double)summary_.newtonIterations / outcome_.steps : 0.0,
                          outcome_.maxViolation, [&] {
                            PetscLogDouble now;
                            (void)PetscTime(&now);
                            return now - started_;
                          }()));
  if (summary_.completed && options_.modal && scene().modal.count > 0) {
    const bool atStart = scene().modal.at == "start";
    bool stopped = false;
    PetscCall(modalAnalysis(atStart ? 0.0 : integrator_->time(), atStart ? x_.get() : integrator_->positions(),
                            integrator_->multipliers(), stop, &stopped));
    if (stopped) outcome_.status = "interrupted";
  }
  PetscCall(finish(state));
  PetscFunctionReturn(0);
}

// initial: static. The equilibrium under the loads and drives at t = 0
// replaces the undeformed state in x_; the run starts from it at rest, and
// integrator_->initialize() adds the consistent accelerations (zero up to
// the static solver's residual) and multipliers.
PetscErrorCode Simulation::staticInitialState()
{
  PetscBool converged = PETSC_TRUE;
  PetscInt lo, hi;
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(statics_->solve(0.0, 1, x_, nullptr, &converged));
  PetscCheck(converged, comm_, PETSC_ERR_NOT_CONVERGED,
             "%s: 'dynamic.initial: static': no static equilibrium found at t = 0 (%s); start from the undeformed state "
             "(leave 'initial' out) or make the loads at t = 0 smaller",
             scene().file.c_str(), statics_->failure().c_str());
  // The solver leaves scaled multipliers after the coordinates: the state is q only.
  PetscCall(VecGetOwnershipRange(x_, &lo, &hi));
  PetscCall(VecGetArray(x_, &a));
  for (PetscInt i = std::max<PetscInt>(lo, model_.numCoordinates()); i < hi; ++i) a[i - lo] = 0.0;
  PetscCall(VecRestoreArray(x_, &a));
  if (!options_.quiet) PetscCall(PetscPrintf(comm_, "initial state: static equilibrium at t = 0\n"));
  PetscFunctionReturn(0);
}

namespace {

// The lines of every rank's text, in rank order, each once (collective).
PetscErrorCode gatherLines(MPI_Comm comm, const std::string &mine, std::vector<std::string> *lines)
{
  PetscMPIInt size, count = static_cast<PetscMPIInt>(mine.size());
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<PetscMPIInt> counts(size), offsets(size, 0);
  PetscCallMPI(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm));
  for (PetscMPIInt r = 1; r < size; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::string all(static_cast<size_t>(offsets[size - 1] + counts[size - 1]), '\0');
  PetscCallMPI(MPI_Allgatherv(mine.data(), count, MPI_CHAR, all.data(), counts.data(), offsets.data(), MPI_CHAR, comm));
  lines->clear();
  for (size_t begin = 0; begin < all.size();) {
    const size_t end = std::min(all.find('\n', begin), all.size());
    const std::string line = all.substr(begin, end - begin);
    if (!line.empty() && std::find(lines->begin(), lines->end(), line) == lines->end()) lines->push_back(line);
    begin = end + 1;
  }
  PetscFunctionReturn(0);
}

} // namespace

// Newton failing with a contact point at a track end: the booms barely
// overlap (two pads nearly at one point) or a slider is leaving its track.
// Collective: the status is the same on every rank.
PetscErrorCode Simulation::failureDetails(const std::string &failure, std::string *status)
{
  PetscFunctionBeginUser;
  *status = failure;
  std::vector<double> slacks, multipliers;
  if (sensors_.readJoints(integrator_->positions(), integrator_->multipliers(), slacks, multipliers) == 0) {
    const std::string ends = contactsNearTrackEnds(model_, slacks);
    if (failure.rfind("Newton failed", 0) == 0 && !ends.empty())
      *status += "; contact points at their track ends (booms without overlap, or a slider leaving its track): " + ends;
  }
  // Items that met a force that is not finite (a rope segment of zero
  // length). Only the rank that evaluates an item sees its fault: gathered
  // from every rank, so that rank 0, which prints the status and writes it
  // to the results file, names it.
  std::string mine;
  for (const auto &item : model_.items())
    if (const std::string fault = item->fault(); !fault.empty()) mine += fault + "\n";
  std::vector<std::string> faults;
  PetscCall(gatherLines(comm_, mine, &faults));
  for (const std::string &fault : faults) *status += "; " + fault;
  if (!conditioning_.empty()) *status += "; likely cause: " + conditioning_.front();
  PetscFunctionReturn(0);
}

} // namespace boomdyn
