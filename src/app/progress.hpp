// A progress line for long runs: step, simulated time, rate and ETA, at most
// every `interval` seconds of wall time, on rank 0.
#pragma once

#include <petscsys.h>

namespace boomdyn {

class Progress {
public:
  Progress(double tEnd, double interval, bool quiet) : tEnd_(tEnd), interval_(interval), quiet_(quiet) {}
  PetscErrorCode start();
  PetscErrorCode update(PetscInt step, double t, double h, PetscInt iterations, PetscInt rejected);
  double elapsed() const;

private:
  double tEnd_, interval_;
  bool quiet_;
  PetscLogDouble start_ = 0, last_ = 0;
};

} // namespace boomdyn
