#include "boomdyn/simulation.hpp"

#include "boomdyn/damped_eigen_solver.hpp"
#include "boomdyn/monitors.hpp"
#include "boomdyn/slider_tracker.hpp"

#include <slepcsys.h>

#include <algorithm>
#include <cmath>

namespace boomdyn {

Simulation::Simulation(const Scene &scene, MPI_Comm comm, const SimulationOptions &options)
  : comm_(comm), options_(options), model_(scene), assembler_(model_), sensors_(model_)
{
}

PetscErrorCode Simulation::setUp()
{
  PetscFunctionBeginUser;
  PetscCall(assembler_.setUp(comm_));
  PetscCall(assembler_.createVector(x_.address()));
  PetscCall(assembler_.createVector(zero_.address()));
  PetscCall(assembler_.initialState(x_));
  PetscCall(assembler_.createVector(v0_.address()));
  PetscCall(assembler_.initialVelocity(v0_));
  PetscCall(sensors_.setUp(x_));
  // Meshes too fine for the step in double precision (reported even in quiet runs).
  conditioning_ = model_.conditioningWarnings();
  if (options_.warnings)
    for (const std::string &w : conditioning_) PetscCall(PetscPrintf(comm_, "warning: %s\n", w.c_str()));
  if (scene().analysis == Scene::Analysis::Dynamic) {
    integrator_ = std::make_unique<GeneralizedAlpha>(assembler_, scene().dynamic.rho_inf);
    PetscCall(integrator_->setUp(scene().dynamic.max_newton));
    integrator_->setErrorTolerance(options_.adaptiveTolerance);
    integrator_->setKinkRestart(options_.kinkRestart);
    integrator_->setAccelerationPredictor(options_.accelerationPredictor);
    integrator_->setFilteredStart(options_.filteredStart);
    integrator_->setConsistentMultipliers(options_.consistentMultipliers);
    auto energy = std::make_unique<EnergyCheck>(options_.energyTolerance, assembler_);
    energy_ = energy.get();
    monitors_.push_back(std::move(energy));
    if (scene().dynamic.startStatic) { // initial: static
      statics_ = std::make_unique<StaticSolver>(assembler_);
      PetscCall(statics_->setUp());
    }
  } else {
    statics_ = std::make_unique<StaticSolver>(assembler_);
    PetscCall(statics_->setUp());
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::run(const std::function<bool()> &stop)
{
  PetscFunctionBeginUser;
  PetscCheck(integrator_ || statics_, comm_, PETSC_ERR_ORDER, "Simulation::run() needs setUp() first");
  PetscCall(PetscTime(&started_));
  outcome_ = RunOutcome{};
  outcome_.dynamic = integrator_ != nullptr;
  stop_ = stop;
  for (auto &m : monitors_) PetscCall(m->setUp());
  if (integrator_) PetscCall(runDynamic(stop));
  else PetscCall(runStatic(stop));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::afterStep(const RunState &state, std::string *failure)
{
  PetscFunctionBeginUser;
  outcome_.maxViolation = std::max(outcome_.maxViolation, state.violation);
  for (auto &m : monitors_) {
    std::string reason;
    PetscCall(m->afterStep(state, &reason));
    if (failure->empty()) *failure = reason;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::finish(const RunState &state)
{
  PetscLogDouble now;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&now));
  outcome_.wallTime = now - started_;
  if (energy_) {
    outcome_.hasEnergyBalance = true;
    outcome_.inputWork = energy_->balance().inputWork();
    outcome_.energyExcess = energy_->balance().excess();
    outcome_.energyInvolved = energy_->balance().involved();
    outcome_.dissipatedWork = energy_->balance().dissipatedWork();
  }
  for (auto &m : monitors_) PetscCall(m->finish(state, outcome_));
  PetscFunctionReturn(0);
}

// SLEPc is initialized only by runs that ask for modes.
PetscErrorCode Simulation::modalAnalysis(double t, Vec q, Vec lambda, const std::function<bool()> &stop,
                                         bool *interrupted)
{
  PetscFunctionBeginUser;
  PetscCall(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  ModalResult modes;
  const bool damped = model_.hasPhysicalDamping();
  ModalOptions options;
  options.stop = stop;
  options.keepVectors = damped; // the damped analysis tries them first (classical damping)
  options.energyShares = true;  // the mode labels (docs/model.md §5)
  PetscCall(solveModes(assembler_, t, q, lambda, scene().modal.count, &modes, options));
  *interrupted = modes.interrupted;
  if (*interrupted) PetscFunctionReturn(0);
  // A model with physical damping (Kelvin-Voigt sections, dampers; not
  // friction's velocity terms) also gets its damped modes (SLEPc PEP,
  // docs/model.md §5).
  if (damped) {
    DampedModalResult dm;
    DampedModalOptions dampedOptions;
    dampedOptions.stop = stop;
    dampedOptions.undamped = &modes;
    PetscCall(solveDampedModes(assembler_, t, q, lambda, scene().modal.count, &dm, dampedOptions));
    *interrupted = dm.interrupted;
    if (*interrupted) PetscFunctionReturn(0);
    for (std::size_t k = 0; k < dm.omega.size(); ++k) {
      modes.dampedFrequencyHz.push_back(dm.dampedOmega[k] / (2.0 * M_PI));
      modes.undampedEquivalentHz.push_back(dm.omega[k] / (2.0 * M_PI));
      modes.dampingRatio.push_back(dm.dampingRatio[k]);
      modes.decayRates.insert(modes.decayRates.end(), dm.decayRates[k].begin(), dm.decayRates[k].end());
    }
  }
  for (auto &m : monitors_) PetscCall(m->modes(t, modes));
  if (!options_.quiet) {
    PetscCall(PetscPrintf(comm_, "modes at t = %g s:\n", t));
    for (std::size_t k = 0; k < modes.frequencyHz.size(); ++k) {
      PetscCall(PetscPrintf(comm_, "  mode %2zu  f = %12.6f Hz  (relative residual %.1e)  %s", k + 1,
                            modes.frequencyHz[k], modes.residuals[k], modeLabel(modes.energyShares[k]).c_str()));
      if (damped && modes.dampedFrequencyHz[k] > 0)
        PetscCall(PetscPrintf(comm_, "  damped: f_d = %12.6f Hz, zeta = %.6f", modes.dampedFrequencyHz[k],
                              modes.dampingRatio[k]));
      else if (damped) // real eigenvalues: no oscillation, two decay rates
        PetscCall(PetscPrintf(comm_, "  damped: overdamped (f_d = 0), zeta = %.6g, decay rates %.6g, %.6g 1/s",
                              modes.dampingRatio[k], modes.decayRates[2 * k], modes.decayRates[2 * k + 1]));
      PetscCall(PetscPrintf(comm_, "\n"));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::writeCheckpoint(const std::string &path) const
{
  PetscFunctionBeginUser;
  PetscCheck(integrator_, comm_, PETSC_ERR_ORDER, "checkpoints are written by dynamic runs only");
  CheckpointWriter w(comm_);
  PetscCall(integrator_->save(w));
  PetscCall(saveStepper(w, stepper_));
  w.addScalar("max_violation", outcome_.maxViolation);
  // The options that define the run, checked by a restart (Simulation::restore).
  w.addScalar("option_dt", scene().dynamic.dt);
  w.addScalar("option_rho_inf", scene().dynamic.rho_inf);
  w.addScalar("option_adaptive_tol", options_.adaptiveTolerance);
  w.addScalar("option_kink_restart", options_.kinkRestart ? 1.0 : 0.0);
  w.addScalar("option_filtered_start", options_.filteredStart ? 1.0 : 0.0);
  for (const BodySpec &b : scene().bodies) // the mesh and the element formulation of every beam
    if (b.type == BodySpec::Type::AncfBeam) {
      w.addScalar("option_elements_" + b.name, b.elements);
      w.addScalar("option_axial_integration_" + b.name, static_cast<double>(b.section.axialIntegration));
    }
  for (const auto &m : monitors_) PetscCall(m->save(w));
  PetscCall(w.write(path, scene().text));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
