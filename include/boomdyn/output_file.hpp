// How an output file (results, checkpoint) is put on disk safely (issue 17):
// never truncated in place, never while another process writes it, created
// under a temporary name and moved into place once it exists, checked at the
// end to still be the file at its path, and written only while the file
// system has room for it (a write that fails inside HDF5 leaves a file HDF5
// can neither close nor read). Used by Hdf5File; POSIX only.
#pragma once

#include <string>
#include <sys/types.h>

namespace boomdyn {

// Throws std::runtime_error when another process holds the file locked for
// writing (HDF5 takes an exclusive flock on the files it writes).
void refuseFileInUse(const std::string &path);
// The name under which `path` is created before it is put in place.
std::string temporaryName(const std::string &path);
// Moves the created temporary to path: replacing an existing file
// (overwrite) by rename, else refusing one that appeared meanwhile (a hard
// link, or a rename after one more check where the file system has none).
// On failure removes the temporary and throws std::runtime_error naming path.
void placeFile(const std::string &temporary, const std::string &path, bool overwrite);
// What path is when it exists and is not a regular file (following
// symbolic links): "a character device", "a block device", "a FIFO (named
// pipe)", "a socket", "a folder"; empty for a regular file or no file. A
// rename onto such a path would remove it (as root: /dev/null replaced by
// a results file), so nothing is ever placed there.
std::string specialFileKind(const std::string &path);
// Throws std::runtime_error naming `what` (e.g. "output file") and path
// when specialFileKind(path) is not empty.
void refuseSpecialFile(const std::string &path, const std::string &what);
// Where a file written to path is put: path itself, or for a symbolic link
// the file it points to (the link stays, as with `cp x link`; a rename
// onto the link would replace the link).
std::string placementPath(const std::string &path);
// Free bytes on the file system of path's folder (-1: unknown).
double freeBytes(const std::string &path);

// The identity of a file (device and inode), to notice that the file at a
// path was removed or replaced by another process.
struct FileIdentity {
  dev_t device = 0;
  ino_t inode = 0;
  bool valid = false;
};
FileIdentity fileIdentity(const std::string &path);
inline bool sameFile(const FileIdentity &a, const FileIdentity &b)
{
  return a.valid && b.valid && a.device == b.device && a.inode == b.inode;
}

} // namespace boomdyn
