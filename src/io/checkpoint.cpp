#include "boomdyn/checkpoint.hpp"

#include "boomdyn/gather.hpp"

#include "boomdyn/hdf5_file.hpp"
#include "boomdyn/output_file.hpp"

#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <cstdio>
#include <stdexcept>

namespace boomdyn {

namespace {

// Gather a distributed vector on rank 0.
// Raw HDF5 reading (rank 0).
std::vector<double> readDoubles(hid_t file, const std::string &path)
{
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (d < 0) throw std::runtime_error("missing dataset " + path);
  const hid_t space = H5Dget_space(d);
  std::vector<double> out(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  const herr_t status = H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  H5Sclose(space);
  H5Dclose(d);
  if (status < 0) throw std::runtime_error("cannot read dataset " + path);
  return out;
}

std::vector<std::string> readStrings(hid_t file, const std::string &path)
{
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (d < 0) throw std::runtime_error("missing dataset " + path);
  const hid_t space = H5Dget_space(d);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  std::vector<char *> buf(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)), nullptr);
  const herr_t status = H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data());
  std::vector<std::string> out;
  for (char *s : buf) out.emplace_back(s ? s : "");
  if (status >= 0) H5Dvlen_reclaim(type, space, H5P_DEFAULT, buf.data());
  H5Tclose(type);
  H5Sclose(space);
  H5Dclose(d);
  if (status < 0) throw std::runtime_error("cannot read dataset " + path);
  return out;
}

// FNV-1a (64 bit) of everything a checkpoint holds, in one fixed order:
// the scene text, then every scalar, array and vector by name (sorted),
// each name and sequence preceded by its length in 8 bytes, numbers as
// their 8 bytes (little-endian IEEE). It finds a damaged or edited file;
// it is no protection against a forgery (anyone can recompute it).
// tests/faults/run_fault.py recomputes it in Python.
class Fnv1a {
public:
  void bytes(const void *data, std::size_t n)
  {
    const auto *p = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 1099511628211ull;
  }
  void count(std::uint64_t n) { bytes(&n, sizeof n); }
  void text(const std::string &s) { count(s.size()), bytes(s.data(), s.size()); }
  void numbers(const std::vector<double> &v) { count(v.size()), bytes(v.data(), v.size() * sizeof(double)); }
  std::string hex() const
  {
    char out[17];
    std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h_));
    return out;
  }

private:
  std::uint64_t h_ = 14695981039346656037ull;
};

std::string contentChecksum(const std::string &sceneText, const std::map<std::string, double> &scalars,
                            const std::map<std::string, std::vector<double>> &arrays,
                            const std::map<std::string, std::vector<double>> &vectors)
{
  static_assert(sizeof(double) == 8, "8-byte doubles");
  Fnv1a h;
  h.text(sceneText);
  for (const auto &[n, v] : scalars) h.text(n), h.numbers({v});
  for (const auto &[n, v] : arrays) h.text(n), h.numbers(v);
  for (const auto &[n, v] : vectors) h.text(n), h.numbers(v);
  return h.hex();
}

} // namespace

