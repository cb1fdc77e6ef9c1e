#include "options.hpp"

#include "boomdyn/schema.hpp"
#include "boomdyn/spatial_embedding.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace boomdyn {

namespace {

// The bodies -boom_elements refines: planar and spatial ANCF beams.
bool isBeam(const BodySpec &b)
{
  return b.type == BodySpec::Type::AncfBeam || b.type == BodySpec::Type::SpatialAncfBeam;
}

// Options of boomdyn read elsewhere than in this file, listed here so that
// they are known to rejectUnknownOptions (their help comes with the solver).
const char *const libraryOptions[] = {"-boom_jacobian_reuse", "-boom_jacobian_refresh_ratio", "-boom_jacobian_max_age",
                                      "-boom_schur_dd", "-boom_newton_block_test"};

// Options read in this file (filled by the Option* helpers as they go).
// More steps than a run can take (1e9 steps of the smallest model take
// about a day).
constexpr double kMaxSteps = 1e9;
// Runs longer than this are announced with their number of steps.
constexpr double kManySteps = 1e7;

std::vector<std::string> &appOptionNames()
{
  static std::vector<std::string> names;
  return names;
}

std::string withoutExtension(const std::string &path, const std::string &extension)
{
  const auto dot = path.rfind(extension);
  return dot != std::string::npos && dot + extension.size() == path.size() ? path.substr(0, dot) : path;
}

PetscErrorCode optionString(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, std::string *value,
                            PetscBool *set = nullptr)
{
  char buf[PETSC_MAX_PATH_LEN];
  PetscBool given = PETSC_FALSE;
  PetscFunctionBeginUser;
  appOptionNames().push_back(name);
  PetscCall(PetscOptionsString(name, help, "docs/options.md", value->c_str(), buf, sizeof buf, &given));
  PetscCheck(!given || buf[0], PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "%s needs a value (%s)", name, help);
  if (given) *value = buf;
  if (set) *set = given;
  PetscFunctionReturn(0);
}

PetscErrorCode optionBool(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, bool *value)
{
  PetscBool flag = *value ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionBeginUser;
  appOptionNames().push_back(name);
  PetscCall(PetscOptionsBool(name, help, "docs/options.md", flag, &flag, nullptr));
  *value = flag;
  PetscFunctionReturn(0);
}

template <class T>
PetscErrorCode optionNumber(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, T *value,
                            PetscBool *set = nullptr)
{
  PetscFunctionBeginUser;
  appOptionNames().push_back(name);
  PetscBool given = PETSC_FALSE, has;
  char text[64] = "";
  PetscCall(PetscOptionsGetString(nullptr, nullptr, name, text, sizeof text, &has));
  // PETSc takes an option without its value as not given.
  PetscCheck(!has || text[0], PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "%s needs a value (%s)", name, help);
  if constexpr (std::is_same_v<T, PetscInt>) {
    PetscCall(PetscOptionsInt(name, help, "docs/options.md", *value, value, &given));
    // PETSc wraps integers beyond PetscInt's range (4294967297 elements would
    // run with 1): read the text again and refuse what does not fit.
    if (given && has) {
      errno = 0;
      char *end = nullptr;
      const long long exact = std::strtoll(text, &end, 10);
      PetscCheck(errno == 0 && end && *end == '\0' && exact == static_cast<long long>(*value), PETSC_COMM_WORLD,
                 PETSC_ERR_USER_INPUT, "%s %s: not an integer in [%" PetscInt_FMT ", %" PetscInt_FMT "]", name, text,
                 PETSC_MIN_INT, PETSC_MAX_INT);
    }
  } else {
    PetscCall(PetscOptionsReal(name, help, "docs/options.md", *value, value, &given));
    // inf and nan parse as numbers; no boomdyn quantity may be either.
    PetscCheck(!given || std::isfinite(*value), PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
               "%s %s: must be a finite number", name, text);
    // The scene's rule for magnitudes (checked_yaml.cpp): products of such
    // numbers would overflow or underflow.
    PetscCheck(!given || *value == 0 || (std::fabs(*value) >= 1e-100 && std::fabs(*value) <= 1e100), PETSC_COMM_WORLD,
               PETSC_ERR_USER_INPUT,
               "%s %s: outside the range boomdyn computes with (0, or 1e-100 to 1e+100 in magnitude)", name, text);
  }
  if (set) *set = given;
  PetscFunctionReturn(0);
}

// Files and the course of the run.
PetscErrorCode readRunOptions(PetscOptionItems *PetscOptionsObject, AppOptions *o)
{
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(optionString(PetscOptionsObject, "-scene", "Scene file (or the first argument)", &o->scenePath));
  std::string stem = o->scenePath.substr(o->scenePath.find_last_of('/') + 1);
  if (stem.find_last_of('.') != std::string::npos) stem = stem.substr(0, stem.find_last_of('.'));
  o->outputPath = stem + ".h5";
  PetscCall(optionString(PetscOptionsObject, "-o", "Results file (HDF5)", &o->outputPath));
  PetscCall(optionBool(PetscOptionsObject, "-boom_overwrite", "Replace an existing results file", &o->overwrite));
  PetscCall(optionBool(PetscOptionsObject, "-boom_quiet", "No progress lines and status messages", &o->quiet));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_progress_interval", "Wall-clock seconds between progress lines",
                         &o->progressInterval));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_energy_tolerance",
                         "Stop a dynamic run whose energy grows beyond the work of loads and drives by this fraction "
                         "of the energy involved (0: no check)", &o->energyTolerance));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_adaptive_tol",
                         "Adaptive steps: largest local position error per step [m] (0: fixed steps)",
                         &o->adaptiveTolerance));
  PetscCall(optionBool(PetscOptionsObject, "-boom_kink_restart",
                       "Land a step on every velocity kink and acceleration jump of a drive and restart there "
                       "(velocity projection at kinks, consistent accelerations); 0: step through them (oscillating "
                       "multipliers)",
                       &o->kinkRestart));
  PetscCall(optionBool(PetscOptionsObject, "-boom_acceleration_predictor",
                       "Start Newton from q + h v + h^2/2 a whenever that predicted the previous step better than "
                       "q + h v (0: always q + h v)",
                       &o->accelerationPredictor));
  PetscCall(optionBool(PetscOptionsObject, "-boom_filtered_start",
                       "Start generalized-alpha (and restart it at kinks) from an algorithmic acceleration without "
                       "the modes the step cannot resolve (0: a = the consistent accelerations)",
                       &o->filteredStart));
  PetscCall(optionBool(PetscOptionsObject, "-boom_consistent_multipliers",
                       "Report the multipliers (reactions, drive forces) of each step from the acceleration-level "
                       "equations at its state (0: the step's own index-3 multipliers, which alternate after a jump "
                       "of a drive's acceleration)",
                       &o->consistentMultipliers));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_checkpoint_interval",
                         "Simulated time between checkpoints (0: only when interrupted)", &o->checkpointInterval));
  o->checkpointPath = withoutExtension(o->outputPath, ".h5") + ".chk.h5";
  PetscCall(optionString(PetscOptionsObject, "-boom_checkpoint", "Checkpoint file", &o->checkpointPath));
  PetscCall(optionString(PetscOptionsObject, "-boom_restart", "Continue a dynamic run from this checkpoint",
                         &o->restartPath));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_partition_report",
                         "No run: compare the contiguous split with a METIS partition into this many parts",
                         &o->partitionParts, &set));
  o->partitionReport = set;
  std::string partition = "contiguous";
  PetscCall(optionString(PetscOptionsObject, "-boom_partition",
                         "Which rank evaluates which work item: contiguous or metis", &partition));
  PetscCall(optionBool(PetscOptionsObject, "-boom_tracking_full",
                       "Frequency tracking: a full eigen-solve at every analysis instead of refining the previous modes",
                       &o->trackingFull));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_error_wait",
                         "Seconds a rank that failed alone waits for the others before it aborts the job",
                         &o->errorWait));
  PetscCall(optionBool(PetscOptionsObject, "-boom_allow_unused",
                       "Options that this run does not use are warnings, not errors", &o->allowUnused));
  PetscFunctionReturn(0);
}

