// Helpers shared by the stiff and extreme cases (tests/extreme, issue 6
// item 3): scene variants, energy balances with the work of loads and
// drives, and "every number is finite" checks. A case passes when its run
// either stays within the stated bounds or stops with a clear message.
#pragma once

#include "support.hpp"

#include <cmath>
#include <string>

namespace boomdyn::testing {

inline int rank()
{
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

inline Scene inputScene(const std::string &name)
{
  return readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/" + name);
}

// Every recorded number of the run is finite (no silent NaN or Inf).
inline bool allFinite(const DynamicHistory &h)
{
  auto finite = [](double v) { return std::isfinite(v); };
  for (std::size_t k = 0; k < h.time.size(); ++k) {
    if (!finite(h.energy[k]) || !finite(h.violation[k])) return false;
    for (double v : h.multipliers[k])
      if (!finite(v)) return false;
    for (double v : h.slacks[k])
      if (!finite(v)) return false;
    for (const SensorReading &r : h.sensors[k])
      if (!r.position.allFinite() || !r.velocity.allFinite()) return false;
  }
  return true;
}

inline double maxOf(const std::vector<double> &v)
{
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Energy balance: E(t) - E(0) - W_drive per step, where E (kinetic + strain
// + potential of gravity and of the dead point forces) is what the
// integrator reports and W_drive the work of one extraction drive
// (multiplier row `driveRow`, slack of joint `joint`; none if driveRow < 0).
// Generalized-alpha with rho_inf < 1 only dissipates, so the residual must
// stay <= 0 up to round-off; rho_inf = 1 keeps it near 0.
inline std::vector<double> energyResidual(const DynamicHistory &h, int driveRow = -1, int joint = -1)
{
  std::vector<double> r(h.time.size(), 0.0);
  double drive = 0;
  for (std::size_t k = 0; k < h.time.size(); ++k) {
    if (k > 0 && driveRow >= 0)
      drive -= 0.5 * (h.multipliers[k][driveRow] + h.multipliers[k - 1][driveRow]) * (h.slacks[k][joint] - h.slacks[k - 1][joint]);
    r[k] = h.energy[k] - h.energy[0] - drive;
  }
  return r;
}

inline double maxNegative(const std::vector<double> &v)
{
  double m = 0;
  for (double x : v) m = std::max(m, -x);
  return m;
}

inline double maxPositive(const std::vector<double> &v)
{
  double m = 0;
  for (double x : v) m = std::max(m, x);
  return m;
}

} // namespace boomdyn::testing
