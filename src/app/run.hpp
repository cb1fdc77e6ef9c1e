// One run of a scene: static, dynamic or modal analysis, with results written
// as described in docs/output.md.
#pragma once

#include "options.hpp"

#include "boomdyn/scene.hpp"

#include <petscsys.h>

#include <stdexcept>

namespace boomdyn {

// A run stopped by SIGINT/SIGTERM (after writing a checkpoint).
class Interrupted : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// -boom_partition_report P: the contiguous split against a METIS partition
// of the work-item graph into P parts (interface unknowns, balance); no run.
PetscErrorCode reportPartitions(const Scene &scene, PetscInt parts);

PetscErrorCode runScene(const Scene &scene, const AppOptions &opts, int argc, char **argv);

} // namespace boomdyn
