// Checkpoint files: everything a dynamic run needs to continue exactly where
// it was (integrator vectors, step control, tracking and stick/slip state,
// output schedule). An HDF5 file written by rank 0 from gathered vectors;
// written to a temporary name and renamed, so a checkpoint on disk is always
// complete. Restarting from it reproduces the uninterrupted run bitwise on
// one rank (same operations on the same numbers).
#pragma once

#include "boomdyn/state_archive.hpp"

#include <petscvec.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace boomdyn {

class CheckpointWriter : public StateWriter {
public:
  explicit CheckpointWriter(MPI_Comm comm) : comm_(comm) {}
  // Collective: a distributed vector, stored whole.
  PetscErrorCode addVector(const std::string &name, Vec v) override;
  // Values known on every rank (identical) or on rank 0 only (rank0Only).
  void addScalar(const std::string &name, double value) override { scalars_[name] = value; }
  void addArray(const std::string &name, const std::vector<double> &values) override { arrays_[name] = values; }
  // Collective: writes path (via path + ".tmp" and a rename).
  PetscErrorCode write(const std::string &path, const std::string &sceneText);

private:
  MPI_Comm comm_;
  std::map<std::string, double> scalars_;
  std::map<std::string, std::vector<double>> arrays_;
  std::map<std::string, std::vector<double>> vectors_; // gathered on rank 0
};

class CheckpointReader : public StateReader {
public:
  explicit CheckpointReader(MPI_Comm comm) : comm_(comm) {}
  // Collective: reads the file on rank 0 and broadcasts scalars and arrays.
  // A file that cannot be read is a user error (PETSC_ERR_USER_INPUT) naming it.
  PetscErrorCode read(const std::string &path);
  // Collective: fills a distributed vector of the right global size.
  PetscErrorCode getVector(const std::string &name, Vec v) const override;
  bool hasVector(const std::string &name) const { return vectorNames_.count(name) > 0; }
  // Throw std::runtime_error naming the file when the value is missing
  // (callers restore inside PetscCallCXX: Simulation::runDynamic).
  double scalar(const std::string &name) const override;
  const std::vector<double> &array(const std::string &name) const override;
  const std::string &sceneText() const { return sceneText_; }
  bool hasScalar(const std::string &name) const override { return scalars_.count(name) > 0; }

private:
  std::string firstNonFinite(const std::vector<std::string> &scalarNames,
                             const std::vector<double> &scalarValues) const;

  MPI_Comm comm_;
  std::string path_, sceneText_;
  std::map<std::string, double> scalars_;
  std::map<std::string, std::vector<double>> arrays_;
  std::map<std::string, std::vector<double>> vectors_; // rank 0 only
  std::map<std::string, int> vectorNames_;
};

} // namespace boomdyn
