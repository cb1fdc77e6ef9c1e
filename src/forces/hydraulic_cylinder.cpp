// The hydraulics of the cylinder and its valve (hydraulic_cylinder.hpp).
#include "boomdyn/hydraulic_cylinder.hpp"

#include <algorithm>
#include <cmath>

namespace boomdyn {

double HydraulicCylinderData::volume(int chamber, double s, double *dVds) const
{
  const double base = deadVolume[chamber] + hoseVolume[chamber];
  if (dVds) *dVds = chamber == 0 ? pistonArea : -rodSideArea;
  return chamber == 0 ? base + pistonArea * s : base + rodSideArea * (strokeLength - s);
}

double HydraulicCylinderData::capacitance(int chamber, double s, double *dCds) const
{
  double dV;
  const double V = volume(chamber, s, &dV), Vh = hoseVolume[chamber];
  const double wall = bulkWall > 0 ? 1.0 / bulkWall : 0.0, hose = bulkHose > 0 ? 1.0 / bulkHose : 0.0;
  if (dCds) *dCds = dV / bulkOil + dV * wall;
  return V / bulkOil + Vh * hose + (V - Vh) * wall;
}

double HydraulicCylinderData::friction(double sdot, double *dFdsdot) const
{
  const double th = coulombVelocity > 0 ? std::tanh(sdot / coulombVelocity) : 0.0;
  *dFdsdot = viscous + (coulombVelocity > 0 ? coulomb * (1 - th * th) / coulombVelocity : 0.0);
  return coulomb * th + viscous * sdot;
}

double HydraulicCylinderData::endStop(double s, double sdot, double *dFds, double *dFdsdot) const
{
  *dFds = *dFdsdot = 0;
  double F = 0;
  for (const double sign : {1.0, -1.0}) { // retracted end: d = -s pushes out; extended end: d = s - L pushes in
    const double d = sign > 0 ? -s : s - strokeLength, dd = sign > 0 ? -sdot : sdot;
    if (!(d > 0)) continue;
    const double ramp = std::min(d / stopDampingDepth, 1.0), dramp = d < stopDampingDepth ? 1.0 / stopDampingDepth : 0.0;
    F += sign * (stopStiffness * d + stopDamping * ramp * dd);
    // d(d)/ds = -sign
    *dFds += sign * (stopStiffness + stopDamping * dramp * dd) * (-sign);
    *dFdsdot += sign * stopDamping * ramp * (-sign);
  }
  return F;
}

double HydraulicCylinderData::stopEnergy(double s) const
{
  const double d = std::max({-s, s - strokeLength, 0.0});
  return 0.5 * stopStiffness * d * d;
}

double ValveData::orifice(double dp, double *slope) const
{
  const double L = laminarPressureDrop, a = std::abs(dp);
  if (a >= L) {
    const double r = std::sqrt(a);
    *slope = 0.5 / r;
    return dp < 0 ? -r : r;
  }
  const double sL = std::sqrt(L), L52 = L * L * sL;
  *slope = 1.25 / sL - 0.75 * dp * dp / L52;
  return 1.25 * dp / sL - 0.25 * dp * dp * dp / L52;
}

void ValveData::flows(double t, double u, const double p[2], double Q[2], double dQdu[2], double dQdp[2][2]) const
{
  Q[0] = Q[1] = dQdu[0] = dQdu[1] = 0;
  dQdp[0][0] = dQdp[0][1] = dQdp[1][0] = dQdp[1][1] = 0;
  if (mode == Mode::Closed) return;
  if (mode == Mode::FlowSource) {
    Q[0] = flow.value(t);
    return;
  }
  const double up = std::max(u, 0.0), um = std::max(-u, 0.0), Cv = flowCoefficient;
  const double dup = u > 0 ? 1.0 : 0.0, dum = u < 0 ? -1.0 : 0.0;
  for (int i = 0; i < 2; ++i) {
    // Chamber i is fed from supply by one sign of u and drained to tank by the other.
    const double feed = i == 0 ? up : um, drain = i == 0 ? um : up;
    const double dfeed = i == 0 ? dup : dum, ddrain = i == 0 ? dum : dup;
    double sIn, sOut;
    const double in = orifice(supplyPressure - p[i], &sIn), out = orifice(p[i] - tankPressure, &sOut);
    Q[i] = Cv * (feed * in - drain * out);
    dQdu[i] = Cv * (dfeed * in - ddrain * out);
    dQdp[i][i] = Cv * (-feed * sIn - drain * sOut);
  }
}

} // namespace boomdyn