PetscErrorCode CheckpointWriter::addVector(const std::string &name, Vec v)
{
  PetscFunctionBeginUser;
  PetscCall(gatherToZero(v, vectors_[name]));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointWriter::write(const std::string &path, const std::string &sceneText)
{
  PetscMPIInt rank;
  int ok = 1;
  char message[512] = "";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0) {
    try {
      refuseSpecialFile(path, "checkpoint file");
      const std::string placement = placementPath(path), tmp = placement + ".tmp";
      {
        Hdf5File f(tmp, true);
        f.writeString("/scene_text", sceneText);
        f.writeString("/checksum", contentChecksum(sceneText, scalars_, arrays_, vectors_));
        std::vector<std::string> names;
        std::vector<double> values;
        for (const auto &[n, v] : scalars_) names.push_back(n), values.push_back(v);
        f.writeStrings("/scalar_names", names.empty() ? std::vector<std::string>{"none"} : names);
        if (values.empty()) values.push_back(0.0);
        f.writeArray("/scalar_values", values, {values.size()});
        names.clear();
        for (const auto &[n, v] : arrays_) {
          names.push_back(n);
          std::vector<double> prefixed{static_cast<double>(v.size())};
          prefixed.insert(prefixed.end(), v.begin(), v.end());
          f.writeArray("/arrays/" + n, prefixed, {prefixed.size()});
        }
        f.writeStrings("/array_names", names.empty() ? std::vector<std::string>{"none"} : names);
        names.clear();
        for (const auto &[n, v] : vectors_) {
          names.push_back(n);
          f.writeArray("/vectors/" + n, v, {v.size()});
        }
        f.writeStrings("/vector_names", names.empty() ? std::vector<std::string>{"none"} : names);
        f.close();
      }
      refuseSpecialFile(placement, "checkpoint file"); // checked last before the rename
      if (std::rename(tmp.c_str(), placement.c_str()) != 0)
        throw std::runtime_error("cannot rename " + tmp + " to " + placement);
    } catch (const std::exception &e) {
      ok = 0;
      std::snprintf(message, sizeof message, "%s", e.what());
      const std::string tmp = placementPath(path) + ".tmp";
      if (specialFileKind(tmp).empty()) std::remove(tmp.c_str()); // a half-written checkpoint (a full disk) is not left behind
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm_));
  if (!ok) PetscCallMPI(MPI_Bcast(message, sizeof message, MPI_CHAR, 0, comm_));
  PetscCheck(ok, comm_, PETSC_ERR_FILE_WRITE, "checkpoint %s: %s", path.c_str(), message);
  PetscFunctionReturn(0);
}

// The first value of the checkpoint that is not finite, named ('t = nan'); empty if none.
std::string CheckpointReader::firstNonFinite(const std::vector<std::string> &scalarNames,
                                             const std::vector<double> &scalarValues) const
{
  auto named = [](const std::string &what, double x) { return what + " = " + std::to_string(x); };
  for (std::size_t i = 0; i < scalarNames.size() && i < scalarValues.size(); ++i)
    if (!std::isfinite(scalarValues[i]))
      return "value '" + scalarNames[i] + "' is not finite (" + named(scalarNames[i], scalarValues[i]) + ")";
  for (const auto &[n, v] : arrays_)
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i])) return "array '" + n + "' is not finite at entry " + std::to_string(i);
  for (const auto &[n, v] : vectors_)
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i])) return "vector '" + n + "' is not finite at entry " + std::to_string(i);
  return "";
}

