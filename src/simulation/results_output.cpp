// The results file of a run (docs/output.md) as a monitor: one /steps row
// (energies, violation, sensors) and one /joints row per step, state
// snapshots every state interval and at the end, the modes, the summary.
#include "boomdyn/monitors.hpp"
#include "boomdyn/schedule.hpp"
#include "boomdyn/simulation.hpp"

namespace boomdyn {

ResultsOutput::ResultsOutput(Simulation &sim, const std::string &path, bool overwrite, const RunInfo &info,
                             double stateInterval)
  : sim_(sim), writer_(sim.model(), sim.comm()), path_(path), overwrite_(overwrite), info_(info),
    stateInterval_(stateInterval), nextState_(stateInterval), ropes_(sim.model()),
    design_(sim.model())
{
}

PetscErrorCode ResultsOutput::setUp()
{
  PetscFunctionBeginUser;
  // An existing file or an unwritable folder is reported by exception.
  PetscErrorCode ierr = 0;
  PetscCallCXX(ierr = writer_.open(path_, overwrite_, info_, sim_.initialState()));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOutput::writeStepRow(const RunState &s)
{
  PetscFunctionBeginUser;
  PetscCall(sim_.sensors().read(s.q, s.v, readings_));
  PetscCall(writer_.appendStep(s.t, s.h, s.iterations, s.violation, s.energy, readings_));
  PetscCall(sim_.sensors().readSections(s.q, s.v, sections_));
  if (!sections_.empty()) PetscCall(writer_.appendSections(sections_));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOutput::writeJoints(const RunState &s)
{
  std::vector<double> &tensions = tensions_;
  PetscFunctionBeginUser;
  PetscCall(sim_.sensors().readJoints(s.q, s.lambda, slacks_, multipliers_));
  PetscCall(sim_.sensors().readFrames(s.q, deflections_));
  PetscCall(ropes_.update(sim_.comm(), s.t, multipliers_, tensions));
  PetscCall(sim_.sensors().readOutputs(s.t, s.q, s.v, multipliers_, outputs_));
  design_.update(s.t, outputs_, multipliers_);
  PetscCall(writer_.appendJoints(slacks_, multipliers_, tensions, deflections_, outputs_));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOutput::writeOutputs(const RunState &s)
{
  PetscFunctionBeginUser;
  if (sim_.model().outputChannels().empty()) PetscFunctionReturn(0);
  PetscCall(sim_.sensors().readJoints(s.q, s.lambda, slacks_, multipliers_));
  PetscCall(sim_.sensors().readOutputs(s.t, s.q, s.v, multipliers_, outputs_));
  PetscCall(writer_.appendJoints({}, {}, {}, {}, outputs_));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOutput::start(const RunState &s, bool restarted)
{
  PetscFunctionBeginUser;
  if (!s.dynamic) PetscFunctionReturn(0); // static runs: rows of converged load increments only
  if (!restarted) { // a restarted file starts with the restored state snapshot only
    PetscCall(writeStepRow(s));
    PetscCall(writeJoints(s));
  }
  PetscCall(writer_.appendState(s.t, s.q, s.v, s.lambda));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOutput::afterStep(const RunState &s, std::string *)
{
  PetscFunctionBeginUser;
  PetscCall(writeStepRow(s));
  if (!s.dynamic) { // converged load increments: the output channels, and state snapshots at the first and
                     // last increment and every state interval of the load factor (docs/output.md)
    PetscCall(writeOutputs(s));
    const double slack = 1e-9 * std::max(stateInterval_, 1e-3);
    if (s.step == 1 || (stateInterval_ > 0 && s.t >= nextState_ - slack) || s.last) {
      PetscCall(writer_.appendState(s.t, s.q, s.v, s.lambda));
      stateWrittenAt_ = s.t;
    }
    if (stateInterval_ > 0 && s.t >= nextState_ - slack)
      nextState_ = nextScheduledTime(nextState_, stateInterval_, s.t, slack);
    loadFactor_ = s.t;
    PetscFunctionReturn(0);
  }
  PetscCall(writeJoints(s));
  if ((stateInterval_ > 0 && s.t >= nextState_ - 1e-9 * s.h) || s.last) {
    PetscCall(writer_.appendState(s.t, s.q, s.v, s.lambda));
    if (stateInterval_ > 0) nextState_ = nextScheduledTime(nextState_, stateInterval_, s.t, 1e-9 * s.h);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOutput::modes(double t, const ModalResult &modes)
{
  PetscFunctionBeginUser;
  PetscCall(writer_.writeModes(t, modes));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOutput::finish(const RunState &s, const RunOutcome &outcome)
{
  PetscFunctionBeginUser;
  // A completed dynamic run wrote its last state with its last step; a
  // failed or interrupted one ends with the last accepted state. A static
  // run ends with its last converged increment (which the solver leaves in
  // x after a failure), at its load factor (0 before the first), unless
  // that increment's snapshot is written already.
  if (outcome.dynamic && !outcome.completed()) PetscCall(writer_.appendState(outcome.endTime, s.q, s.v, s.lambda));
  if (!outcome.dynamic && stateWrittenAt_ != loadFactor_)
    PetscCall(writer_.appendState(loadFactor_, s.q, s.v, s.lambda));
  if (outcome.hasEnergyBalance)
    writer_.setEnergyBalance(outcome.inputWork, outcome.energyExcess, outcome.energyInvolved);
  writer_.setSlackRopeSteps(ropes_.slackSteps());
  if (outcome.dynamic) {
    writer_.setSummaryNumbers(design_.attributes());
    if (!sim_.options().quiet) PetscCall(PetscPrintf(sim_.comm(), "%s", design_.report().c_str()));
  }
  PetscCall(writer_.finish(outcome.status, outcome.steps, outcome.rejected, outcome.wallTime, outcome.maxViolation));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOutput::save(CheckpointWriter &out) const
{
  PetscFunctionBeginUser;
  out.addScalar("next_state", nextState_);
  out.addScalar("slack_rope_steps", ropes_.slackSteps());
  const std::vector<double> design = design_.state();
  out.addScalar("design_numbers_size", (double)design.size());
  out.addArray("design_numbers", design);
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOutput::restore(const CheckpointReader &in)
{
  PetscFunctionBeginUser;
  nextState_ = in.scalar("next_state");
  ropes_.setSlackSteps(static_cast<PetscInt>(in.scalar("slack_rope_steps")));
  // Checkpoints from before the design numbers start them afresh at the restart.
  if (in.hasScalar("design_numbers_size")) design_.restore(in.array("design_numbers"));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
