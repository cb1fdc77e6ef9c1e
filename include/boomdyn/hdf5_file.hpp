// A small RAII writer over the HDF5 C API for boomdyn results files
// (layout: docs/output.md). It is meant for ONE MPI rank: the file is opened
// with the default (serial) driver, so the other ranks must not touch it.
//
// Paths are absolute or relative to the root ("/steps/time" == "steps/time");
// missing groups along a path are created on demand. Every HDF5 failure
// becomes a std::runtime_error naming the file and the object. HDF5's own
// automatic error-stack printing is switched off (process-wide) so that
// errors reach the caller once, as exceptions, instead of on stderr.
//
// The file is written in place (no temporary + rename) so that a run that
// crashes still leaves the data up to its last flush() readable.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace boomdyn {

class Hdf5File {
public:
  // Creates `path`. An existing file is replaced only when `overwrite` is
  // true (never truncated in place: a new file under a temporary name is
  // renamed over it; a file that another process holds locked is refused);
  // otherwise std::runtime_error names the path and the option to use.
  Hdf5File(const std::string &path, bool overwrite);
  ~Hdf5File(); // closes; errors at this point are swallowed (use close())
  Hdf5File(Hdf5File &&) noexcept;
  Hdf5File &operator=(Hdf5File &&) noexcept;
  Hdf5File(const Hdf5File &) = delete;
  Hdf5File &operator=(const Hdf5File &) = delete;

  const std::string &path() const;
  bool isOpen() const;
  // False when the file at path() is no longer the one created here (removed,
  // or replaced by another run): what is written goes nowhere.
  bool stillAtPath() const;
  // True if a group or dataset exists at `objectPath` ("/" always exists).
  bool exists(const std::string &objectPath) const;

  // Attributes on the group or dataset at `objectPath` ("/" = root). A
  // missing object is created as a group. An existing attribute of the same
  // name is replaced, so e.g. a status can be updated during a run.
  void setAttribute(const std::string &objectPath, const std::string &name, const std::string &value);
  void setAttribute(const std::string &objectPath, const std::string &name, double value);
  void setAttribute(const std::string &objectPath, const std::string &name, long long value);
  void setAttribute(const std::string &objectPath, const std::string &name, const std::vector<double> &value);
  // Other integers (int, std::size_t, ...) are stored as 64-bit integers;
  // without this, setAttribute(p, n, 3) would be ambiguous (double vs long long).
  template <typename Int, typename = std::enable_if_t<std::is_integral_v<Int> && !std::is_same_v<Int, bool>>>
  void setAttribute(const std::string &objectPath, const std::string &name, Int value)
  {
    setAttribute(objectPath, name, static_cast<long long>(value));
  }

  // Write-once datasets; writing to an existing path throws.
  // Strings are variable-length UTF-8 (h5py: ds[()] gives bytes, ds.asstr()[()] str).
  void writeString(const std::string &datasetPath, const std::string &text);
  void writeStrings(const std::string &datasetPath, const std::vector<std::string> &texts);
  // Row-major data of shape `dims` (empty dims: a scalar); the product of
  // dims must equal data.size().
  void writeArray(const std::string &datasetPath, const std::vector<double> &data,
                  const std::vector<std::size_t> &dims);
  void writeArray(const std::string &datasetPath, const std::vector<int> &data, const std::vector<std::size_t> &dims);
  // A new group of new double datasets (name, data, dims as writeArray)
  // with one double attribute: the group's path is looked up once, not once
  // per dataset (the /paraview snapshots: those lookups were most of their
  // output time, docs/performance-history.md).
  struct NamedArray {
    std::string name;
    const std::vector<double> *data;
    std::vector<std::size_t> dims;
  };
  void writeGroup(const std::string &groupPath, const std::vector<NamedArray> &arrays, const std::string &attribute,
                  double value);

  // Time series: an extendible chunked dataset of shape (n, ncols), created
  // by the first call and grown by one row per call. The dataset handle is
  // kept open until close(), so an append is one extent change and one write.
  // Appending with a different ncols or element type than at creation throws.
  void appendRow(const std::string &datasetPath, const double *row, std::size_t ncols);
  void appendRow(const std::string &datasetPath, const int *row, std::size_t ncols);
  // Same, but the dataset is 1-D, shape (n).
  void appendScalar(const std::string &datasetPath, double value);
  void appendScalarInt(const std::string &datasetPath, int value);

  // Writes everything buffered (data and metadata) to disk: after it returns
  // the file on disk is a complete, readable HDF5 file. Flush regularly:
  // HDF5 may also write metadata on its own between flushes, so a crash long
  // after the last flush can (rarely) leave a file HDF5 cannot open.
  void flush();
  // Closes the file; idempotent. Any later write throws.
  void close();

private:
  struct Impl;
  Impl &live() const; // the open file's state; throws once closed or moved from
  std::unique_ptr<Impl> impl_;
};

} // namespace boomdyn
