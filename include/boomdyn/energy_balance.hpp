// Energy balance of a dynamic run: with E = kinetic + strain + potential
// (gravity and dead loads) and P_in the power fed in by loads that vary in
// time and by driven constraints, every part of the model either conserves
// or dissipates, so
//
//     E(t) - E(0) <= W_in(t) - W_diss(t)   (up to the scheme's error),
//
// with W_in = integral of P_in dt and W_diss = integral of the power the
// material (Kelvin-Voigt) damping dissipates; with that damping the only
// dissipation and rho_inf = 1 the two sides are equal up to the integration
// error (closure(); dampers of springs and friction enter as an inequality).
// The check itself tests E - E(0) <= W_in, without the W_diss credit: the
// trapezoidal rule on the dissipated power overestimates it in stiff,
// overdamped modes after a step load (see update()).
//
// Generalized-alpha dissipates (rho_inf < 1) or conserves (rho_inf = 1) for
// linear problems, but can gain energy without bound on strongly nonlinear
// ones (a whipping beam at rho_inf near 1, a too-large step on a flexible
// pendulum): every step converges and the results are garbage. The balance
// starts after the first step (whose overshoot from a non-equilibrium start
// is a one-time error of the scheme, large on fine meshes). The check
// ends such a run with a clear message instead. The excess E - E(0) - W_in
// is compared with the energy the motion has involved: the largest kinetic
// plus strain energy so far plus the work exchanged with loads and drives,
// above two floors: the round-off of the energy sums (the strain energy of
// very short elements, reported by the items) and what the trapezoidal rule
// may miss of W_in (half the change of the power over each step times h),
// which dominates while a load rises from nothing and the energies are tiny.
#pragma once

#include "boomdyn/work_item.hpp"

#include <string>

namespace boomdyn {

class EnergyBalance {
public:
  // tolerance: largest excess as a fraction of the energy involved (0: no check).
  explicit EnergyBalance(double tolerance) : tolerance_(tolerance) {}
  // At every accepted step (and once at the start, h = 0). Returns a
  // non-empty message when energy was created beyond the tolerance.
  std::string update(double t, double h, const EnergyParts &e);
  double inputWork() const { return work_; }      // W_in so far [J]
  double dissipatedWork() const { return dissipated_; } // W_diss so far [J]
  double excess() const { return excess_; }        // E - E(0) - W_in [J], checked
  double closure() const { return closure_; }      // E - E(0) - W_in + W_diss [J]
  double involved() const { return activity_ + exchanged_; }

private:
  double tolerance_;
  int steps_ = 0;
  double roundoff_ = 0, quadrature_ = 0;
  double previousImpulseWork_ = 0; // cumulative impulse work at the last update
  double e0_ = 0, previousPower_ = 0, work_ = 0, exchanged_ = 0, activity_ = 0, excess_ = 0;
  double previousDissipation_ = 0, dissipated_ = 0, closure_ = 0;
};

} // namespace boomdyn
