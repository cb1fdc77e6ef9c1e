#include "options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace boomdyn {

namespace {

// Options of boomdyn read elsewhere than in this file, listed here so that
// they are known to rejectUnknownOptions (their help comes with the solver).
const char *const libraryOptions[] = {"-boom_jacobian_reuse", "-boom_jacobian_refresh_ratio", "-boom_jacobian_max_age",
                                      "-boom_schur_dd", "-boom_newton_block_test"};

// Options read in this file (filled by the Option* helpers as they go).
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
  PetscCall(PetscOptionsString(name, help, "README.md", value->c_str(), buf, sizeof buf, &given));
  if (given) *value = buf;
  if (set) *set = given;
  PetscFunctionReturn(0);
}

PetscErrorCode optionBool(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, bool *value)
{
  PetscBool flag = *value ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionBeginUser;
  appOptionNames().push_back(name);
  PetscCall(PetscOptionsBool(name, help, "README.md", flag, &flag, nullptr));
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
  if constexpr (std::is_same_v<T, PetscInt>) {
    PetscCall(PetscOptionsInt(name, help, "README.md", *value, value, &given));
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
    PetscCall(PetscOptionsReal(name, help, "README.md", *value, value, &given));
    // inf and nan parse as numbers; no boomdyn quantity may be either.
    PetscCheck(!given || std::isfinite(*value), PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
               "%s %s: must be a finite number", name, text);
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
  PetscCall(optionNumber(PetscOptionsObject, "-boom_error_wait",
                         "Seconds a rank that failed alone waits for the others before it aborts the job",
                         &o->errorWait));
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
    if (b.type != BodySpec::Type::AncfBeam) continue;
    PetscInt n = all ? elements : b.elements;
    const std::string name = "-boom_elements_" + b.name, help = "Elements of the beam '" + b.name + "'";
    PetscCall(PetscOptionsInt(name.c_str(), help.c_str(), "README.md", n, &n, nullptr));
    b.elements = static_cast<int>(n);
  }
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
  PetscFunctionReturn(0);
}

// Overridden values are checked like the scene's own.
PetscErrorCode checkOverrides(const Scene &scene, const Overrides &set)
{
  const MPI_Comm comm = PETSC_COMM_WORLD;
  PetscFunctionBeginUser;
  double elements = 0;
  for (const BodySpec &b : scene.bodies) {
    elements += b.type == BodySpec::Type::AncfBeam ? b.elements : 1;
    PetscCheck(b.type != BodySpec::Type::AncfBeam || (b.elements >= 1 && b.elements <= 10000000), comm,
               PETSC_ERR_USER_INPUT, "-boom_elements: body '%s' needs between 1 and 1e7 elements (got %d)",
               b.name.c_str(), b.elements);
  }
  // About 4 kB per element (Jacobian pattern and values, factorization,
  // state vectors): refuse meshes that cannot fit before allocating them.
  const double available = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  PetscCheck(elements * 4096.0 < available, comm, PETSC_ERR_USER_INPUT,
             "mesh too large for this machine's memory: %.0f elements need about %.0f GB, the machine has %.0f GB",
             elements, elements * 4096.0 / 1e9, available / 1e9);
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
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "boomdyn: run options (README.md)", "boomdyn");
  PetscCall(readRunOptions(PetscOptionsObject, opts));
  PetscCall(readSceneOverrides(PetscOptionsObject, scene ? scene : &noScene, &set));
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  opts->help = help;
  PetscCheck(opts->energyTolerance >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-boom_energy_tolerance must be >= 0");
  PetscCheck(opts->adaptiveTolerance >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-boom_adaptive_tol must be >= 0");
  PetscCheck(opts->checkpointInterval >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT,
             "-boom_checkpoint_interval must be >= 0");
  if (scene) PetscCall(checkOverrides(*scene, set));
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
    if (word.rfind("-boom_", 0) != 0 || std::find(known.begin(), known.end(), word) != known.end()) continue;
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

} // namespace boomdyn