// Sizes of the run that override the scene's values.
struct Overrides {
  PetscBool dt = PETSC_FALSE, rhoInf = PETSC_FALSE, stateInterval = PETSC_FALSE, tracking = PETSC_FALSE;
  PetscBool modalCount = PETSC_FALSE, loadSteps = PETSC_FALSE, tEnd = PETSC_FALSE;
};

PetscErrorCode readSceneOverrides(PetscOptionItems *PetscOptionsObject, Scene *scene, Overrides *set)
{
  PetscInt elements = 0;
  PetscBool all = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(optionNumber(PetscOptionsObject, "-boom_elements", "Elements of every ANCF beam (0: the scene's)",
                         &elements, &all));
  for (BodySpec &b : scene->bodies) {
    if (!isBeam(b)) continue;
    PetscInt n = all ? elements : b.elements;
    const std::string name = "-boom_elements_" + b.name, help = "Elements of the beam '" + b.name + "'";
    PetscCall(optionNumber(PetscOptionsObject, name.c_str(), help.c_str(), &n));
    b.elements = static_cast<int>(n);
  }
  std::string axial = "assumed";
  PetscCall(optionString(PetscOptionsObject, "-boom_axial_integration",
                         "Axial strain of the ANCF element: assumed (projected strain: no membrane locking), full "
                         "(5 Gauss points) or reduced (3)",
                         &axial));
  PetscCheck(axial == "full" || axial == "reduced" || axial == "assumed", PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
             "-boom_axial_integration must be full, reduced or assumed (got '%s')", axial.c_str());
  const SectionSpec::AxialIntegration treatment = axial == "reduced" ? SectionSpec::AxialIntegration::Reduced
                                                  : axial == "assumed" ? SectionSpec::AxialIntegration::Assumed
                                                                       : SectionSpec::AxialIntegration::Full;
  for (BodySpec &b : scene->bodies) b.section.axialIntegration = treatment;
  DynamicSpec &d = scene->dynamic;
  double dt = d.dt;
  PetscCall(optionNumber(PetscOptionsObject, "-ts_dt", "Time step (largest step with -boom_adaptive_tol)", &dt, &set->dt));
  if (set->dt) d.dt = dt, d.dt_min = std::min(d.dt_min, dt);
  PetscCall(optionNumber(PetscOptionsObject, "-ts_max_time", "End time of a dynamic run", &d.t_end, &set->tEnd));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_rho_inf", "Spectral radius at infinity of generalized-alpha",
                         &d.rho_inf, &set->rhoInf));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_state_interval", "Simulated time between state snapshots",
                         &scene->output.state_interval, &set->stateInterval));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_tracking_interval", "Frequency tracking interval (0: off)",
                         &scene->tracking.interval, &set->tracking));
  PetscInt count = scene->modal.count, steps = scene->statics.load_steps;
  PetscCall(optionNumber(PetscOptionsObject, "-boom_modal_count", "Modes of the eigen-analysis", &count,
                         &set->modalCount));
  PetscCall(optionNumber(PetscOptionsObject, "-boom_load_steps", "Load increments of a static analysis", &steps,
                         &set->loadSteps));
  scene->modal.count = static_cast<int>(count);
  scene->statics.load_steps = static_cast<int>(steps);
  bool spatial = false;
  PetscCall(optionBool(PetscOptionsObject, "-boom_spatial",
                       "Run a planar scene as a spatial model in its plane (rigid bodies, pins, clamps, angle drives, "
                       "point forces and masses)",
                       &spatial));
  if (spatial) PetscCallCXX(*scene = spatialEmbedding(*scene));
  PetscFunctionReturn(0);
}

