#include "boomdyn/monitors.hpp"

namespace boomdyn {

PetscErrorCode ProgressLine::start(const RunState &, bool)
{
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&start_));
  last_ = start_;
  PetscFunctionReturn(0);
}

PetscErrorCode ProgressLine::afterStep(const RunState &s, std::string *)
{
  PetscLogDouble now;
  PetscFunctionBeginUser;
  if (!s.dynamic) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "load factor %.4f: %" PetscInt_FMT " Newton iterations\n", s.t,
                          s.iterations));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscTime(&now));
  const bool last = s.t >= tEnd_ * (1 - 1e-12);
  if (now - last_ < interval_ && !last) PetscFunctionReturn(0);
  last_ = now;
  const double wall = now - start_;
  const double rate = wall > 0 ? s.t / wall : 0; // simulated seconds per wall second
  const double eta = rate > 0 ? (tEnd_ - s.t) / rate : 0;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "step %6" PetscInt_FMT "  t = %9.5f / %g s  dt = %.3g  newton %2" PetscInt_FMT
                        "  rejected %" PetscInt_FMT "  %.0f steps/s  ETA %.1f s\n",
                        s.step, s.t, tEnd_, s.h, s.iterations, s.rejected, wall > 0 ? s.step / wall : 0.0, eta));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
