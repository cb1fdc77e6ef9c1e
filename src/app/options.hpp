// Run-time options of the boomdyn program. The program's own options carry
// the prefix -boom_ (plus -o for the output file); PETSc's own (-ts_dt,
// -ts_max_time, -snes_*, -ksp_*, -log_view, ...) keep their usual meaning.
#pragma once

#include "boomdyn/scene.hpp"

#include <petscsys.h>

#include <string>

namespace boomdyn {

struct AppOptions {
  std::string scenePath;
  std::string outputPath;  // -o; default: scene file stem + ".h5"
  bool overwrite = false;  // -boom_overwrite
  bool quiet = false;      // -boom_quiet
  double progressInterval = 2.0; // -boom_progress_interval (s of wall time)
  double energyTolerance = 0.05; // -boom_energy_tolerance (0: no energy-balance check)
  double adaptiveTolerance = 0;  // -boom_adaptive_tol (local position error per step; 0: fixed steps)
  double checkpointInterval = 0; // -boom_checkpoint_interval (s of simulated time; 0: only when interrupted)
  std::string checkpointPath;    // -boom_checkpoint (default: output stem + ".chk.h5")
  std::string restartPath;       // -boom_restart: continue a dynamic run from this checkpoint
};

// Scene path from argv[1] (or -scene PATH); the rest from the options database.
PetscErrorCode readAppOptions(int argc, char **argv, AppOptions *opts);
// Apply command-line overrides to the scene (mesh sizes, step, end time,
// rho_inf, output interval, modal count) so that convergence studies need no
// edited files. Invalid values are rejected like bad scene values.
PetscErrorCode applySceneOverrides(Scene *scene);

} // namespace boomdyn
