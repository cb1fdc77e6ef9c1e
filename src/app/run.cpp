#include "run.hpp"

#include "progress.hpp"
#include "signals.hpp"

#include "boomdyn/energy_balance.hpp"
#include "boomdyn/partition.hpp"
#include "boomdyn/assembler.hpp"
#include "boomdyn/checkpoint.hpp"
#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/frequency_tracker.hpp"
#include "boomdyn/generalized_alpha.hpp"
#include "boomdyn/model.hpp"
#include "boomdyn/results_writer.hpp"
#include "boomdyn/sensors.hpp"
#include "boomdyn/slider_tracker.hpp"
#include "boomdyn/static_solver.hpp"
#include "boomdyn/stick_slip.hpp"
#include "boomdyn/time_stepper.hpp"
#include "boomdyn/version.hpp"

#include <slepcsys.h>

#include <algorithm>
#include <memory>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace boomdyn {

namespace {

std::string commandLine(int argc, char **argv)
{
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

PetscErrorCode allOptions(std::string *out)
{
  char *text;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(nullptr, &text));
  *out = text;
  PetscCall(PetscFree(text));
  PetscFunctionReturn(0);
}

// SLEPc is initialized only by runs that ask for modes.
PetscErrorCode modalAnalysis(Assembler &assembler, ResultsWriter &out, double t, Vec q, Vec lambda, int count, bool quiet)
{
  PetscFunctionBeginUser;
  PetscCall(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  ModalResult modes;
  PetscCall(solveModes(assembler, t, q, lambda, count, &modes));
  PetscCall(out.writeModes(t, modes));
  if (!quiet) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "modes at t = %g s:\n", t));
    for (std::size_t k = 0; k < modes.frequencyHz.size(); ++k)
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  mode %2zu  f = %12.6f Hz  (relative residual %.1e)\n", k + 1,
                            modes.frequencyHz[k], modes.residuals[k]));
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode reportPartitions(const Scene &scene, PetscInt parts)
{
  PetscFunctionBeginUser;
  PetscCheck(parts >= 1 && parts <= 4096, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
             "-boom_partition_report: the number of parts must be between 1 and 4096, got %" PetscInt_FMT, parts);
  Model model(scene);
  const int p = static_cast<int>(parts);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "scene '%s': %zu work items, %" PetscInt_FMT " unknowns, %d parts\n",
                        scene.name.c_str(), model.items().size(), model.size(), p));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-12s %10s %10s %10s  items per part\n", "partition", "interface", "cut edges",
                        "imbalance"));
  for (const PartitionQuality &q : {evaluatePartition(model, contiguousPartition(model, p), p, "contiguous"),
                                    evaluatePartition(model, metisPartition(model, p), p, "METIS k-way")}) {
    std::string counts;
    for (int n : q.itemsPerPart) counts += " " + std::to_string(n);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-12s %10d %10d %10.3f %s\n", q.method.c_str(), q.interfaceUnknowns,
                          q.cutEdges, q.imbalance, counts.c_str()));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode runScene(const Scene &scene, const AppOptions &opts, int argc, char **argv)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  Model model(scene);
  Assembler assembler(model);
  PetscCall(assembler.setUp(PETSC_COMM_WORLD));
  Vec x, zero;
  PetscCall(assembler.createVector(&x));
  PetscCall(assembler.createVector(&zero));
  PetscCall(assembler.initialState(x));

  RunInfo info;
  info.commandLine = commandLine(argc, argv);
  PetscCall(allOptions(&info.petscOptions));
  info.version = BOOMDYN_VERSION;
  info.ranks = size;
  ResultsWriter out(model, PETSC_COMM_WORLD);
  PetscCall(out.open(opts.outputPath, opts.overwrite, info, x));
  SensorProbe sensors(model);
  PetscCall(sensors.setUp(x));
  std::vector<SensorReading> readings;
  std::vector<double> slacks, multipliers, tensions, deflections;
  // Rope tensions: the output channels of group "rope" (factor * multiplier, rope_type.cpp).
  std::vector<OutputChannel> ropeRows;
  for (const OutputChannel &ch : model.outputChannels())
    if (ch.group == "rope") ropeRows.push_back(ch);
  PetscInt slackRopeSteps = 0;
  auto recordJoints = [&](double t) -> PetscErrorCode {
    PetscFunctionBeginUser;
    tensions.clear();
    bool slack = false;
    std::string which;
    for (const OutputChannel &rope : ropeRows)
      if (!multipliers.empty()) {
        tensions.push_back(rope.factor * multipliers[rope.index]);
        if (tensions.back() < 0 && !slack) slack = true, which = rope.name;
      }
    PetscCall(out.appendJoints(slacks, multipliers, tensions, deflections));
    int flag = slack;
    PetscCallMPI(MPI_Bcast(&flag, 1, MPI_INT, 0, PETSC_COMM_WORLD));
    if (flag && slackRopeSteps++ == 0)
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "warning: rope '%s' would have to push at t = %g s (tension %g N): the rope "
                            "is slack there; counted in /summary/slack_rope_steps\n", which.c_str(), t,
                            tensions.empty() ? 0.0 : *std::min_element(tensions.begin(), tensions.end())));
    PetscFunctionReturn(0);
  };

  if (!opts.quiet)
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "boomdyn %s: scene '%s' (%s), %" PetscInt_FMT " coordinates, %" PetscInt_FMT
                          " multipliers, %d rank(s) -> %s\n",
                          BOOMDYN_VERSION, scene.name.c_str(), scene.file.c_str(), model.numCoordinates(),
                          model.numMultipliers(), size, opts.outputPath.c_str()));
  // Meshes too fine for the step in double precision (reported even in quiet runs).
  const std::vector<std::string> conditioning = model.conditioningWarnings();
  for (const std::string &w : conditioning) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "warning: %s\n", w.c_str()));
  Progress progress(scene.dynamic.t_end, opts.progressInterval, opts.quiet);
  PetscCall(progress.start());
  std::string status = "completed";
  double interruptedAt = 0;
  PetscInt steps = 0, rejected = 0;
  double maxViolation = 0;

  if (scene.analysis == Scene::Analysis::Dynamic) {
    // Test aid (tests/mpi_tests.cmake): an error on one rank only, as a
    // rank-local solver or I/O failure would give; the run must not hang.
    if (const char *failRank = std::getenv("BOOMDYN_TEST_FAIL_RANK"); failRank && std::atoi(failRank) == rank)
      throw std::runtime_error("failure injected on rank " + std::to_string(rank) + " (BOOMDYN_TEST_FAIL_RANK)");
    GeneralizedAlpha integrator(assembler, scene.dynamic.rho_inf);
    PetscCall(integrator.setUp(scene.dynamic.max_newton));
    integrator.setErrorTolerance(opts.adaptiveTolerance);
    const bool restart = !opts.restartPath.empty();
    CheckpointReader restartFile(PETSC_COMM_WORLD);
    if (restart) {
      PetscCall(restartFile.read(opts.restartPath));
      if (restartFile.sceneText() != scene.text)
        throw std::runtime_error("restart file " + opts.restartPath + " was written for another scene text than " +
                                 scene.file);
      PetscCall(integrator.restore(restartFile));
    } else {
      PetscCall(integrator.initialize(0.0, x, zero));
    }
    EnergyParts energy;
    PetscReal violation;
    PetscCall(integrator.diagnostics(&energy, &violation));
    // Restarted runs check the balance from the restart on.
    EnergyBalance balance(opts.energyTolerance);
    (void)balance.update(integrator.time(), 0.0, energy);
    if (!restart) { // a restarted file starts with the restored state snapshot only
      PetscCall(sensors.read(integrator.positions(), integrator.velocities(), readings));
      PetscCall(out.appendStep(0.0, 0.0, 0, violation, energy, readings));
      PetscCall(sensors.readJoints(integrator.positions(), integrator.multipliers(), slacks, multipliers));
      PetscCall(sensors.readFrames(integrator.positions(), deflections));
      PetscCall(recordJoints(0.0));
    }
    PetscCall(out.appendState(integrator.time(), integrator.positions(), integrator.velocities(), integrator.multipliers()));
    maxViolation = violation;
    double nextState = scene.output.state_interval;
    double nextCheckpoint = opts.checkpointInterval;
    StepperState stepper;
    // Stick/slip of frictional joints: readings every step, transitions as events.
    StickSlipMonitor stickSlip(model);
    std::vector<double> frictionValues;
    std::vector<FrictionReading> frictionReadings;
    auto recordFriction = [&](double t) -> PetscErrorCode {
      PetscFunctionBeginUser;
      if (model.frictions().empty()) PetscFunctionReturn(0);
      PetscCall(sensors.readFriction(integrator.positions(), integrator.velocities(), integrator.multipliers(), frictionValues));
      const std::vector<StickSlipEvent> events = stickSlip.update(t, frictionValues, frictionReadings);
      PetscCall(out.appendFriction(frictionReadings));
      PetscCall(out.appendEvents(events));
      for (const StickSlipEvent &e : events)
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "event: t = %.4f s, joint '%s': %s (%s)\n", e.t, e.joint.c_str(),
                              e.toSlip ? "stick -> slip" : "slip -> stick", e.direction > 0 ? "s decreasing" : "s increasing"));
      PetscFunctionReturn(0);
    };
    if (!restart) PetscCall(recordFriction(0.0));
    // Frequency tracking: SLEPc only for scenes that ask for it.
    std::unique_ptr<FrequencyTracker> tracker;
    double nextTrack = 0.0;
    std::vector<double> shapeTimes = scene.tracking.shapesAt;
    auto track = [&](double t, double h) -> PetscErrorCode {
      PetscFunctionBeginUser;
      if (!tracker || t < nextTrack - 1e-9 * h) PetscFunctionReturn(0);
      TrackedModes modes;
      PetscCall(tracker->analyze(t, integrator.positions(), integrator.multipliers(), &modes));
      // A shape is written at the first analysis at or after each requested time.
      bool shape = false;
      while (!shapeTimes.empty() && *std::min_element(shapeTimes.begin(), shapeTimes.end()) <= t + 1e-9 * h) {
        shapeTimes.erase(std::min_element(shapeTimes.begin(), shapeTimes.end()));
        shape = true;
      }
      PetscCall(out.appendTracking(modes, shape));
      while (nextTrack <= t + 1e-9 * h) nextTrack += scene.tracking.interval;
      PetscFunctionReturn(0);
    };
    if (scene.tracking.interval > 0) {
      PetscCall(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
      tracker = std::make_unique<FrequencyTracker>(assembler, scene.tracking.count);
      if (!restart) PetscCall(track(0.0, scene.dynamic.dt));
    }
    // Checkpoints: everything needed to continue this run bitwise (one rank).
    auto writeCheckpoint = [&](const StepperState &st) -> PetscErrorCode {
      PetscFunctionBeginUser;
      CheckpointWriter w(PETSC_COMM_WORLD);
      PetscCall(integrator.save(w));
      w.addScalar("stepper.h", st.h);
      w.addScalar("stepper.successes", st.successesSinceCut);
      w.addScalar("stepper.steps", st.steps);
      w.addScalar("stepper.rejected", st.rejected);
      w.addScalar("stepper.newton", st.newtonIterations);
      w.addScalar("next_state", nextState);
      w.addScalar("next_track", nextTrack);
      w.addScalar("next_checkpoint", nextCheckpoint);
      w.addScalar("slack_rope_steps", slackRopeSteps);
      w.addScalar("max_violation", maxViolation);
      w.addArray("shape_times", shapeTimes);
      w.addArray("stick_slip", stickSlip.state());
      if (tracker) PetscCall(tracker->save(w));
      PetscCall(w.write(opts.checkpointPath, scene.text));
      if (!opts.quiet)
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "checkpoint at t = %g s -> %s\n", integrator.time(), opts.checkpointPath.c_str()));
      PetscFunctionReturn(0);
    };
    if (restart) {
      stepper.h = restartFile.scalar("stepper.h");
      stepper.successesSinceCut = static_cast<int>(restartFile.scalar("stepper.successes"));
      stepper.steps = static_cast<PetscInt>(restartFile.scalar("stepper.steps"));
      stepper.rejected = static_cast<PetscInt>(restartFile.scalar("stepper.rejected"));
      stepper.newtonIterations = static_cast<PetscInt>(restartFile.scalar("stepper.newton"));
      nextState = restartFile.scalar("next_state");
      nextTrack = restartFile.scalar("next_track");
      nextCheckpoint = restartFile.scalar("next_checkpoint");
      slackRopeSteps = static_cast<PetscInt>(restartFile.scalar("slack_rope_steps"));
      maxViolation = restartFile.scalar("max_violation");
      shapeTimes = restartFile.array("shape_times");
      stickSlip.setState(restartFile.array("stick_slip"));
      if (tracker) PetscCall(tracker->restore(restartFile));
      if (!opts.quiet)
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "restarted from %s at t = %g s (step %" PetscInt_FMT ")\n",
                              opts.restartPath.c_str(), integrator.time(), stepper.steps));
    }
    auto onStep = [&](const StepInfo &s) -> PetscErrorCode {
      PetscFunctionBeginUser;
      PetscCall(integrator.diagnostics(&energy, &violation));
      maxViolation = std::max(maxViolation, (double)violation);
      s.failure = balance.update(s.t, s.h, energy);
      PetscCall(sensors.read(integrator.positions(), integrator.velocities(), readings));
      PetscCall(out.appendStep(s.t, s.h, s.iterations, violation, energy, readings));
      PetscCall(sensors.readJoints(integrator.positions(), integrator.multipliers(), slacks, multipliers));
      PetscCall(sensors.readFrames(integrator.positions(), deflections));
      PetscCall(recordJoints(s.t));
      const bool last = s.t >= scene.dynamic.t_end * (1 - 1e-12);
      if ((scene.output.state_interval > 0 && s.t >= nextState - 1e-9 * s.h) || last) {
        PetscCall(out.appendState(s.t, integrator.positions(), integrator.velocities(), integrator.multipliers()));
        while (scene.output.state_interval > 0 && nextState <= s.t + 1e-9 * s.h) nextState += scene.output.state_interval;
      }
      PetscCall(recordFriction(s.t));
      PetscCall(track(s.t, s.h));
      if (opts.checkpointInterval > 0 && s.t >= nextCheckpoint - 1e-9 * s.h && !last) {
        while (nextCheckpoint <= s.t + 1e-9 * s.h) nextCheckpoint += opts.checkpointInterval;
        PetscCall(writeCheckpoint(*s.stepper));
      }
      PetscCall(progress.update(s.step, s.t, s.h, s.iterations, s.rejected));
      PetscFunctionReturn(0);
    };
    RunSummary summary;
    PetscCall(integrate(integrator, scene.dynamic, onStep, &summary, &stepper,
                        [] { return interruptRequested(PETSC_COMM_WORLD); }));
    steps = summary.steps;
    rejected = summary.rejected;
    out.setEnergyBalance(balance.inputWork(), balance.excess(), balance.involved());
    if (summary.interrupted) {
      status = "interrupted";
      interruptedAt = integrator.time();
      PetscCall(out.appendState(integrator.time(), integrator.positions(), integrator.velocities(), integrator.multipliers()));
      PetscCall(writeCheckpoint(stepper));
    } else if (!summary.completed) {
      status = "failed: " + summary.failure;
      // Newton failing with a contact point at a track end: the booms barely
      // overlap (two pads nearly at one point) or a slider is leaving its track.
      const std::string ends = contactsNearTrackEnds(model, slacks);
      if (summary.failure.rfind("Newton failed", 0) == 0 && !ends.empty())
        status += "; contact points at their track ends (booms without overlap, or a slider leaving its track): " + ends;
      if (!conditioning.empty()) status += "; likely cause: " + conditioning.front();
      PetscCall(out.appendState(integrator.time(), integrator.positions(), integrator.velocities(), integrator.multipliers()));
    }
    if (!opts.quiet)
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "%s: %" PetscInt_FMT " steps, %" PetscInt_FMT " rejected, %.2f Newton iterations/step, max "
                            "constraint violation %.2e, %.2f s\n",
                            status.c_str(), steps, rejected, steps ? (double)summary.newtonIterations / steps : 0.0,
                            maxViolation, progress.elapsed()));
    if (!model.frictions().empty() && !opts.quiet) {
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "stick/slip events: %zu\n", stickSlip.events().size()));
      for (const StickSlipEvent &e : stickSlip.events())
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "  t = %8.4f s  %-12s %s (%s)\n", e.t, e.joint.c_str(),
                              e.toSlip ? "stick -> slip" : "slip -> stick", e.direction > 0 ? "s decreasing" : "s increasing"));
    }
    if (summary.completed && scene.modal.count > 0) {
      Vec q = scene.modal.at == "start" ? x : integrator.positions();
      PetscCall(modalAnalysis(assembler, out, scene.modal.at == "start" ? 0.0 : integrator.time(), q,
                              integrator.multipliers(), scene.modal.count, opts.quiet));
    }
  } else {
    // Static and modal analyses: static equilibrium under the loads at statics.time.
    StaticSolver statics(assembler);
    PetscCall(statics.setUp());
    PetscBool converged = PETSC_TRUE;
    Vec lambda0;
    PetscCall(assembler.createVector(&lambda0));
    const bool modesAtStart = scene.modal.count > 0 && scene.modal.at == "start";
    if (modesAtStart) PetscCall(modalAnalysis(assembler, out, scene.statics.time, x, lambda0, scene.modal.count, opts.quiet));
    auto onLoadStep = [&](const LoadStepInfo &s) -> PetscErrorCode {
      EnergyParts energy;
      PetscReal violation;
      AssemblyContext ctx;
      PetscFunctionBeginUser;
      ctx.t = scene.statics.time;
      ctx.loadFactor = s.loadFactor;
      PetscCall(assembler.setOffsets(nullptr, nullptr, nullptr));
      PetscCall(assembler.diagnostics(ctx, x, &energy, &violation));
      maxViolation = std::max(maxViolation, (double)violation);
      PetscCall(sensors.read(x, zero, readings));
      PetscCall(out.appendStep(s.loadFactor, 0.0, s.iterations, violation, energy, readings));
      ++steps;
      if (!opts.quiet)
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "load factor %.4f: %" PetscInt_FMT " Newton iterations\n", s.loadFactor,
                              s.iterations));
      PetscFunctionReturn(0);
    };
    PetscCall(statics.solve(scene.statics.time, scene.statics.load_steps, x, onLoadStep, &converged));
    PetscCall(out.appendState(scene.statics.time, x, zero, statics.multipliers()));
    if (!converged) status = "failed: " + statics.failure();
    if (converged && scene.modal.count > 0 && !modesAtStart)
      PetscCall(modalAnalysis(assembler, out, scene.statics.time, x, statics.multipliers(), scene.modal.count, opts.quiet));
    PetscCall(VecDestroy(&lambda0));
  }
  out.setSlackRopeSteps(slackRopeSteps);
  PetscCall(out.finish(status, steps, rejected, progress.elapsed(), maxViolation));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&zero));
  // A failed or interrupted run exits non-zero; its results file is complete
  // up to that point and says so in /summary.
  if (status == "interrupted")
    throw Interrupted("run interrupted at t = " + std::to_string(interruptedAt) + " s by signal " +
                      std::to_string(interruptSignal()) + "; results so far in " + opts.outputPath +
                      ", continue with -boom_restart " + opts.checkpointPath);
  if (status != "completed")
    throw std::runtime_error(scene.file + ": run " + status + " (results so far in " + opts.outputPath + ")");
  PetscFunctionReturn(0);
}

} // namespace boomdyn
