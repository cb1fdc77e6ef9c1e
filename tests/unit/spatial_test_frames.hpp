// Small fixtures shared by the spatial kernel, sliding-joint and pad unit
// tests: body axes from an axis and an up direction (as a scene's `axis` and
// `up` give them) and a unit-scale beam section with EI_y != EI_z.
#pragma once

#include "boomdyn/spatial_beam_element.hpp"

namespace boomdyn::spatial_test {

// x along `x`, y the part of `up` normal to it, z = x cross y.
inline Eigen::Matrix3d axesOf(const Eigen::Vector3d &x, const Eigen::Vector3d &up)
{
  Eigen::Matrix3d R;
  R.col(0) = x.normalized();
  R.col(1) = (up - up.dot(R.col(0)) * R.col(0)).normalized();
  R.col(2) = R.col(0).cross(R.col(1));
  return R;
}

inline spatial_beam::Section unitSection()
{
  spatial_beam::Section s;
  s.EA = 100, s.EIy = 1, s.EIz = 2, s.GJ = 0.5, s.rhoA = 1, s.rhoIp = 0.01;
  return s;
}

} // namespace boomdyn::spatial_test
