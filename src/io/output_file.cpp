#include "boomdyn/output_file.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace boomdyn {

void refuseFileInUse(const std::string &path)
{
  // A shared lock is refused while a writer holds its exclusive one; it is
  // released at once (close), before this process creates its own file.
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  const bool busy = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  if (busy)
    throw std::runtime_error("output file '" + path + "' is being written by another run (it is locked); it was "
                             "left as it is: choose another -o, or wait for that run to end");
}

std::string specialFileKind(const std::string &path)
{
  struct stat s;
  if (::stat(path.c_str(), &s) != 0 || S_ISREG(s.st_mode)) return "";
  if (S_ISCHR(s.st_mode)) return "a character device";
  if (S_ISBLK(s.st_mode)) return "a block device";
  if (S_ISFIFO(s.st_mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(s.st_mode)) return "a socket";
  if (S_ISDIR(s.st_mode)) return "a folder";
  return "not a regular file";
}

void refuseSpecialFile(const std::string &path, const std::string &what)
{
  const std::string kind = specialFileKind(path);
  if (!kind.empty())
    throw std::runtime_error(what + " '" + path + "' is " + kind + ", not a regular file: it was left as it is; give "
                             "the name of a regular file");
}

std::string placementPath(const std::string &path)
{
  struct stat s;
  if (::lstat(path.c_str(), &s) != 0 || !S_ISLNK(s.st_mode)) return path;
  std::error_code e;
  const std::filesystem::path target = std::filesystem::weakly_canonical(path, e);
  return e ? path : target.string();
}

std::string temporaryName(const std::string &path) { return path + ".tmp" + std::to_string(::getpid()); }

void placeFile(const std::string &temporary, const std::string &path, bool overwrite)
{
  try { // checked last before the rename, whatever the caller checked before
    refuseSpecialFile(path, "output file");
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
  int placed = overwrite ? std::rename(temporary.c_str(), path.c_str()) : ::link(temporary.c_str(), path.c_str());
  if (placed != 0 && !overwrite && errno != EEXIST) {
    // A file system without hard links (FAT, some network mounts): rename,
    // after checking once more that no file has appeared.
    std::error_code ignored;
    if (std::filesystem::exists(path, ignored)) errno = EEXIST;
    else placed = std::rename(temporary.c_str(), path.c_str());
  }
  const int error = errno;
  if (placed == 0) {
    if (!overwrite) ::unlink(temporary.c_str()); // the hard link's first name (no-op after a rename)
    return;
  }
  std::remove(temporary.c_str());
  if (error == EEXIST)
    throw std::runtime_error("output file '" + path + "' already exists; use the overwrite option to replace it");
  throw std::runtime_error("HDF5 file '" + path + "': cannot create the file (" + std::strerror(error) + ")");
}

double freeBytes(const std::string &path)
{
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  struct statvfs fs;
  if (::statvfs(folder.empty() ? "." : folder.c_str(), &fs) != 0) return -1;
  return double(fs.f_bavail) * double(fs.f_frsize);
}

FileIdentity fileIdentity(const std::string &path)
{
  struct stat s;
  FileIdentity id;
  if (::stat(path.c_str(), &s) == 0) id.device = s.st_dev, id.inode = s.st_ino, id.valid = true;
  return id;
}

} // namespace boomdyn
