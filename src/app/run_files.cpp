// The files of one run: the scene and a restart file are read, the results
// and the checkpoint written. An output that is one of the inputs would
// destroy it (-o scene.yaml replaced the scene), so the files are compared
// by identity (device and inode: a link or another spelling of the path is
// the same file), or by their canonical path when the output does not exist
// yet.
#include "options.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace boomdyn {

namespace {

bool sameFile(const std::string &a, const std::string &b)
{
  if (a.empty() || b.empty()) return false;
  struct stat sa, sb;
  if (stat(a.c_str(), &sa) == 0 && stat(b.c_str(), &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  std::error_code e1, e2;
  const auto ca = std::filesystem::weakly_canonical(a, e1), cb = std::filesystem::weakly_canonical(b, e2);
  return !e1 && !e2 && ca == cb;
}

} // namespace

PetscErrorCode checkRunFiles(const AppOptions &opts, bool dynamic)
{
  const MPI_Comm comm = PETSC_COMM_WORLD;
  PetscFunctionBeginUser;
  std::error_code ignored;
  for (const auto &[option, path] : {std::pair<const char *, std::string>{"-o", opts.outputPath},
                                     std::pair<const char *, std::string>{"-boom_checkpoint", opts.checkpointPath}}) {
    if (!dynamic && std::string(option) == "-boom_checkpoint") continue; // written by dynamic runs only
    PetscCheck(!std::filesystem::is_directory(path, ignored), comm, PETSC_ERR_USER_INPUT,
               "%s %s: is a folder; give a file name (e.g. %s/run.h5)", option, path.c_str(), path.c_str());
    PetscCheck(!sameFile(path, opts.scenePath), comm, PETSC_ERR_USER_INPUT,
               "%s %s is the scene file: it would be overwritten", option, path.c_str());
    PetscCheck(!sameFile(path, opts.restartPath) || std::string(option) == "-boom_checkpoint", comm,
               PETSC_ERR_USER_INPUT, "%s %s is the restart file (-boom_restart): it would be overwritten", option,
               path.c_str());
  }
  PetscCheck(!dynamic || !sameFile(opts.outputPath, opts.checkpointPath), comm, PETSC_ERR_USER_INPUT,
             "-o %s is the checkpoint file (-boom_checkpoint): give them different names", opts.outputPath.c_str());
  PetscFunctionReturn(0);
}

std::string unreadableOptionsFile(int argc, char **argv)
{
  for (int i = 1; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "-options_file" && access(argv[i + 1], R_OK) != 0)
      return std::string("-options_file ") + argv[i + 1] + ": cannot read it (" + std::strerror(errno) + ")";
  return "";
}

} // namespace boomdyn
