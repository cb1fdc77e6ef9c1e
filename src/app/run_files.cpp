// The files of one run: the scene and a restart file are read, the results
// and the checkpoint written. An output that is one of the inputs would
// destroy it (-o scene.yaml replaced the scene), so the files are compared
// by identity (device and inode: a link or another spelling of the path is
// the same file), or by their canonical path when the output does not exist
// yet.
#include "options.hpp"

#include "boomdyn/output_file.hpp"

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
    // A rename onto a device (as root: -o /dev/null), FIFO or socket would
    // replace it by a results file; the io layer refuses too, this says which option.
    const std::string kind = specialFileKind(path);
    PetscCheck(kind.empty(), comm, PETSC_ERR_USER_INPUT,
               "%s %s: is %s, not a regular file; it is left as it is: give the name of a regular file", option,
               path.c_str(), kind.c_str());
    PetscCheck(!sameFile(path, opts.scenePath), comm, PETSC_ERR_USER_INPUT,
               "%s %s is the scene file: it would be overwritten", option, path.c_str());
    PetscCheck(!sameFile(path, opts.restartPath) || std::string(option) == "-boom_checkpoint", comm,
               PETSC_ERR_USER_INPUT, "%s %s is the restart file (-boom_restart): it would be overwritten", option,
               path.c_str());
  }
  // The XDMF descriptions next to the results (RUN.xmf, RUN.ropes.xmf) are replaced by rename too.
  const std::string &out = opts.outputPath; // the stem as ResultsWriter::writeXdmf takes it
  const std::string stem = out.size() > 3 && out.compare(out.size() - 3, 3, ".h5") == 0 ? out.substr(0, out.size() - 3) : out;
  for (const std::string &xdmf : {stem + ".xmf", stem + ".ropes.xmf"}) {
    const std::string kind = specialFileKind(xdmf);
    PetscCheck(kind.empty(), comm, PETSC_ERR_USER_INPUT,
               "-o %s: its XDMF file %s is %s, not a regular file; it is left as it is: choose another -o",
               opts.outputPath.c_str(), xdmf.c_str(), kind.c_str());
  }
  // A restart file is read whole: a FIFO would block the run, a device give garbage.
  if (dynamic && !opts.restartPath.empty()) {
    const std::string kind = specialFileKind(opts.restartPath);
    PetscCheck(kind.empty(), comm, PETSC_ERR_USER_INPUT,
               "-boom_restart %s: is %s, not a regular file: give a checkpoint file written by boomdyn",
               opts.restartPath.c_str(), kind.c_str());
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
