#include "boomdyn/hdf5_file.hpp"

#include "boomdyn/output_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace boomdyn {

namespace {

// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle &&other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Handle &operator=(Handle &&other) noexcept
  {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle &) = delete;
  Handle &operator=(const Handle &) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes now and reports HDF5's status (a destructor could not).
  herr_t reset()
  {
    herr_t status = 0;
    if (id_ >= 0)
      status = closer_(id_);
    id_ = H5I_INVALID_HID;
    return status;
  }

private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// The innermost message on HDF5's error stack, the most specific one (e.g.
// the errno text of a failed open rather than "unable to create file");
// clears the stack.
std::string takeHdf5ErrorDetail()
{
  std::string detail;
  auto keepLast = [](unsigned, const H5E_error2_t *err, void *data) -> herr_t {
    if (err->desc && *err->desc)
      *static_cast<std::string *>(data) = err->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, keepLast, &detail);
  H5Eclear2(H5E_DEFAULT);
  return detail;
}

// "/a//b/" -> "/a/b"; "" and "/" -> "/". One spelling per object, so the
// series cache cannot hold the same dataset under two keys.
std::string normalizePath(const std::string &path)
{
  std::string out;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    std::size_t end = path.find('/', begin);
    if (end == std::string::npos)
      end = path.size();
    if (end > begin)
      out += "/" + path.substr(begin, end - begin);
    begin = end + 1;
  }
  return out.empty() ? "/" : out;
}

// Rows per chunk of an appended dataset: about kChunkBytes per chunk, at most
// kMaxChunkRows rows. Each chunk then fits HDF5's default 1 MiB per-dataset
// chunk cache, so an append touches memory only until the next flush.
constexpr std::size_t kChunkBytes = 256 * 1024;
constexpr std::size_t kMaxChunkRows = 1024;

// One appendable dataset, kept open between appends.
// Rows appended but not yet written: appends are buffered and written in
// blocks (one H5Dset_extent and one H5Dwrite per block instead of per row,
// which made output a quarter of a small run's time); flush() and close()
// write what is pending, so a flushed file has every row.
constexpr hsize_t kBlockRows = 256;

struct Series {
  Handle dataset;
  Handle rowSpace; // memory dataspace of one row
  hid_t memType = H5I_INVALID_HID;
  int rank = 2;
  std::size_t ncols = 0;
  std::size_t rowBytes = 0; // ncols * the memory type's size
  hsize_t rows = 0;        // rows in the file
  hsize_t pendingRows = 0; // rows in `pending`
  std::vector<char> pending;
  double chunkBytes = 0;     // file space of one chunk
  double unflushedBytes = 0; // handed to HDF5 since the last flush (in its chunk cache)
};

} // namespace

struct Hdf5File::Impl {
  std::string path;
  FileIdentity identity; // of the created file (stillAtPath)
  Handle file;
  Handle linkCreate; // creates missing intermediate groups
  Handle stringType; // variable-length UTF-8
  std::unordered_map<std::string, Series> series;
  // Paths known to be groups (nothing is ever deleted from the file): the
  // lookups of a snapshot's datasets, /paraview/N/..., skip their parents.
  mutable std::unordered_set<std::string> groups;

  [[noreturn]] void fail(const std::string &what) const
  {
    std::string message = "HDF5 file '" + path + "': " + what;
    std::string detail = takeHdf5ErrorDetail();
    if (!detail.empty())
      message += " (" + detail + ")";
    throw std::runtime_error(message);
  }
  hid_t checkId(hid_t id, const std::string &what) const
  {
    if (id < 0)
      fail(what);
    return id;
  }
  void checkStatus(herr_t status, const std::string &what) const
  {
    if (status < 0)
      fail(what);
  }

  bool exists(const std::string &normalized) const
  {
    if (normalized == "/")
      return true;
    // Walk the prefixes: H5Lexists fails rather than answering "no" when an
    // intermediate group is missing.
    std::size_t pos = 0;
    while (pos != std::string::npos) {
      pos = normalized.find('/', pos + 1);
      std::string prefix = normalized.substr(0, pos);
      if (pos != std::string::npos && groups.count(prefix))
        continue;
      htri_t found = H5Lexists(file.get(), prefix.c_str(), H5P_DEFAULT);
      if (found < 0)
        fail("cannot look up '" + prefix + "'");
      if (found == 0)
        return false;
      if (pos != std::string::npos && !isGroup(prefix))
        return false; // nothing can be below a dataset
    }
    return true;
  }

