// One run of a scene by the program: a Simulation with the program's
// monitors (results file, friction, tracking, checkpoints, progress).
#pragma once

#include "options.hpp"

#include "boomdyn/monitor.hpp"
#include "boomdyn/scene.hpp"

#include <petscsys.h>

namespace boomdyn {

// -boom_partition_report P: the contiguous split against a METIS partition
// of the work-item graph into P parts (interface unknowns, balance); no run.
PetscErrorCode reportPartitions(const Scene &scene, PetscInt parts);

// Collective. A run that fails or is interrupted returns 0; outcome says how it ended.
PetscErrorCode runScene(const Scene &scene, const AppOptions &opts, int argc, char **argv, RunOutcome *outcome);

} // namespace boomdyn
