// Random element states for the finite-difference tests of the ANCF element
// (elastic, damping, reduced axial integration): shared so that every test
// draws its states the same way.
#pragma once

#include "boomdyn/ancf_element.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace boomdyn::ancf::element_states {

// Size of coordinate k: positions scale with the element length, slopes are ~1.
inline double coordinateScale(int k, double l) { return (k % 4) < 2 ? l : 1.0; }

// A straight element at a random place and direction, perturbed by amp (relative).
inline Vec8 deformedState(std::mt19937 &rng, double l, double amp)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double angle = 3.0 * u(rng);
  Vec8 e = straightElement(Vec2(u(rng), u(rng)), Vec2(std::cos(angle), std::sin(angle)), l);
  for (int k = 0; k < 8; ++k) e[k] += amp * u(rng) * coordinateScale(k, l);
  return e;
}

// Random nodal velocities up to speed * the coordinate's size.
inline Vec8 randomVelocity(std::mt19937 &rng, double l, double speed)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec8 v;
  for (int k = 0; k < 8; ++k) v[k] = speed * u(rng) * coordinateScale(k, l);
  return v;
}

inline double relErr(const Eigen::MatrixXd &a, const Eigen::MatrixXd &b) { return (a - b).norm() / b.norm(); }

} // namespace boomdyn::ancf::element_states
