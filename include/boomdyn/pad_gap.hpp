// The signed gap a compliant pad (pad_contact.hpp) acts on: a joint's
// normal offset d of the slider point from the track, with its gradient and
// Hessian over the joint's coordinates. The planar sliding joint gives one
// (along the track normal), the spatial one one per padded section
// direction d2, d3 (SpatialPadGap).
#pragma once

#include <Eigen/Dense>
#include <petscsys.h>

#include <string>
#include <vector>

namespace boomdyn {

class PadGap {
public:
  virtual ~PadGap() = default;
  // The force item's name (the joint's name and the pad).
  virtual std::string padName() const = 0;
  // The coordinates d depends on (the joint's, with the slack coordinate last).
  virtual void coordinates(std::vector<PetscInt> &dofs) const = 0;
  // d, d_q and d_qq over coordinates().
  virtual void normalGap(const double *q, double &d, Eigen::VectorXd &dq, Eigen::MatrixXd &dqq) const = 0;
  // d and d_q only (residuals, outputs, energies).
  virtual void normalGap(const double *q, double &d, Eigen::VectorXd &dq) const = 0;
};

} // namespace boomdyn
