#include "run.hpp"

#include "signals.hpp"

#include "boomdyn/monitors.hpp"
#include "boomdyn/partition.hpp"
#include "boomdyn/simulation.hpp"
#include "boomdyn/version.hpp"

#include <cstdlib>
#include <memory>
#include <vector>

namespace boomdyn {

namespace {

PetscErrorCode runInfo(int argc, char **argv, RunInfo *info)
{
  PetscMPIInt size;
  char *options;
  PetscFunctionBeginUser;
  for (int i = 0; i < argc; ++i) info->commandLine += (i ? " " : "") + std::string(argv[i]);
  PetscCall(PetscOptionsGetAll(nullptr, &options));
  info->petscOptions = options;
  PetscCall(PetscFree(options));
  info->version = BOOMDYN_VERSION;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  info->ranks = size;
  PetscFunctionReturn(0);
}

// The program's monitors, in the order they see every step: results first
// (other monitors write into its file), checkpoints after every monitor has
// updated its state, the progress line last.
void addMonitors(Simulation &sim, const AppOptions &opts, const RunInfo &info)
{
  const Scene &scene = sim.scene();
  auto results = std::make_unique<ResultsOutput>(sim, opts.outputPath, opts.overwrite, info, scene.output.state_interval);
  ResultsWriter &writer = results->writer();
  sim.addMonitor(std::move(results));
  if (scene.analysis == Scene::Analysis::Dynamic) {
    sim.addMonitor(std::make_unique<FrictionOutput>(sim, writer, opts.quiet));
    if (!sim.model().eventSources().empty())
      sim.addMonitor(std::make_unique<TypeEventsOutput>(sim, &writer, opts.quiet));
    if (scene.tracking.interval > 0) sim.addMonitor(std::make_unique<FrequencyTracking>(sim, writer));
    sim.addMonitor(std::make_unique<Checkpointer>(sim, opts.checkpointPath, opts.checkpointInterval, opts.quiet));
  }
  if (!opts.quiet) sim.addMonitor(std::make_unique<ProgressLine>(scene.dynamic.t_end, opts.progressInterval));
}

// Test aid (tests/mpi_tests.cmake): an error on one rank only, as a
// rank-local solver or I/O failure would give; the run must not hang.
PetscErrorCode injectedFailure()
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  const char *failRank = std::getenv("BOOMDYN_TEST_FAIL_RANK");
  PetscCheck(!failRank || std::atoi(failRank) != rank, PETSC_COMM_SELF, PETSC_ERR_USER,
             "failure injected on rank %d (BOOMDYN_TEST_FAIL_RANK)", rank);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode reportPartitions(const Scene &scene, PetscInt parts)
{
  PetscFunctionBeginUser;
  PetscCheck(parts >= 1 && parts <= 4096, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
             "-boom_partition_report: the number of parts must be between 1 and 4096, got %" PetscInt_FMT, parts);
  std::unique_ptr<Model> model;
  PetscCallCXX(model = std::make_unique<Model>(scene));
  const int p = static_cast<int>(parts);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "scene '%s': %zu work items, %" PetscInt_FMT " unknowns, %d parts\n",
                        scene.name.c_str(), model->items().size(), model->size(), p));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-12s %10s %10s %10s  items per part\n", "partition", "interface", "cut edges",
                        "imbalance"));
  std::vector<PartitionQuality> qualities; // METIS failures are reported by exception
  PetscCallCXX(qualities = {evaluatePartition(*model, contiguousPartition(*model, p), p, "contiguous"),
                            evaluatePartition(*model, metisPartition(*model, p), p, "METIS k-way")});
  for (const PartitionQuality &q : qualities) {
    std::string counts;
    for (int n : q.itemsPerPart) counts += " " + std::to_string(n);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-12s %10d %10d %10.3f %s\n", q.method.c_str(), q.interfaceUnknowns,
                          q.cutEdges, q.imbalance, counts.c_str()));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode runScene(const Scene &scene, const AppOptions &opts, int argc, char **argv, RunOutcome *outcome)
{
  SimulationOptions options;
  RunInfo info;
  PetscMPIInt size;
  std::unique_ptr<Simulation> sim;
  PetscFunctionBeginUser;
  options.energyTolerance = opts.energyTolerance;
  options.trackingFullSolve = opts.trackingFull;
  options.adaptiveTolerance = opts.adaptiveTolerance;
  options.kinkRestart = opts.kinkRestart;
  options.accelerationPredictor = opts.accelerationPredictor;
  options.filteredStart = opts.filteredStart;
  options.consistentMultipliers = opts.consistentMultipliers;
  options.restartPath = opts.restartPath;
  options.quiet = opts.quiet;
  // A scene that is no mechanism is reported by exception (ModelError).
  PetscCallCXX(sim = std::make_unique<Simulation>(scene, PETSC_COMM_WORLD, options));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  if (!opts.quiet)
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "boomdyn %s: scene '%s' (%s), %" PetscInt_FMT " coordinates, %" PetscInt_FMT
                          " multipliers, %d rank(s) -> %s\n",
                          BOOMDYN_VERSION, scene.name.c_str(), scene.file.c_str(), sim->model().numCoordinates(),
                          sim->model().numMultipliers(), size, opts.outputPath.c_str()));
  PetscCall(sim->setUp());
  if (scene.analysis == Scene::Analysis::Dynamic) PetscCall(injectedFailure());
  PetscCall(runInfo(argc, argv, &info));
  addMonitors(*sim, opts, info);
  PetscCall(sim->run([] { return interruptRequested(PETSC_COMM_WORLD); }));
  *outcome = sim->outcome();
  PetscFunctionReturn(0);
}

} // namespace boomdyn