PetscErrorCode CheckpointReader::read(const std::string &path)
{
  PetscMPIInt rank;
  int ok = 1;
  char message[512] = "";
  std::vector<std::string> scalarNames, arrayNames, vectorNames;
  std::vector<double> scalarValues;
  std::string stored; // the checksum written with the contents
  PetscFunctionBeginUser;
  path_ = path;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0) {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    try {
      if (file < 0) throw std::runtime_error("cannot open the file");
      sceneText_ = readStrings(file, "/scene_text").at(0);
      scalarNames = readStrings(file, "/scalar_names");
      scalarValues = readDoubles(file, "/scalar_values");
      arrayNames = readStrings(file, "/array_names");
      vectorNames = readStrings(file, "/vector_names");
      for (const auto &n : arrayNames)
        if (n != "none") {
          const std::vector<double> v = readDoubles(file, "/arrays/" + n);
          arrays_[n].assign(v.begin() + 1, v.begin() + 1 + static_cast<std::size_t>(v.at(0)));
        }
      for (const auto &n : vectorNames)
        if (n != "none") vectors_[n] = readDoubles(file, "/vectors/" + n);
      if (H5Lexists(file, "/checksum", H5P_DEFAULT) > 0) stored = readStrings(file, "/checksum").at(0);
    } catch (const std::exception &e) {
      ok = 0;
      std::snprintf(message, sizeof message, "%s (not a boomdyn checkpoint?)", e.what());
    }
    if (file >= 0) H5Fclose(file);
    // A damaged or edited checkpoint (t = nan) would run on with nonsense.
    if (ok) {
      const std::string bad = firstNonFinite(scalarNames, scalarValues);
      if (!bad.empty()) ok = 0, std::snprintf(message, sizeof message, "%s: the checkpoint is damaged", bad.c_str());
    }
    // A state edited or damaged so that it still satisfies the constraints
    // (a free coordinate moved) would continue silently from it.
    if (ok) {
      std::map<std::string, double> scalars;
      for (std::size_t i = 0; i < scalarNames.size() && i < scalarValues.size(); ++i)
        if (scalarNames[i] != "none") scalars[scalarNames[i]] = scalarValues[i];
      const std::string computed = contentChecksum(sceneText_, scalars, arrays_, vectors_);
      if (stored.empty())
        ok = 0, std::snprintf(message, sizeof message,
                              "it holds no checksum (written by a boomdyn without checkpoint checksums), so its "
                              "contents cannot be verified; start the run again from t = 0");
      else if (computed != stored)
        ok = 0, std::snprintf(message, sizeof message,
                              "its contents do not match the checksum written with them (%s, computed %s): the "
                              "checkpoint was damaged or edited after it was written",
                              stored.c_str(), computed.c_str());
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm_));
  if (!ok) PetscCallMPI(MPI_Bcast(message, sizeof message, MPI_CHAR, 0, comm_));
  PetscCheck(ok, comm_, PETSC_ERR_USER_INPUT, "restart file %s: %s", path.c_str(), message);
  // Broadcast names, scalars, arrays and the scene text.
  auto bcastString = [&](std::string &s) -> PetscErrorCode {
    int n = static_cast<int>(s.size());
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Bcast(&n, 1, MPI_INT, 0, comm_));
    s.resize(n);
    PetscCallMPI(MPI_Bcast(s.data(), n, MPI_CHAR, 0, comm_));
    PetscFunctionReturn(0);
  };
  auto bcastDoubles = [&](std::vector<double> &v) -> PetscErrorCode {
    int n = static_cast<int>(v.size());
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Bcast(&n, 1, MPI_INT, 0, comm_));
    v.resize(n);
    PetscCallMPI(MPI_Bcast(v.data(), n, MPI_DOUBLE, 0, comm_));
    PetscFunctionReturn(0);
  };
  auto bcastNames = [&](std::vector<std::string> &names) -> PetscErrorCode {
    int n = static_cast<int>(names.size());
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Bcast(&n, 1, MPI_INT, 0, comm_));
    names.resize(n);
    for (auto &s : names) PetscCall(bcastString(s));
    PetscFunctionReturn(0);
  };
  PetscCall(bcastString(sceneText_));
  PetscCall(bcastNames(scalarNames));
  PetscCall(bcastDoubles(scalarValues));
  for (std::size_t i = 0; i < scalarNames.size(); ++i)
    if (scalarNames[i] != "none") scalars_[scalarNames[i]] = scalarValues[i];
  PetscCall(bcastNames(arrayNames));
  for (const auto &n : arrayNames)
    if (n != "none") PetscCall(bcastDoubles(arrays_[n]));
  PetscCall(bcastNames(vectorNames));
  for (const auto &n : vectorNames)
    if (n != "none") vectorNames_[n] = 1;
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointReader::getVector(const std::string &name, Vec v) const
{
  PetscMPIInt rank;
  VecScatter sc;
  Vec all;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCheck(hasVector(name), comm_, PETSC_ERR_USER_INPUT, "restart file %s: no vector '%s'", path_.c_str(), name.c_str());
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCall(VecGetSize(v, &n));
  int sizeOk = rank != 0 || static_cast<PetscInt>(vectors_.at(name).size()) == n;
  PetscCallMPI(MPI_Bcast(&sizeOk, 1, MPI_INT, 0, comm_));
  PetscCheck(sizeOk, comm_, PETSC_ERR_USER_INPUT,
             "restart file %s: vector '%s' has another size than this scene's (was the mesh or scene changed?)",
             path_.c_str(), name.c_str());
  PetscCall(VecScatterCreateToZero(v, &sc, &all));
  if (rank == 0) {
    PetscScalar *a;
    PetscCall(VecGetArray(all, &a));
    std::copy(vectors_.at(name).begin(), vectors_.at(name).end(), a);
    PetscCall(VecRestoreArray(all, &a));
  }
  PetscCall(VecScatterBegin(sc, all, v, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(sc, all, v, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscFunctionReturn(0);
}

double CheckpointReader::scalar(const std::string &name) const
{
  const auto it = scalars_.find(name);
  if (it == scalars_.end()) throw std::runtime_error("restart file " + path_ + ": no value '" + name + "'");
  return it->second;
}

const std::vector<double> &CheckpointReader::array(const std::string &name) const
{
  const auto it = arrays_.find(name);
  if (it == arrays_.end()) throw std::runtime_error("restart file " + path_ + ": no array '" + name + "'");
  return it->second;
}

} // namespace boomdyn