// Overridden values are checked like the scene's own.
PetscErrorCode checkOverrides(const Scene &scene, const Overrides &set)
{
  const MPI_Comm comm = PETSC_COMM_WORLD;
  PetscFunctionBeginUser;
  double elements = 0;
  for (const BodySpec &b : scene.bodies) {
    elements += isBeam(b) ? b.elements : 1;
    PetscCheck(!isBeam(b) || (b.elements >= 1 && b.elements <= 10000000), comm,
               PETSC_ERR_USER_INPUT, "-boom_elements: body '%s' needs between 1 and 1e7 elements (got %d)",
               b.name.c_str(), b.elements);
  }
  // Peak memory per element, measured (/usr/bin/time -v, one rank, the
  // cantilever of inputs/ with -boom_elements 1e4 and 1e5; docs/performance.md):
  // 6.5 KiB from 1e4 to 1e5 elements for a dynamic run (Jacobian pattern and
  // values, KLU factors, state vectors), 5.4 KiB for a static one, 11.1 KiB
  // with an eigen-analysis (the factor of the shifted pencil and the Krylov
  // basis). The estimate is that plus about 20 % for the program itself
  // (about 50 MB), the system and what else runs: 8 kB, or 14 kB when the run
  // solves for modes. A mesh is refused before anything is allocated.
  const bool eigen = scene.analysis == Scene::Analysis::Modal || scene.modal.count > 0 || scene.tracking.interval > 0;
  const double perElement = eigen ? 14e3 : 8e3;
  const double available = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  PetscCheck(elements * perElement < available, comm, PETSC_ERR_USER_INPUT,
             "mesh too large for this machine's memory: %.0f elements need about %.0f GB (%.0f kB per element%s), "
             "the machine has %.0f GB",
             elements, elements * perElement / 1e9, perElement / 1e3, eigen ? " with an eigen-analysis" : "",
             available / 1e9);
  const DynamicSpec &d = scene.dynamic;
  PetscCheck(!set.dt || d.dt > 0, comm, PETSC_ERR_USER_INPUT, "-ts_dt must be > 0 (got %g)", d.dt);
  PetscCheck(!set.tEnd || d.t_end > 0, comm, PETSC_ERR_USER_INPUT, "-ts_max_time must be > 0 (got %g)", d.t_end);
  PetscCheck(!set.rhoInf || (d.rho_inf >= 0 && d.rho_inf <= 1), comm, PETSC_ERR_USER_INPUT,
             "-boom_rho_inf must lie in [0, 1] (got %g)", d.rho_inf);
  PetscCheck(!set.stateInterval || scene.output.state_interval >= 0, comm, PETSC_ERR_USER_INPUT,
             "-boom_state_interval must be >= 0 (got %g)", scene.output.state_interval);
  PetscCheck(!set.tracking || scene.tracking.interval >= 0, comm, PETSC_ERR_USER_INPUT,
             "-boom_tracking_interval must be >= 0 (0 turns tracking off; got %g)", scene.tracking.interval);
  PetscCheck(!set.tracking || scene.tracking.interval == 0 || scene.analysis == Scene::Analysis::Dynamic, comm,
             PETSC_ERR_USER_INPUT, "-boom_tracking_interval needs a dynamic scene");
  PetscCheck(!set.modalCount || (scene.modal.count >= 0 && scene.modal.count <= 1000), comm, PETSC_ERR_USER_INPUT,
             "-boom_modal_count must lie in [0, 1000]");
  PetscCheck(!set.loadSteps || scene.statics.load_steps >= 1, comm, PETSC_ERR_USER_INPUT,
             "-boom_load_steps must be >= 1");
  if (scene.analysis == Scene::Analysis::Dynamic) {
    PetscCheck(!(set.dt || set.tEnd) || d.dt <= d.t_end, comm, PETSC_ERR_USER_INPUT,
               "the step %s s (-ts_dt or dynamic.dt) is longer than the end time %s s (-ts_max_time or dynamic.t_end)",
               numberText(d.dt).c_str(), numberText(d.t_end).c_str());
    // A run of 1e15 steps would never end: refuse it with the number.
    const double steps = d.t_end / d.dt;
    PetscCheck(steps <= kMaxSteps, comm, PETSC_ERR_USER_INPUT,
               "the run would take %s steps (end time %s s / step %s s), more than the limit of %s; use a larger "
               "-ts_dt or a shorter -ts_max_time",
               numberText(steps).c_str(), numberText(d.t_end).c_str(), numberText(d.dt).c_str(),
               numberText(kMaxSteps).c_str());
  }
  PetscFunctionReturn(0);
}

