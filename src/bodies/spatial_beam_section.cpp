#include "boomdyn/spatial_beam_element.hpp"

#include <algorithm>

namespace boomdyn::spatial_beam {

Section boxSection(double E, double G, double rho, double b, double h, double t)
{
  Section s;
  const double A = 2.0 * t * (b + h);
  const double Iy = t * h * h * (3.0 * b + h) / 6.0, Iz = t * b * b * (3.0 * h + b) / 6.0;
  const double J = 2.0 * t * b * b * h * h / (b + h);
  s.EA = E * A, s.EIy = E * Iy, s.EIz = E * Iz, s.GJ = G * J;
  s.rhoA = rho * A, s.rhoIp = rho * (Iy + Iz);
  return s;
}

double assumedPointwiseWeight(const Section &sec, double l)
{
  if (sec.axialIntegration != AxialIntegration::Assumed) return 1.0;
  const double L = sec.length > 0 ? sec.length : l;
  return std::min(1.0, ancf::kAssumedStabilization * std::min(sec.EIy, sec.EIz) / (sec.EA * L * L));
}

StrainLaw strainLaw(const Section &sec)
{
  return {{sec.EA, sec.GJ, sec.EIy, sec.EIz}, {sec.etaA, sec.etaT, sec.etaB, sec.etaB}};
}

} // namespace boomdyn::spatial_beam
