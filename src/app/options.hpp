// Run-time options of the boomdyn program. The program's own options carry
// the prefix -boom_ (plus -o and -scene); PETSc's own (-ts_dt, -ts_max_time,
// -snes_*, -ksp_*, -log_view, ...) keep their usual meaning. Every option is
// read inside one PetscOptionsBegin/End block, so -help lists each with its
// default (the scene's value where the scene sets it), and a misspelt -boom_
// option is an error naming the closest valid one.
#pragma once

#include "boomdyn/scene.hpp"

#include <petscsys.h>

#include <string>
#include <vector>

namespace boomdyn {

struct AppOptions {
  std::string scenePath;
  std::string outputPath;  // -o; default: scene file stem + ".h5"
  bool overwrite = false;  // -boom_overwrite
  bool quiet = false;      // -boom_quiet
  double progressInterval = 2.0; // -boom_progress_interval (s of wall time)
  double energyTolerance = 0.05; // -boom_energy_tolerance (0: no energy-balance check)
  double adaptiveTolerance = 0;  // -boom_adaptive_tol (local position error per step; 0: fixed steps)
  bool kinkRestart = true;       // -boom_kink_restart (restart at drives' velocity kinks)
  bool accelerationPredictor = true; // -boom_acceleration_predictor (Newton's start from h^2/2 a_n when it helps)
  bool filteredStart = true; // -boom_filtered_start (the first step's a without the unresolved modes)
  bool consistentMultipliers = false; // -boom_consistent_multipliers (reported multipliers from the acceleration level)
  double checkpointInterval = 0; // -boom_checkpoint_interval (s of simulated time; 0: only when interrupted)
  std::string checkpointPath;    // -boom_checkpoint (default: output stem + ".chk.h5")
  std::string restartPath;       // -boom_restart: continue a dynamic run from this checkpoint
  bool partitionReport = false;  // -boom_partition_report P: no run, a partition report into P parts
  PetscInt partitionParts = 0;
  double errorWait = 30;         // -boom_error_wait (s), in [0, 1 day]
  bool allowUnused = false;      // -boom_allow_unused: unused options are warnings
  bool trackingFull = false;     // -boom_tracking_full: full eigen-solve at every tracking analysis
  bool help = false;             // -help: options listed, no run without a scene
};

// The scene path: argv[1] unless it is an option, or -scene PATH.
PetscErrorCode sceneArgument(int argc, char **argv, std::string *path);
// Every option, with its help text. scene (may be null with -help): the
// scene whose values are the defaults of the overriding options (mesh
// sizes, step, end time, rho_inf, intervals, modal count, load steps),
// changed in place so that convergence studies need no edited files.
// Invalid values are user errors (PETSC_ERR_USER_INPUT) naming the option.
PetscErrorCode readAppOptions(Scene *scene, AppOptions *opts);
// Collective: an error naming every -boom_ option of the database that
// boomdyn does not know, and the closest one it knows.
// Every other option must be a PETSc or SLEPc option (by family: -ts_,
// -ksp_, -static_snes_, -modal_eps_, -log_view, ...).
PetscErrorCode rejectUnknownOptions(const Scene *scene);
// A word after the scene that is neither an option nor an option's value
// (a second scene file) is an error.
PetscErrorCode rejectStrayArguments(int argc, char **argv);
// The names of the options in the database (the user's, before the run).
PetscErrorCode userOptionNames(std::vector<std::string> *names);
// The options among `given` that nothing read during the run, separated by
// blanks (PETSc's own global options excepted).
PetscErrorCode reportUnusedOptions(const std::vector<std::string> &given, std::string *unused);

// Collective: an output (results, checkpoint) that is an input of the run
// (scene, restart file) or a folder, or results and checkpoint in one file,
// is an error naming the option (run_files.cpp).
PetscErrorCode checkRunFiles(const AppOptions &opts, bool dynamic);
// Before PetscInitialize: an -options_file that cannot be read, as one line
// (PETSc would print a traceback); empty when there is none.
std::string unreadableOptionsFile(int argc, char **argv);

} // namespace boomdyn