// Options that the analysis of this scene does not use: an error, or with
// -boom_allow_unused a warning, naming each (a -ts_dt on a static scene was
// silently ignored before).
PetscErrorCode checkApplicable(const Scene &scene, const AppOptions &opts)
{
  const bool dynamic = scene.analysis == Scene::Analysis::Dynamic;
  const char *analysis = dynamic ? "dynamic" : scene.analysis == Scene::Analysis::Static ? "static" : "modal";
  PetscFunctionBeginUser;
  const char *dynamicOnly[] = {"-ts_dt", "-ts_max_time", "-boom_rho_inf", "-boom_restart", "-boom_checkpoint",
                               "-boom_checkpoint_interval", "-boom_adaptive_tol", "-boom_energy_tolerance",
                               "-boom_state_interval", "-boom_jacobian_reuse", "-boom_jacobian_refresh_ratio",
                               "-boom_jacobian_max_age", "-boom_schur_dd", "-ts_max_steps", "-ts_exact_final_time"};
  std::vector<std::string> unused;
  for (const char *name : dynamicOnly) {
    PetscBool given;
    PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &given));
    if (given && !dynamic) unused.push_back(name);
  }
  PetscBool steps;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-boom_load_steps", &steps));
  if (steps && dynamic) unused.push_back("-boom_load_steps");
  for (const std::string &name : unused) {
    const std::string reason = name + " does not apply to the " + analysis + " analysis of " + scene.file;
    PetscCheck(opts.allowUnused, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
               "%s (-boom_allow_unused: ignore it with a warning)", reason.c_str());
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "warning: %s: ignored\n", reason.c_str()));
  }
  PetscFunctionReturn(0);
}

