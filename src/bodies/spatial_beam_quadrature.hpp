// Quadrature of the spatial beam element (docs/model.md §1.7): the 5- and
// 3-point Gauss-Legendre rules on [0, 1] and the Legendre basis of the
// assumed axial strain. Shared by the jet kernels (spatial_beam_element.cpp)
// and the hand-structured ones (spatial_beam_forces.cpp); not a public header.
#pragma once

#include "boomdyn/spatial_beam_element.hpp"

#include <cmath>

namespace boomdyn::spatial_beam::detail {

// n-point Gauss-Legendre rule (n = 3 or 5) on [0, 1].
struct GaussRule {
  int n;
  double xi[kGaussPoints], w[kGaussPoints];
};

inline GaussRule gaussRule01(int n)
{
  GaussRule r{n, {}, {}};
  if (n == 3) {
    const double a = std::sqrt(0.6);
    const double x[3] = {-a, 0.0, a}, wt[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    for (int i = 0; i < 3; ++i) r.xi[i] = 0.5 * (x[i] + 1.0), r.w[i] = 0.5 * wt[i];
    return r;
  }
  const double a = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  const double b = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  const double wa = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0, wb = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
  const double x[5] = {-b, -a, 0.0, a, b}, wt[5] = {wb, wa, 128.0 / 225.0, wa, wb};
  for (int i = 0; i < 5; ++i) r.xi[i] = 0.5 * (x[i] + 1.0), r.w[i] = 0.5 * wt[i];
  return r;
}

inline const GaussRule &rule5()
{
  static const GaussRule r = gaussRule01(kGaussPoints);
  return r;
}
inline const GaussRule &rule3()
{
  static const GaussRule r = gaussRule01(kReducedAxialPoints);
  return r;
}

// Orthonormal Legendre polynomials on [0, 1] of degree 0 and 1: the basis of
// the assumed axial strain (as in the planar element).
inline double legendre01(int j, double xi) { return j == 0 ? 1.0 : std::sqrt(3.0) * (2.0 * xi - 1.0); }

} // namespace boomdyn::spatial_beam::detail
