#include "boomdyn/monitors.hpp"

namespace boomdyn {

EnergyCheck::EnergyCheck(double tolerance, Assembler &assembler)
  : balance_(tolerance, assembler.model().energyScale()), assembler_(assembler), damped_(assembler.model().hasPhysicalDamping())
{
}

PetscErrorCode EnergyCheck::remember(const RunState &s)
{
  PetscFunctionBeginUser;
  if (!qPrevious_) {
    PetscCall(assembler_.createVector(qPrevious_.address()));
    PetscCall(assembler_.createVector(dq_.address()));
  }
  PetscCall(VecCopy(s.q, qPrevious_));
  PetscFunctionReturn(0);
}

PetscErrorCode EnergyCheck::start(const RunState &s, bool)
{
  PetscFunctionBeginUser;
  if (!s.dynamic) PetscFunctionReturn(0);
  (void)balance_.update(s.t, 0.0, s.energy, 0.0);
  if (damped_) {
    PetscCall(remember(s));
    if (s.dampingForces) forcesPrevious_ = *s.dampingForces;
    else PetscCall(assembler_.dampingForces(s.q, s.v, &forcesPrevious_));
  }
  PetscFunctionReturn(0);
}

// The damping work of a step is dq . (Q_d(q_n, v_n) + Q_d(q_n+1, v_n+1)) / 2
// with the step's own increment dq = q_n+1 - q_n: the work the discrete
// damping forces do on the discrete motion. For rho_inf = 1 (trapezoidal
// velocities, dq = h (v_n + v_n+1) / 2) that is exactly what the scheme
// removes from E for a linear damping, so the balance closes to round-off;
// the trapezoidal rule on the dissipated power v . Q_d does not, and is
// wrong by orders of magnitude in the stiff modes that the damping makes
// overdamped (omega h >> 1). With rho_inf < 1 the discrete work can be
// negative in those modes right after a step load: generalized-alpha feeds
// them energy through the damping force for a few steps (docs/model.md,
// "energy balance with damping").
PetscErrorCode EnergyCheck::afterStep(const RunState &s, std::string *failure)
{
  PetscFunctionBeginUser;
  if (!s.dynamic) PetscFunctionReturn(0);
  double work = 0;
  if (damped_) {
    PetscReal w[2]; // before, after
    PetscCall(VecWAXPY(dq_, -1.0, qPrevious_, s.q));
    // The forces at the new state from the diagnostics pass when it computed
    // them (the same item values, the same numbers), else a pass of their own.
    if (s.dampingForces) forces_ = *s.dampingForces;
    else PetscCall(assembler_.dampingForces(s.q, s.v, &forces_));
    const Assembler::DampingForces *const both[2] = {&forcesPrevious_, &forces_};
    PetscCall(assembler_.dampingWork(both, 2, dq_, w)); // one pass for both
    work = 0.5 * (w[0] + w[1]);
    std::swap(forcesPrevious_, forces_);
    PetscCall(remember(s));
  }
  *failure = balance_.update(s.t, s.h, s.energy, work);
  PetscFunctionReturn(0);
}

} // namespace boomdyn
