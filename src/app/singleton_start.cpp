#include "boomdyn/singleton_start.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace boomdyn {

namespace {

bool underLauncher()
{
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_RANK");
}

} // namespace

// Start-up: Open MPI's singleton start waits about 0.3 s for things a
// one-process run never uses: it launches a supporting daemon (orted) for a
// possible MPI_Comm_spawn, and its default point-to-point layer loads the
// PSM/PSM2 (Omni-Path) transports, whose initialization calibrates a timer
// by sleeping ~0.1 s each, hardware or not (docs/performance-history.md,
// "Start-up"). One process needs neither: unless the user's environment says
// otherwise, a singleton runs without the daemon and with the plain ob1
// layer.
//
// Session directories: isolated singletons all take job family 0, so every
// one of them makes and, when it ends, removes the same directories
// $TMPDIR/ompi.<host>.<uid>/jf.0/...; one that starts while another ends
// fails in MPI_Init ("orte_ess_init failed", mkdir: No such file or
// directory). 13 of 600 runs, 12 at a time, failed so; a test suite runs
// hundreds of short processes side by side (CI saw it). Each singleton
// therefore gets a private base directory, removed at the end.
//
// Runs under mpiexec (which sets OMPI_COMM_WORLD_SIZE or PMIX_RANK) are left
// alone, other MPI implementations ignore these variables, and a setting in
// the user's environment wins.
SingletonStart::SingletonStart()
{
  if (underLauncher()) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0); // 0: an existing setting wins
  setenv("OMPI_MCA_pml", "ob1", 0);
  if (std::getenv("OMPI_MCA_orte_tmpdir_base")) return;
  const char *tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/boomdyn-mpi-XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (!::mkdtemp(name.data())) return; // no private base: Open MPI's default, as before
  sessionBase_ = name.data();
  setenv("OMPI_MCA_orte_tmpdir_base", sessionBase_.c_str(), 1);
}

SingletonStart::~SingletonStart()
{
  if (sessionBase_.empty()) return;
  std::error_code ignored; // a directory left behind is harmless; never throw here
  std::filesystem::remove_all(sessionBase_, ignored);
}

} // namespace boomdyn
