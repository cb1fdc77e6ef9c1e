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
  // dC/dt at fixed q (right derivative at a drive's breakpoint), so that
  // dC/dt = C_q v + Ct; filled with gamma when v != nullptr. Left empty
  // by constraints that do not depend on t (read as zero).
  Eigen::VectorXd Ct;
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
  // Times at which dC/dt jumps (a drive's velocity kinks), appended to out.
  virtual void velocityBreakpoints(std::vector<double> &out) const { (void)out; }
  // Times at which only d2C/dt2 jumps (a drive's acceleration jumps), appended to out.
  virtual void accelerationBreakpoints(std::vector<double> &out) const { (void)out; }
  // Unit of the rows, for messages ("m", "rad", ...).
  virtual const char *rowUnit(int row) const { (void)row; return "m"; }
  // The kind its stiffness lambda . d2C/dq2 counts as in the mode labels
  // (ConstraintItem::modeEnergyKind): geometric unless it says otherwise.
  virtual ModeEnergyKind modeEnergyKind() const { return ModeEnergyKind::Geometric; }
};

} // namespace boomdyn