  bool isGroup(const std::string &existing) const
  {
    if (groups.count(existing))
      return true;
    Handle object(checkId(H5Oopen(file.get(), existing.c_str(), H5P_DEFAULT), "cannot open '" + existing + "'"),
                  H5Oclose);
    const bool group = H5Iget_type(object.get()) == H5I_GROUP;
    if (group)
      groups.insert(existing);
    return group;
  }

  // Before creating `normalized`: HDF5 would report a dataset along the
  // path only as "message type not found" deep down its error stack.
  void requireParentGroups(const std::string &normalized) const
  {
    for (std::size_t pos = normalized.find('/', 1); pos != std::string::npos; pos = normalized.find('/', pos + 1)) {
      std::string prefix = normalized.substr(0, pos);
      if (groups.count(prefix))
        continue;
      htri_t found = H5Lexists(file.get(), prefix.c_str(), H5P_DEFAULT);
      if (found < 0)
        fail("cannot look up '" + prefix + "'");
      if (found == 0)
        return; // the rest is created on demand
      if (!isGroup(prefix))
        throw std::runtime_error("HDF5 file '" + path + "': cannot create '" + normalized + "', '" + prefix +
                                 "' is a dataset, not a group");
    }
  }

  void requireNew(const std::string &normalized) const
  {
    if (exists(normalized))
      throw std::runtime_error("HDF5 file '" + path + "': '" + normalized + "' already exists");
    requireParentGroups(normalized);
  }

  // The group or dataset at `normalized`, created as a group if missing.
  Handle openOrCreateObject(const std::string &normalized) const
  {
    if (exists(normalized))
      return {checkId(H5Oopen(file.get(), normalized.c_str(), H5P_DEFAULT), "cannot open '" + normalized + "'"),
              H5Oclose};
    requireParentGroups(normalized);
    hid_t group = H5Gcreate2(file.get(), normalized.c_str(), linkCreate.get(), H5P_DEFAULT, H5P_DEFAULT);
    return {checkId(group, "cannot create group '" + normalized + "'"), H5Gclose};
  }

  void writeAttribute(const std::string &objectPath, const std::string &name, hid_t fileType, hid_t memType,
                      hid_t space, const void *buffer) const
  {
    const std::string object = normalizePath(objectPath);
    const std::string where = "attribute '" + name + "' of '" + object + "'";
    Handle target = openOrCreateObject(object);
    htri_t present = H5Aexists(target.get(), name.c_str());
    if (present < 0)
      fail("cannot look up " + where);
    if (present > 0)
      checkStatus(H5Adelete(target.get(), name.c_str()), "cannot replace " + where);
    Handle attribute(checkId(H5Acreate2(target.get(), name.c_str(), fileType, space, H5P_DEFAULT, H5P_DEFAULT),
                             "cannot create " + where),
                     H5Aclose);
    if (H5Sget_simple_extent_npoints(space) > 0) // HDF5 refuses a null buffer even for no values
      checkStatus(H5Awrite(attribute.get(), memType, buffer), "cannot write " + where);
  }

  void writeDataset(const std::string &datasetPath, hid_t fileType, hid_t memType,
                    const std::vector<std::size_t> &dims, const void *buffer) const
  {
    const std::string dataset = normalizePath(datasetPath);
    requireNew(dataset);
    createDataset(file.get(), dataset, dataset, fileType, memType, dims, buffer);
  }

  // The dataset `name` below the open object `location` (the file, or a
  // group just created), `shown` in messages; no lookups of its path.
  void createDataset(hid_t location, const std::string &name, const std::string &shown, hid_t fileType,
                     hid_t memType, const std::vector<std::size_t> &dims, const void *buffer) const
  {
    double bytes = double(H5Tget_size(memType));
    for (std::size_t d : dims) bytes *= double(d);
    ensureSpace(bytes);
    std::vector<hsize_t> extent(dims.begin(), dims.end());
    Handle space(dims.empty() ? H5Screate(H5S_SCALAR)
                              : H5Screate_simple(static_cast<int>(extent.size()), extent.data(), nullptr),
                 H5Sclose);
    checkId(space.get(), "cannot make the dataspace of '" + shown + "'");
    Handle handle(checkId(H5Dcreate2(location, name.c_str(), fileType, space.get(), linkCreate.get(), H5P_DEFAULT,
                                     H5P_DEFAULT),
                          "cannot create dataset '" + shown + "'"),
                  H5Dclose);
    if (H5Sget_simple_extent_npoints(space.get()) > 0)
      checkStatus(H5Dwrite(handle.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer),
                  "cannot write '" + shown + "'");
  }

