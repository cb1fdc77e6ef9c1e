// Angle drive: the centerline tangent of a body at s points along the
// prescribed direction theta(t):  j(theta) . r'(s) = 0  with
// j = (-sin theta, cos theta). One row, dimensionless (|r'| sin of the angle error).
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/constraint.hpp"
#include "boomdyn/time_function.hpp"

namespace boomdyn {

class AngleDrive : public Constraint {
public:
  AngleDrive(std::string name, const Body &body, double s, TimeFunction theta);
  std::string name() const override { return name_; }
  int numRows() const override { return 1; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override;
  const char *rowUnit(int) const override { return "rad"; }
  void velocityBreakpoints(std::vector<double> &out) const override { theta_.velocityBreakpoints(out); }
  void accelerationBreakpoints(std::vector<double> &out) const override { theta_.accelerationBreakpoints(out); }

private:
  std::string name_;
  const Body *body_;
  double s_;
  CenterlineLocation loc_;
  TimeFunction theta_;
};

} // namespace boomdyn
