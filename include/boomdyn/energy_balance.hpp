// Energy balance of a dynamic run: with E = kinetic + strain + potential
// (gravity and dead loads) and P_in the power fed in by loads that vary in
// time and by driven constraints,
//
//     E(t) - E(0) = W_in(t) - W_diss(t)   (up to the scheme's error),
//
// with W_in = integral of P_in dt and W_diss the work of the damping forces
// of the items with physical damping (Kelvin-Voigt sections), summed step by
// step as the discrete forces do it on the discrete motion (EnergyCheck);
// friction and the scheme's own dissipation (rho_inf < 1) make the left
// side smaller. The check tests the excess E - E(0) - W_in + W_diss: with
// rho_inf = 1 and linear damping it is round-off; energy created beyond it
// comes from the conservative parts of the step.
//
// Generalized-alpha dissipates (rho_inf < 1) or conserves (rho_inf = 1) for
// linear problems, but can gain energy without bound on strongly nonlinear
// ones (a whipping beam at rho_inf near 1, a too-large step on a flexible
// pendulum): every step converges and the results are garbage. The balance
// starts after the first step (whose overshoot from a non-equilibrium start
// is a one-time error of the scheme, large on fine meshes). The check
// ends such a run with a clear message instead. The excess
// is compared with the energy the motion has involved: the largest kinetic
// plus strain energy so far plus the work exchanged with loads and drives,
// above two floors: the round-off of the energy sums (the strain energy of
// very short elements, reported by the items) and what the trapezoidal rule
// may miss of W_in (half the change of the power over each step times h),
// which dominates while a load rises from nothing and the energies are tiny;
// and one absolute floor, 1e-12 of the model's own energy scale
// M (|g| L + (L/T)^2) (Model::energyScale): without it a model whose
// energies are all zero (a block at rest at height 0) would be stopped for
// an excess of 1e-34 J, 1e31 times the nothing it involves.
#pragma once

#include "boomdyn/work_item.hpp"

#include <string>

namespace boomdyn {

class EnergyBalance {
public:
  // tolerance: largest excess as a fraction of the energy involved (0: no check).
  // energyScale: the model's own energy (Model::energyScale) [J]; 1e-12 of
  // it is an absolute floor of the excess (round-off of energies that are
  // all zero, a block at rest at height 0, is no instability).
  explicit EnergyBalance(double tolerance, double energyScale = 0.0)
    : tolerance_(tolerance), absoluteFloor_(kAbsoluteFloor * energyScale)
  {
  }
  static constexpr double kAbsoluteFloor = 1e-12;
  // At every accepted step (and once at the start, h = 0). Returns a
  // non-empty message when energy was created beyond the tolerance.
  // dampingWork: W_diss of the step that reached t (0 at the start).
  std::string update(double t, double h, const EnergyParts &e, double dampingWork = 0.0);
  double inputWork() const { return work_; }      // W_in so far [J]
  double dissipatedWork() const { return dissipated_; } // W_diss so far [J]
  double excess() const { return excess_; }        // E - E(0) - W_in + W_diss [J], checked
  // Largest kinetic + strain energy, plus the work exchanged with loads,
  // drives and the damping [J].
  double involved() const { return activity_ + exchanged_ + damped_; }

private:
  double tolerance_, absoluteFloor_;
  int steps_ = 0;
  double roundoff_ = 0, quadrature_ = 0;
  double previousImpulseWork_ = 0; // cumulative impulse work at the last update
  double e0_ = 0, previousPower_ = 0, work_ = 0, exchanged_ = 0, activity_ = 0, excess_ = 0;
  double dissipated_ = 0, damped_ = 0;
};

} // namespace boomdyn
