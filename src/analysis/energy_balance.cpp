#include "boomdyn/energy_balance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace boomdyn {

std::string EnergyBalance::update(double t, double h, const EnergyParts &e, double dampingWork)
{
  const double total = e.kinetic + e.strain + e.potential;
  activity_ = std::max(activity_, e.kinetic + std::abs(e.strain));
  // The balance starts after the first step: from a state that is not in
  // equilibrium (loads and gravity switched on at t = 0) generalized-alpha
  // started from the consistent accelerations (-boom_filtered_start 0)
  // overshoots once in the modes with omega h >> 1, which fine meshes have
  // many of; that one-time error is not the growth this check is for. (The
  // filtered start keeps it at the modes' static energy, docs/model.md §4.3.)
  if (steps_++ < 2) { // the start (h = 0) and the first step
    e0_ = total;
    previousPower_ = e.inputPower;
    previousImpulseWork_ = e.impulseWork;
    return {};
  }
  // The drives' impulses at velocity kinks (kink restart): their work, exactly.
  work_ += e.impulseWork - previousImpulseWork_;
  exchanged_ += std::abs(e.impulseWork - previousImpulseWork_);
  previousImpulseWork_ = e.impulseWork;
  // Trapezoidal rule over the step: second order, like the integrator. At
  // its end the power of the step's own segment of the loads' and winches'
  // rates (the left limit, where a rate jumps at a breakpoint): a haul
  // that ends on the step's end did its work inside the step.
  const double powerAtEnd = e.inputPower + e.inputPowerJump;
  work_ += 0.5 * (previousPower_ + powerAtEnd) * h;
  // What the trapezoidal rule may miss over the step (its distance from
  // either rectangle rule): large while a load ramps up from nothing,
  // negligible against the work later.
  quadrature_ += 0.5 * std::abs(powerAtEnd - previousPower_) * h;
  exchanged_ += 0.5 * (std::abs(previousPower_) + std::abs(powerAtEnd)) * h;
  previousPower_ = e.inputPower;
  // The damping work of the step as the discrete forces did it on the
  // discrete motion (EnergyCheck::afterStep), not a quadrature of the
  // dissipated power: energy the scheme feeds into overdamped modes through
  // the damping force (negative step work) is accounted where it arises, so
  // the check keeps testing what the conservative parts of the step create.
  dissipated_ += dampingWork;
  damped_ += std::abs(dampingWork);
  excess_ = total - e0_ - work_ + dissipated_;
  // Round-off of the sums (the potential may carry a large constant) and of
  // the strain energy of short elements (at both ends of the comparison),
  // with a margin: on a 10^5-element boom whose load has just started, the
  // energies themselves are at that level.
  roundoff_ = std::max(roundoff_, e.roundoff);
  const double floor = 1e-9 * (std::abs(total) + std::abs(e0_)) + 10.0 * roundoff_ + quadrature_ + absoluteFloor_;
  if (tolerance_ <= 0 || excess_ <= tolerance_ * involved() + floor) return {};
  char text[768];
  std::snprintf(text, sizeof text,
                "energy balance violated at t = %g s: the total energy grew by %.4g J more than the work of loads and "
                "drives (%.4g J) less the damping work (%.4g J), %.3g times the energy the motion involves (%.4g J; "
                "tolerance %g). The integration is unstable here (generalized-alpha on a strongly nonlinear motion, "
                "or a step too large for it): use a smaller rho_inf (<= 0.9) or a smaller dt "
                "(-boom_energy_tolerance 0 turns this check off)",
                t, excess_, work_, dissipated_, excess_ / std::max(involved(), 1e-300), involved(), tolerance_);
  return text;
}

} // namespace boomdyn