  Series &findOrCreateSeries(const std::string &dataset, hid_t fileType, hid_t memType, int rank, std::size_t ncols)
  {
    auto found = series.find(dataset);
    if (found != series.end()) {
      const Series &s = found->second;
      if (s.memType != memType || s.rank != rank || s.ncols != ncols)
        throw std::runtime_error("HDF5 file '" + path + "': appending to '" + dataset +
                                 "' with another shape or type than it was created with");
      return found->second;
    }
    if (exists(dataset))
      throw std::runtime_error("HDF5 file '" + path + "': '" + dataset +
                               "' already exists and was not created by appending");
    requireParentGroups(dataset);

    const std::size_t rowBytes = ncols * H5Tget_size(memType);
    const hsize_t chunkRows = std::clamp<std::size_t>(kChunkBytes / rowBytes, 1, kMaxChunkRows);
    // A single row wider than a chunk is split along the columns too.
    const hsize_t chunkCols =
        std::min<std::size_t>(ncols, std::max<std::size_t>(1, kChunkBytes / H5Tget_size(memType)));
    const hsize_t initial[2] = {0, ncols};
    const hsize_t maximum[2] = {H5S_UNLIMITED, ncols};
    const hsize_t chunk[2] = {chunkRows, chunkCols};

    Handle space(checkId(H5Screate_simple(rank, initial, maximum), "cannot make the dataspace of '" + dataset + "'"),
                 H5Sclose);
    Handle layout(checkId(H5Pcreate(H5P_DATASET_CREATE), "cannot make a property list"), H5Pclose);
    checkStatus(H5Pset_chunk(layout.get(), rank, chunk), "cannot set the chunks of '" + dataset + "'");
    Series s;
    s.dataset = Handle(checkId(H5Dcreate2(file.get(), dataset.c_str(), fileType, space.get(), linkCreate.get(),
                                          layout.get(), H5P_DEFAULT),
                               "cannot create dataset '" + dataset + "'"),
                       H5Dclose);
    const hsize_t rowLength = ncols;
    s.rowSpace = Handle(checkId(H5Screate_simple(1, &rowLength, nullptr), "cannot make a row dataspace"), H5Sclose);
    s.memType = memType;
    s.rank = rank;
    s.ncols = ncols;
    s.rowBytes = rowBytes;
    s.chunkBytes = double(chunkRows) * double(rank == 2 ? chunkCols : 1) * double(H5Tget_size(memType));
    return series.emplace(dataset, std::move(s)).first->second;
  }

  void append(const std::string &datasetPath, const void *row, std::size_t ncols, hid_t fileType, hid_t memType,
              int rank)
  {
    // A path that is a key of `series` is in its normal spelling already
    // (keys are normalized): every append after a series' first finds it
    // here, without normalizing the path again (a new string per row, most
    // of the cost of the per-step rows).
    auto found = series.find(datasetPath);
    if (found == series.end() || !row || ncols == 0) {
      const std::string dataset = normalizePath(datasetPath);
      if (!row || ncols == 0)
        throw std::runtime_error("HDF5 file '" + path + "': empty row appended to '" + dataset + "'");
      findOrCreateSeries(dataset, fileType, memType, rank, ncols);
      found = series.find(dataset);
    }
    Series &s = found->second;
    if (s.memType != memType || s.rank != rank || s.ncols != ncols)
      throw std::runtime_error("HDF5 file '" + path + "': appending to '" + found->first +
                               "' with another shape or type than it was created with");
    const char *bytes = static_cast<const char *>(row);
    s.pending.insert(s.pending.end(), bytes, bytes + s.rowBytes);
    ++s.pendingRows;
    if (s.pendingRows >= kBlockRows) writePending(found->first, s);
  }

