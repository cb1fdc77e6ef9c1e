#include "progress.hpp"

namespace boomdyn {

PetscErrorCode Progress::start()
{
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&start_));
  last_ = start_;
  PetscFunctionReturn(0);
}

double Progress::elapsed() const
{
  PetscLogDouble now;
  (void)PetscTime(&now);
  return now - start_;
}

PetscErrorCode Progress::update(PetscInt step, double t, double h, PetscInt iterations, PetscInt rejected)
{
  PetscLogDouble now;
  PetscFunctionBeginUser;
  if (quiet_) PetscFunctionReturn(0);
  PetscCall(PetscTime(&now));
  const bool last = t >= tEnd_ * (1 - 1e-12);
  if (now - last_ < interval_ && !last) PetscFunctionReturn(0);
  last_ = now;
  const double wall = now - start_;
  const double rate = wall > 0 ? t / wall : 0; // simulated seconds per wall second
  const double eta = rate > 0 ? (tEnd_ - t) / rate : 0;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "step %6" PetscInt_FMT "  t = %9.5f / %g s  dt = %.3g  newton %2" PetscInt_FMT
                        "  rejected %" PetscInt_FMT "  %.0f steps/s  ETA %.1f s\n",
                        step, t, tEnd_, h, iterations, rejected, wall > 0 ? step / wall : 0.0, eta));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
