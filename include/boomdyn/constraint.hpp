// A holonomic constraint C(q, t) = 0 as a pure kernel: rows, Jacobian,
// multiplier-weighted Hessian and the acceleration-level term. The generic
// ConstraintItem (model/constraint_item) turns it into a WorkItem.
#pragma once

#include "boomdyn/work_item.hpp"

#include <Eigen/Dense>

namespace boomdyn {

struct ConstraintEval {
  Eigen::VectorXd C;     // rows
  Eigen::MatrixXd Cq;    // rows x coords
  Eigen::VectorXd gamma; // (C_q v)_q v + 2 C_qt v + C_tt  (so that d2C/dt2 = C_q a + gamma)
  Eigen::MatrixXd H;     // sum_i w_i d2C_i/dq2 (coords x coords)
};

class Constraint {
public:
  virtual ~Constraint() = default;
  virtual std::string name() const = 0;
  virtual int numRows() const = 0;
  virtual void coordinates(std::vector<PetscInt> &dofs) const = 0;
  // Fill C and Cq always; gamma when v != nullptr; H when w != nullptr (weights per row).
  virtual void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const = 0;
  // False when C does not depend on t explicitly (C_t = 0): such constraints
  // do no work, and the energy balance skips them.
  virtual bool dependsOnTime() const { return true; }
  // Unit of the rows, for messages ("m", "rad", ...).
  virtual const char *rowUnit(int row) const { (void)row; return "m"; }
};

} // namespace boomdyn