  // Writes the buffered rows of one series as one block.
  // A full file system must not reach HDF5: a write or flush that fails
  // there leaves a file HDF5 can neither close nor read, and HDF5 then
  // crashes at exit (SIGSEGV in MPI_Finalize). Writing stops while there is
  // still room for the file's metadata and status (kReserve), with an error
  // naming the file; the file stays readable up to its last flush.
  static constexpr double kReserve = 256 * 1024;
  mutable bool full = false;
  // bytes: about to be written. The chunks in HDF5's cache take file space
  // when they are flushed: a new chunk for every series written to since
  // the last flush, plus what was written.
  void ensureSpace(double bytes) const
  {
    for (const auto &[name, s] : series)
      if (s.unflushedBytes > 0) bytes += s.chunkBytes + s.unflushedBytes;
    if (!full) {
      const double available = freeBytes(path);
      if (available < 0 || available >= bytes + kReserve) return;
      full = true;
    }
    throw std::runtime_error("HDF5 file '" + path + "': the file system is full (less than " +
                             std::to_string(static_cast<long long>((bytes + kReserve) / 1024)) +
                             " kB free); writing stopped, what was flushed before is readable");
  }

  void writePending(const std::string &dataset, Series &s)
  {
    if (s.pendingRows == 0) return;
    ensureSpace(double(s.pending.size()) + s.chunkBytes);
    s.unflushedBytes += double(s.pending.size());
    const hsize_t extent[2] = {s.rows + s.pendingRows, s.ncols};
    checkStatus(H5Dset_extent(s.dataset.get(), extent), "cannot extend '" + dataset + "'");
    Handle fileSpace(checkId(H5Dget_space(s.dataset.get()), "cannot get the dataspace of '" + dataset + "'"),
                     H5Sclose);
    const hsize_t start[2] = {s.rows, 0};
    const hsize_t count[2] = {s.pendingRows, s.ncols};
    checkStatus(H5Sselect_hyperslab(fileSpace.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
                "cannot select the new rows of '" + dataset + "'");
    Handle memSpace(checkId(H5Screate_simple(s.rank, count, nullptr), "cannot make a block dataspace"), H5Sclose);
    checkStatus(H5Dwrite(s.dataset.get(), s.memType, memSpace.get(), fileSpace.get(), H5P_DEFAULT, s.pending.data()),
                "cannot append to '" + dataset + "'");
    s.rows += s.pendingRows;
    s.pendingRows = 0;
    s.pending.clear();
  }

  void writeAllPending()
  {
    for (auto &[name, s] : series) writePending(name, s);
  }
};

Hdf5File::Hdf5File(const std::string &path, bool overwrite) : impl_(std::make_unique<Impl>())
{
  // Failures are reported through exceptions carrying the stack's message;
  // HDF5 printing its own stack trace to stderr as well would only be noise.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);

  Impl &impl = *impl_;
  impl.path = path;
  std::error_code ignored;
  if (!overwrite && std::filesystem::exists(path, ignored))
    throw std::runtime_error("output file '" + path + "' already exists; use the overwrite option to replace it");

  // Closing the file closes every object still open in it (a dataset whose
  // close failed on a full disk would otherwise keep the file open, and
  // HDF5 would crash closing it at exit).
  Handle access(impl.checkId(H5Pcreate(H5P_FILE_ACCESS), "cannot make a property list"), H5Pclose);
  impl.checkStatus(H5Pset_fclose_degree(access.get(), H5F_CLOSE_STRONG), "cannot set the close degree");
  // Replacing a file: never truncate it in place, never one that another
  // process is writing. The new file is created under a temporary name (a
  // creation that fails, a full disk, leaves nothing behind) and moved into
  // place, so that a process still writing the old file (without locks)
  // writes to its own, unlinked copy and notices at the end (stillAtPath).
  // A device, FIFO, socket or folder at the path is never replaced; a
  // symbolic link is written through (the link stays).
  refuseSpecialFile(path, "output file");
  const std::string placement = placementPath(path);
  // A file started on a file system without room for its metadata could be
  // neither finished nor closed with a status: none is created.
  if (const double available = freeBytes(placement); available >= 0 && available < Impl::kReserve)
    throw std::runtime_error("HDF5 file '" + path + "': the file system is full (" +
                             std::to_string(static_cast<long long>(available / 1024)) + " kB free, " +
                             std::to_string(static_cast<long long>(Impl::kReserve / 1024)) +
                             " kB are needed to start a file); nothing was written");
  if (overwrite) refuseFileInUse(path);
  const std::string temporary = temporaryName(placement);
  const hid_t created = H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get());
  if (created < 0) {
    std::remove(temporary.c_str());
    impl.fail("cannot create the file");
  }
  impl.file = Handle(created, H5Fclose);
  try {
    placeFile(temporary, placement, overwrite);
  } catch (...) {
    impl.file.reset();
    throw;
  }
  impl.identity = fileIdentity(path);
  impl.linkCreate = Handle(impl.checkId(H5Pcreate(H5P_LINK_CREATE), "cannot make a property list"), H5Pclose);
  impl.checkStatus(H5Pset_create_intermediate_group(impl.linkCreate.get(), 1), "cannot set up group creation");
  impl.stringType = Handle(impl.checkId(H5Tcopy(H5T_C_S1), "cannot make the string type"), H5Tclose);
  impl.checkStatus(H5Tset_size(impl.stringType.get(), H5T_VARIABLE), "cannot set up the string type");
  impl.checkStatus(H5Tset_cset(impl.stringType.get(), H5T_CSET_UTF8), "cannot set up the string type");
}

