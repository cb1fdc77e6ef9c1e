// The monitors of a boomdyn run (monitor.hpp). The program attaches all that
// apply; tests attach their own (tests/support.hpp).
//   EnergyCheck        energy balance of a dynamic run; fails a run that creates energy
//   ResultsOutput      the results file: /steps (with sensors), /joints, /state, /modes, /summary
//   FrictionOutput     stick/slip of frictional joints: /friction and /events
//   TypeEventsOutput   events of the registered types (rope slack/taut): /type_events
//   FrequencyTracking  modes along the trajectory: /tracking
//   Checkpointer       checkpoints every interval of simulated time and on interruption
//   ProgressLine       progress lines on the console
#pragma once

#include "boomdyn/assembler.hpp"
#include "boomdyn/design_numbers.hpp"
#include "boomdyn/energy_balance.hpp"
#include "boomdyn/frequency_tracker.hpp"
#include "boomdyn/monitor.hpp"
#include "boomdyn/results_writer.hpp"
#include "boomdyn/rope_tensions.hpp"
#include "boomdyn/stick_slip.hpp"

#include <memory>
#include <string>
#include <vector>

namespace boomdyn {

class Simulation;

class EnergyCheck : public Monitor {
public:
  // assembler: for the work of the damping forces over each step (models
  // with physical damping only; Assembler::dampingForces).
  // The absolute floor of the balance: 1e-12 of the model's energy scale (Model::energyScale).
  EnergyCheck(double tolerance, Assembler &assembler);
  PetscErrorCode start(const RunState &s, bool) override;
  PetscErrorCode afterStep(const RunState &s, std::string *failure) override;
  const EnergyBalance &balance() const { return balance_; }
  // True when the check uses damping forces (RunState::dampingForces).
  bool wantsDampingForces() const { return damped_; }

private:
  PetscErrorCode remember(const RunState &s);

  EnergyBalance balance_; // restarted runs check the balance from the restart on: not checkpointed
  Assembler &assembler_;
  bool damped_;
  // Damped models: q before the step (for the increment dq_) and the damping
  // forces there, evaluated once per state and used by the two steps it ends
  // and begins.
  PetscHandle<Vec> qPrevious_, dq_;
  Assembler::DampingForces forcesPrevious_, forces_;
};

class ResultsOutput : public Monitor {
public:
  // stateInterval: simulated time between state snapshots (static runs: of
  // the load factor; 0: the first and the last step only).
  ResultsOutput(Simulation &sim, const std::string &path, bool overwrite, const RunInfo &info, double stateInterval);
  PetscErrorCode setUp() override;
  PetscErrorCode start(const RunState &s, bool restarted) override;
  PetscErrorCode afterStep(const RunState &s, std::string *failure) override;
  PetscErrorCode modes(double t, const ModalResult &modes) override;
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override;
  PetscErrorCode save(CheckpointWriter &out) const override;
  PetscErrorCode restore(const CheckpointReader &in) override;
  // For the monitors that write groups of their own into the same file.
  ResultsWriter &writer() { return writer_; }

private:
  PetscErrorCode writeStepRow(const RunState &s);
  PetscErrorCode writeJoints(const RunState &s);
  PetscErrorCode writeOutputs(const RunState &s); // static runs: output channels only

  Simulation &sim_;
  ResultsWriter writer_;
  std::string path_;
  bool overwrite_;
  RunInfo info_;
  double stateInterval_, nextState_;
  // Static runs: the load factor of the last converged increment and of the last state snapshot (-1: none).
  double loadFactor_ = 0, stateWrittenAt_ = -1;
  RopeTensions ropes_;
  DesignNumbers design_; // peak rope tensions, root moments, contact forces (dynamic runs)
  std::vector<SensorReading> readings_;
  std::vector<SectionReading> sections_;
  std::vector<double> slacks_, multipliers_, deflections_, outputs_; // rank 0 data of the current step
  std::vector<double> tensions_;                                       // kept between steps (no allocation per step)
};

class FrictionOutput : public Monitor {
public:
  FrictionOutput(Simulation &sim, ResultsWriter &writer, bool quiet);
  PetscErrorCode start(const RunState &s, bool restarted) override;
  PetscErrorCode afterStep(const RunState &s, std::string *failure) override;
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override;
  PetscErrorCode save(CheckpointWriter &out) const override;
  PetscErrorCode restore(const CheckpointReader &in) override;

private:
  PetscErrorCode record(const RunState &s);