// An interval of simulated time below the step fires at every step.
PetscErrorCode warnShortInterval(const char *what, double interval, double dt)
{
  PetscFunctionBeginUser;
  if (interval > 0 && interval < dt)
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "warning: %s %s s is shorter than the step %s s: at every step\n", what,
                          numberText(interval).c_str(), numberText(dt).c_str()));
  PetscFunctionReturn(0);
}

// Edits (insertions, deletions, substitutions) between two names.
std::size_t editDistance(const std::string &a, const std::string &b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// An option name (-ts_dt), not a value (-5, -1e-3, -.5, -inf).
bool isOptionName(const std::string &word)
{
  if (word.size() < 2 || word[0] != '-' || !std::isalpha(static_cast<unsigned char>(word[1]))) return false;
  return word != "-inf" && word != "-nan" && word != "-INF" && word != "-NAN" && word != "-Inf";
}

// PETSc's and MPI's options for the whole program (logging, memory, debugger, ...).
bool isGlobalPetscOption(const std::string &name)
{
  static const char *const global[] = {
      "-help", "-version", "-log", "-malloc", "-memory_view", "-info", "-options_", "-on_error_",
      "-no_signal_handler", "-fp_trap", "-debugger", "-start_in_debugger", "-stop_for_debugger", "-display", "-nox",
      "-checkstack", "-objects_dump", "-skip_petscrc", "-history", "-check_pointer_intensity", "-error_output_",
      "-get_total_flops", "-saws", "-mpi", "-petsc", "-use_gpu_aware_mpi", "-device", "-viewer_", "-draw_",
      "-x_virtual", "-python", "-slepc", "-vec_", "-sf_", "-is_", "-dm_", "-citations", "-timing"};
  for (const char *g : global)
    if (name.rfind(g, 0) == 0) return true;
  return false;
}

// An option of PETSc or SLEPc: a global one, or one of the solver families,
// plain (dynamics) or with the statics' (static_) or the eigen-analysis'
// (modal_) prefix.
bool isPetscOption(const std::string &name)
{
  if (isGlobalPetscOption(name)) return true;
  static const char *const families[] = {"ts_", "snes_", "ksp_", "pc_", "mat_", "eps_", "pep_", "st_", "bv_", "ds_", "rg_",
                                         "fn_", "boom_"};
  for (const char *prefix : {"-", "-static_", "-modal_"})
    for (const char *f : families)
      if (name.rfind(std::string(prefix) + f, 0) == 0 && (std::string(f) != "boom_" || std::string(prefix) != "-"))
        return true;
  return false;
}

} // namespace