Hdf5File::~Hdf5File()
{
  try {
    close();
  } catch (...) {
    // A destructor must not throw; callers who care call close() themselves.
  }
}

Hdf5File::Hdf5File(Hdf5File &&) noexcept = default;

Hdf5File &Hdf5File::operator=(Hdf5File &&other) noexcept
{
  if (this != &other) {
    try {
      close();
    } catch (...) {
    }
    impl_ = std::move(other.impl_);
  }
  return *this;
}

const std::string &Hdf5File::path() const
{
  static const std::string none;
  return impl_ ? impl_->path : none;
}

bool Hdf5File::isOpen() const { return impl_ && impl_->file.valid(); }

bool Hdf5File::stillAtPath() const
{
  return impl_ && sameFile(fileIdentity(impl_->path), impl_->identity);
}

Hdf5File::Impl &Hdf5File::live() const
{
  if (!isOpen())
    throw std::runtime_error("HDF5 file '" + path() + "' is closed");
  return *impl_;
}

bool Hdf5File::exists(const std::string &objectPath) const { return live().exists(normalizePath(objectPath)); }

void Hdf5File::setAttribute(const std::string &objectPath, const std::string &name, const std::string &value)
{
  Impl &impl = live();
  Handle space(impl.checkId(H5Screate(H5S_SCALAR), "cannot make a dataspace"), H5Sclose);
  const char *text = value.c_str();
  hid_t type = impl.stringType.get();
  impl.writeAttribute(objectPath, name, type, type, space.get(), &text);
}

void Hdf5File::setAttribute(const std::string &objectPath, const std::string &name, double value)
{
  Impl &impl = live();
  Handle space(impl.checkId(H5Screate(H5S_SCALAR), "cannot make a dataspace"), H5Sclose);
  impl.writeAttribute(objectPath, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), &value);
}

void Hdf5File::setAttribute(const std::string &objectPath, const std::string &name, long long value)
{
  Impl &impl = live();
  Handle space(impl.checkId(H5Screate(H5S_SCALAR), "cannot make a dataspace"), H5Sclose);
  impl.writeAttribute(objectPath, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, space.get(), &value);
}

void Hdf5File::setAttribute(const std::string &objectPath, const std::string &name, const std::vector<double> &value)
{
  Impl &impl = live();
  const hsize_t length = value.size();
  Handle space(impl.checkId(H5Screate_simple(1, &length, nullptr), "cannot make a dataspace"), H5Sclose);
  impl.writeAttribute(objectPath, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), value.data());
}

void Hdf5File::writeString(const std::string &datasetPath, const std::string &text)
{
  Impl &impl = live();
  const char *pointer = text.c_str();
  hid_t type = impl.stringType.get();
  impl.writeDataset(datasetPath, type, type, {}, &pointer);
}

void Hdf5File::writeStrings(const std::string &datasetPath, const std::vector<std::string> &texts)
{
  Impl &impl = live();
  std::vector<const char *> pointers;
  pointers.reserve(texts.size());
  for (const std::string &text : texts)
    pointers.push_back(text.c_str());
  hid_t type = impl.stringType.get();
  impl.writeDataset(datasetPath, type, type, {texts.size()}, pointers.data());
}