  Simulation &sim_;
  ResultsWriter &writer_;
  bool quiet_;
  StickSlipMonitor stickSlip_;
  std::vector<double> values_;
  std::vector<FrictionReading> readings_;
};

// The registered types' event sources (Model::eventSources()): after every
// converged dynamic step each source reports its changes; they go to
// /type_events (when writer is not null), to the console (unless quiet) and
// to events(). Sources take their state from the first state of a run (a
// restarted run: the restored state), so nothing is checkpointed.
class TypeEventsOutput : public Monitor {
public:
  TypeEventsOutput(Simulation &sim, ResultsWriter *writer, bool quiet) : sim_(sim), writer_(writer), quiet_(quiet) {}
  PetscErrorCode start(const RunState &s, bool restarted) override;
  PetscErrorCode afterStep(const RunState &s, std::string *failure) override;
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override;
  // Every event so far (rank 0).
  const std::vector<TypeEvent> &events() const { return events_; }

private:
  PetscErrorCode detect(const RunState &s, bool first);

  Simulation &sim_;
  ResultsWriter *writer_;
  bool quiet_;
  std::vector<TypeEvent> events_;
  std::vector<double> qs_, vs_;
};

class FrequencyTracking : public Monitor {
public:
  FrequencyTracking(Simulation &sim, ResultsWriter &writer);
  PetscErrorCode setUp() override; // SLEPc is initialized only by runs that track
  PetscErrorCode start(const RunState &s, bool restarted) override;
  PetscErrorCode afterStep(const RunState &s, std::string *failure) override;
  PetscErrorCode save(CheckpointWriter &out) const override;
  PetscErrorCode restore(const CheckpointReader &in) override;

private:
  PetscErrorCode track(const RunState &s, double h);
  PetscErrorCode trackDamped(const RunState &s, TrackedModes *modes);

  Simulation &sim_;
  ResultsWriter &writer_;
  std::unique_ptr<FrequencyTracker> tracker_;
  int damped_ = -1; // the model has physical damping (Model::hasPhysicalDamping): 1, 0, -1 not yet known
  double interval_, next_ = 0;
  std::vector<double> shapeTimes_;
};

class Checkpointer : public Monitor {
public:
  // interval: simulated time between checkpoints (0: only when interrupted).
  Checkpointer(const Simulation &sim, const std::string &path, double interval, bool quiet)
    : sim_(sim), path_(path), interval_(interval), next_(interval), quiet_(quiet)
  {
  }
  PetscErrorCode afterStep(const RunState &s, std::string *failure) override;
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override;
  PetscErrorCode save(CheckpointWriter &out) const override;
  PetscErrorCode restore(const CheckpointReader &in) override;

private:
  PetscErrorCode write(double t);

  const Simulation &sim_;
  std::string path_;
  double interval_, next_;
  bool quiet_;
};

// A progress line for long runs: step, simulated time, rate and ETA, at most
// every `interval` seconds of wall time, on rank 0; static runs: one line per
// load increment.
class ProgressLine : public Monitor {
public:
  ProgressLine(double tEnd, double interval) : tEnd_(tEnd), interval_(interval) {}
  PetscErrorCode start(const RunState &s, bool restarted) override;
  PetscErrorCode afterStep(const RunState &s, std::string *failure) override;

private:
  double tEnd_, interval_;
  PetscLogDouble start_ = 0, last_ = 0;
};

} // namespace boomdyn