PetscErrorCode sceneArgument(int argc, char **argv, std::string *path)
{
  char buf[PETSC_MAX_PATH_LEN];
  PetscBool set;
  PetscFunctionBeginUser;
  if (argc > 1 && argv[1][0] != '-') *path = argv[1];
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-scene", buf, sizeof buf, &set));
  if (set) *path = buf;
  PetscFunctionReturn(0);
}

PetscErrorCode readAppOptions(Scene *scene, AppOptions *opts)
{
  Scene noScene; // -help without a scene: the overriding options with their built-in defaults
  Overrides set;
  PetscBool help;
  PetscFunctionBeginUser;
  appOptionNames().clear();
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "boomdyn: run options (docs/options.md)", "boomdyn");
  PetscCall(readRunOptions(PetscOptionsObject, opts));
  PetscCall(readSceneOverrides(PetscOptionsObject, scene ? scene : &noScene, &set));
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  opts->help = help;
  PetscCheck(opts->energyTolerance >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-boom_energy_tolerance must be >= 0");
  PetscCheck(opts->adaptiveTolerance >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-boom_adaptive_tol must be >= 0");
  PetscCheck(opts->checkpointInterval >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
             "-boom_checkpoint_interval must be >= 0");
  PetscCheck(opts->errorWait >= 0 && opts->errorWait <= 86400, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
             "-boom_error_wait must lie in [0, 86400] s (got %s)", numberText(opts->errorWait).c_str());
  if (!scene) PetscFunctionReturn(0);
  PetscCall(checkOverrides(*scene, set));
  PetscCall(checkApplicable(*scene, *opts));
  if (scene->analysis == Scene::Analysis::Dynamic) {
    const double dt = scene->dynamic.dt, steps = scene->dynamic.t_end / dt;
    if (steps > kManySteps && !opts->quiet)
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "warning: the run takes %s steps (end time %s s / step %s s)\n",
                            numberText(steps).c_str(), numberText(scene->dynamic.t_end).c_str(),
                            numberText(dt).c_str()));
    PetscCall(warnShortInterval("the state interval (-boom_state_interval, output.state_interval)",
                                scene->output.state_interval, dt));
    PetscCall(warnShortInterval("the tracking interval (-boom_tracking_interval, tracking.interval)",
                                scene->tracking.interval, dt));
    PetscCall(warnShortInterval("the checkpoint interval (-boom_checkpoint_interval)", opts->checkpointInterval, dt));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode rejectUnknownOptions(const Scene *scene)
{
  char *all;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  std::istringstream words(all);
  PetscCall(PetscFree(all));
  std::vector<std::string> known = appOptionNames();
  known.insert(known.end(), std::begin(libraryOptions), std::end(libraryOptions));
  const std::string perBody = "-boom_elements_";
  std::string word;
  while (words >> word) {
    if (!isOptionName(word) || std::find(known.begin(), known.end(), word) != known.end()) continue;
    if (word.rfind("-boom_", 0) != 0) {
      // Not boomdyn's: it must belong to a family of PETSc or SLEPc options
      // (possibly with the statics' or the eigen-analysis' prefix).
      PetscCheck(isPetscOption(word), PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
                 "unknown option %s: neither a boomdyn option (-boom_..., -o, -scene) nor a PETSc or SLEPc one "
                 "(boomdyn -help lists them)",
                 word.c_str());
      continue;
    }
    if (word.rfind(perBody, 0) == 0 && word.size() > perBody.size()) {
      // Every -boom_elements_<name> must name an ANCF body of this scene.
      const std::string name = word.substr(perBody.size());
      bool found = !scene;
      for (const BodySpec &b : scene ? scene->bodies : std::vector<BodySpec>{})
        found = found || (b.name == name && b.type == BodySpec::Type::AncfBeam);
      PetscCheck(found, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "%s: the scene has no ANCF beam named '%s'",
                 word.c_str(), name.c_str());
      continue;
    }
    const auto closest = std::min_element(known.begin(), known.end(), [&](const std::string &a, const std::string &b) {
      return editDistance(word, a) < editDistance(word, b);
    });
    SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "unknown option %s; did you mean %s? (boomdyn -help lists them all)",
            word.c_str(), closest->c_str());
  }
  PetscFunctionReturn(0);
}