namespace {
void requireShape(const std::string &file, const std::string &dataset, std::size_t size,
                  const std::vector<std::size_t> &dims)
{
  std::size_t count = 1;
  for (std::size_t d : dims)
    count *= d;
  if (count != size)
    throw std::runtime_error("HDF5 file '" + file + "': dataset '" + dataset + "' has " + std::to_string(size) +
                             " values, its dimensions ask for " + std::to_string(count));
}
} // namespace

void Hdf5File::writeArray(const std::string &datasetPath, const std::vector<double> &data,
                          const std::vector<std::size_t> &dims)
{
  Impl &impl = live();
  requireShape(path(), datasetPath, data.size(), dims);
  impl.writeDataset(datasetPath, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, data.data());
}

void Hdf5File::writeGroup(const std::string &groupPath, const std::vector<NamedArray> &arrays,
                          const std::string &attribute, double value)
{
  Impl &impl = live();
  const std::string group = normalizePath(groupPath);
  for (const NamedArray &a : arrays) requireShape(path(), group + "/" + a.name, a.data->size(), a.dims);
  impl.requireNew(group);
  Handle handle(impl.checkId(H5Gcreate2(impl.file.get(), group.c_str(), impl.linkCreate.get(), H5P_DEFAULT, H5P_DEFAULT),
                             "cannot create group '" + group + "'"),
                H5Gclose);
  impl.groups.insert(group);
  for (const NamedArray &a : arrays)
    impl.createDataset(handle.get(), a.name, group + "/" + a.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, a.dims,
                       a.data->data());
  Handle space(impl.checkId(H5Screate(H5S_SCALAR), "cannot make a dataspace"), H5Sclose);
  Handle stored(impl.checkId(H5Acreate2(handle.get(), attribute.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                                        H5P_DEFAULT),
                             "cannot create attribute '" + attribute + "' of '" + group + "'"),
                H5Aclose);
  impl.checkStatus(H5Awrite(stored.get(), H5T_NATIVE_DOUBLE, &value),
                   "cannot write attribute '" + attribute + "' of '" + group + "'");
}

void Hdf5File::writeArray(const std::string &datasetPath, const std::vector<int> &data,
                          const std::vector<std::size_t> &dims)
{
  Impl &impl = live();
  requireShape(path(), datasetPath, data.size(), dims);
  impl.writeDataset(datasetPath, H5T_STD_I32LE, H5T_NATIVE_INT, dims, data.data());
}

void Hdf5File::appendRow(const std::string &datasetPath, const double *row, std::size_t ncols)
{
  live().append(datasetPath, row, ncols, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2);
}

void Hdf5File::appendRow(const std::string &datasetPath, const int *row, std::size_t ncols)
{
  live().append(datasetPath, row, ncols, H5T_STD_I32LE, H5T_NATIVE_INT, 2);
}

void Hdf5File::appendScalar(const std::string &datasetPath, double value)
{
  live().append(datasetPath, &value, 1, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1);
}

void Hdf5File::appendScalarInt(const std::string &datasetPath, int value)
{
  live().append(datasetPath, &value, 1, H5T_STD_I32LE, H5T_NATIVE_INT, 1);
}

void Hdf5File::flush()
{
  Impl &impl = live();
  impl.writeAllPending();
  impl.ensureSpace(0);
  impl.checkStatus(H5Fflush(impl.file.get(), H5F_SCOPE_LOCAL), "cannot flush");
  for (auto &[name, s] : impl.series) s.unflushedBytes = 0;
}

void Hdf5File::close()
{
  if (!isOpen())
    return;
  Impl &impl = *impl_;
  // A failed write (a full disk) still closes the file: the error is
  // reported after HDF5 has let go of it, not at exit inside HDF5.
  std::string pendingError;
  try {
    if (!impl.full) impl.writeAllPending(); // a full file system: the rows since the last flush are dropped
  } catch (const std::exception &e) {
    pendingError = e.what();
  }
  // Objects first: the file is only really closed once nothing in it is open.
  impl.series.clear();
  impl.linkCreate.reset();
  impl.stringType.reset();
  const bool closed = impl.file.reset() >= 0;
  if (!pendingError.empty())
    throw std::runtime_error(pendingError);
  if (!closed)
    impl.fail("cannot close the file");
}

} // namespace boomdyn
