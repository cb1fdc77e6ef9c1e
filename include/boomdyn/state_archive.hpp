// The hand-over of solver state to a checkpoint as plain named data:
// scalars, arrays and distributed vectors. The solvers save and restore
// through these interfaces; the io layer implements them on files
// (CheckpointWriter, CheckpointReader), so no solver depends on io.
#pragma once

#include <petscvec.h>

#include <string>
#include <vector>

namespace boomdyn {

class StateWriter {
public:
  virtual ~StateWriter() = default;
  // Collective: a distributed vector, stored whole.
  virtual PetscErrorCode addVector(const std::string &name, Vec v) = 0;
  // Values known (identically) on every rank.
  virtual void addScalar(const std::string &name, double value) = 0;
  virtual void addArray(const std::string &name, const std::vector<double> &values) = 0;
};

class StateReader {
public:
  virtual ~StateReader() = default;
  // Collective: fills a distributed vector of the stored global size.
  virtual PetscErrorCode getVector(const std::string &name, Vec v) const = 0;
  // Throw std::runtime_error naming the source when the entry is missing.
  virtual double scalar(const std::string &name) const = 0;
  // Whether a scalar is stored (entries newer than some checkpoints).
  virtual bool hasScalar(const std::string &name) const = 0;
  virtual const std::vector<double> &array(const std::string &name) const = 0;
};

} // namespace boomdyn