PetscErrorCode userOptionNames(std::vector<std::string> *names)
{
  char *all;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  std::istringstream words(all);
  PetscCall(PetscFree(all));
  std::string word;
  names->clear();
  while (words >> word)
    if (isOptionName(word)) names->push_back(word);
  PetscFunctionReturn(0);
}

PetscErrorCode reportUnusedOptions(const std::vector<std::string> &given, std::string *unused)
{
  PetscInt n;
  char **names, **values;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  unused->clear();
  for (PetscInt i = 0; i < n; ++i) {
    const std::string name = std::string("-") + names[i];
    // Options that PETSc or boomdyn set for themselves (-mat_mumps_icntl_14) are not the user's.
    if (std::find(given.begin(), given.end(), name) == given.end() || isGlobalPetscOption(name)) continue;
    *unused += (unused->empty() ? "" : " ") + name;
  }
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  PetscFunctionReturn(0);
}

PetscErrorCode rejectStrayArguments(int argc, char **argv)
{
  PetscFunctionBeginUser;
  // argv[1] is the scene; after it, every word is an option or the value of
  // the option before it. A word after a word is a second scene or a value
  // without its option.
  // A switch (-boom_quiet) followed by a word that is no truth value: the
  // word is a stray argument too (PETSc would say "Unknown logical value").
  const char *switches[] = {"-boom_overwrite", "-boom_quiet", "-boom_allow_unused", "-boom_jacobian_reuse",
                            "-boom_schur_dd"};
  const char *truth[] = {"1", "0", "true", "false", "yes", "no", "on", "off", "TRUE", "FALSE", "YES", "NO"};
  for (int i = 2; i < argc; ++i) {
    const bool afterSwitch = std::find_if(std::begin(switches), std::end(switches), [&](const char *s) {
                               return std::strcmp(s, argv[i - 1]) == 0;
                             }) != std::end(switches);
    const bool truthValue = std::find_if(std::begin(truth), std::end(truth), [&](const char *s) {
                              return std::strcmp(s, argv[i]) == 0;
                            }) != std::end(truth);
    PetscCheck(isOptionName(argv[i]) || (isOptionName(argv[i - 1]) && !(afterSwitch && !truthValue)),
               PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
               "unexpected argument '%s' after '%s': boomdyn runs one scene (the first argument), and every other "
               "argument is an option (-name [value])",
               argv[i], argv[i - 1]);
  }
  PetscFunctionReturn(0);
}

} // namespace boomdyn
