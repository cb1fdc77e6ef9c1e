#include "options.hpp"

#include <cstring>
#include <unistd.h>
#include <stdexcept>
#include <string>

namespace boomdyn {

namespace {
// Bad options are user errors: a one-line message from main, not a PETSc traceback.
void require(bool condition, const std::string &message)
{
  if (!condition) throw std::invalid_argument(message);
}
} // namespace

PetscErrorCode readAppOptions(int argc, char **argv, AppOptions *opts)
{
  char buf[PETSC_MAX_PATH_LEN];
  PetscBool set;
  PetscFunctionBeginUser;
  if (argc > 1 && argv[1][0] != '-') opts->scenePath = argv[1];
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-scene", buf, sizeof buf, &set));
  if (set) opts->scenePath = buf;
  require(!opts->scenePath.empty(),
          "usage: boomdyn SCENE.yaml [-o OUT.h5] [-boom_overwrite] [-boom_quiet] [PETSc options]; see README.md");
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-o", buf, sizeof buf, &set));
  if (set) opts->outputPath = buf;
  else {
    std::string stem = opts->scenePath;
    const auto slash = stem.find_last_of('/');
    if (slash != std::string::npos) stem = stem.substr(slash + 1);
    const auto dot = stem.find_last_of('.');
    if (dot != std::string::npos) stem = stem.substr(0, dot);
    opts->outputPath = stem + ".h5";
  }
  PetscBool flag = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(nullptr, "boom_", "-overwrite", &flag, nullptr));
  opts->overwrite = flag;
  flag = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(nullptr, "boom_", "-quiet", &flag, nullptr));
  opts->quiet = flag;
  PetscCall(PetscOptionsGetReal(nullptr, "boom_", "-progress_interval", &opts->progressInterval, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, "boom_", "-energy_tolerance", &opts->energyTolerance, nullptr));
  require(opts->energyTolerance >= 0, "-boom_energy_tolerance must be >= 0");
  PetscCall(PetscOptionsGetReal(nullptr, "boom_", "-adaptive_tol", &opts->adaptiveTolerance, nullptr));
  require(opts->adaptiveTolerance >= 0, "-boom_adaptive_tol must be >= 0");
  PetscCall(PetscOptionsGetReal(nullptr, "boom_", "-checkpoint_interval", &opts->checkpointInterval, nullptr));
  require(opts->checkpointInterval >= 0, "-boom_checkpoint_interval must be >= 0");
  PetscCall(PetscOptionsGetString(nullptr, "boom_", "-checkpoint", buf, sizeof buf, &set));
  if (set) opts->checkpointPath = buf;
  else {
    const std::string out = opts->outputPath;
    const auto dot = out.rfind(".h5");
    opts->checkpointPath = (dot != std::string::npos && dot + 3 == out.size() ? out.substr(0, dot) : out) + ".chk.h5";
  }
  PetscCall(PetscOptionsGetString(nullptr, "boom_", "-restart", buf, sizeof buf, &set));
  if (set) opts->restartPath = buf;
  PetscFunctionReturn(0);
}

PetscErrorCode applySceneOverrides(Scene *scene)
{
  PetscInt n;
  PetscReal r;
  PetscBool set;
  PetscFunctionBeginUser;
  // -boom_elements N: every ANCF body; -boom_elements_<body> N: one body.
  PetscCall(PetscOptionsGetInt(nullptr, "boom_", "-elements", &n, &set));
  for (BodySpec &b : scene->bodies) {
    if (b.type != BodySpec::Type::AncfBeam) continue;
    if (set) b.elements = static_cast<int>(n);
    PetscBool one;
    PetscInt m;
    PetscCall(PetscOptionsGetInt(nullptr, "boom_", ("-elements_" + b.name).c_str(), &m, &one));
    if (one) b.elements = static_cast<int>(m);
    require(b.elements >= 1 && b.elements <= 10000000,
            "-boom_elements: body '" + b.name + "' needs between 1 and 1e7 elements (got " + std::to_string(b.elements) + ")");
  }
  // Every -boom_elements_<name> must name an ANCF body of this scene.
  char *all;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  const std::string options = all;
  PetscCall(PetscFree(all));
  for (std::size_t pos = options.find("-boom_elements_"); pos != std::string::npos;
       pos = options.find("-boom_elements_", pos + 1)) {
    const std::size_t end = options.find_first_of(" \t", pos);
    const std::string name = options.substr(pos + 15, end == std::string::npos ? std::string::npos : end - pos - 15);
    bool found = false;
    for (const BodySpec &b : scene->bodies) found = found || (b.name == name && b.type == BodySpec::Type::AncfBeam);
    require(found, "-boom_elements_" + name + ": the scene has no ANCF beam named '" + name + "'");
  }
  // About 4 kB per element (Jacobian pattern and values, factorization,
  // state vectors): refuse meshes that cannot fit before allocating them.
  double elements = 0;
  for (const BodySpec &b : scene->bodies) elements += b.type == BodySpec::Type::AncfBeam ? b.elements : 1;
  const double available = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  require(elements * 4096.0 < available,
          "mesh too large for this machine's memory: " + std::to_string(static_cast<long long>(elements)) +
            " elements need about " + std::to_string(static_cast<long long>(elements * 4096.0 / 1e9)) +
            " GB, the machine has " + std::to_string(static_cast<long long>(available / 1e9)) + " GB");
  DynamicSpec &d = scene->dynamic;
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-ts_dt", &r, &set));
  if (set) {
    require(r > 0, "-ts_dt must be > 0 (got " + std::to_string(r) + ")");
    d.dt = r;
    d.dt_min = std::min(d.dt_min, r);
  }
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-ts_max_time", &r, &set));
  if (set) {
    require(r > 0, "-ts_max_time must be > 0 (got " + std::to_string(r) + ")");
    d.t_end = r;
  }
  PetscCall(PetscOptionsGetReal(nullptr, "boom_", "-rho_inf", &r, &set));
  if (set) {
    require(r >= 0 && r <= 1, "-boom_rho_inf must lie in [0, 1] (got " + std::to_string(r) + ")");
    d.rho_inf = r;
  }
  PetscCall(PetscOptionsGetReal(nullptr, "boom_", "-state_interval", &r, &set));
  if (set) {
    require(r >= 0, "-boom_state_interval must be >= 0 (got " + std::to_string(r) + ")");
    scene->output.state_interval = r;
  }
  PetscCall(PetscOptionsGetReal(nullptr, "boom_", "-tracking_interval", &r, &set));
  if (set) {
    require(r >= 0, "-boom_tracking_interval must be >= 0 (0 turns tracking off; got " + std::to_string(r) + ")");
    require(r == 0 || scene->analysis == Scene::Analysis::Dynamic, "-boom_tracking_interval needs a dynamic scene");
    scene->tracking.interval = r;
  }
  PetscCall(PetscOptionsGetInt(nullptr, "boom_", "-modal_count", &n, &set));
  if (set) {
    require(n >= 0 && n <= 1000, "-boom_modal_count must lie in [0, 1000]");
    scene->modal.count = static_cast<int>(n);
  }
  PetscCall(PetscOptionsGetInt(nullptr, "boom_", "-load_steps", &n, &set));
  if (set) {
    require(n >= 1, "-boom_load_steps must be >= 1");
    scene->statics.load_steps = static_cast<int>(n);
  }
  PetscFunctionReturn(0);
}

} // namespace boomdyn
