// Extraction drive: prescribes the slack coordinate of a sliding joint,
//     C = s - s_0 - d(t) = 0,
// i.e. where along the track the slider stands: the relative position of one
// boom in the other. The multiplier is the actuator force along the track (N).
#pragma once

#include "boomdyn/constraint.hpp"
#include "boomdyn/time_function.hpp"

namespace boomdyn {

class SlackDrive : public Constraint {
public:
  SlackDrive(std::string name, PetscInt slackIndex, double s0, TimeFunction displacement)
    : name_(std::move(name)), slack_(slackIndex), s0_(s0), d_(std::move(displacement))
  {
  }
  std::string name() const override { return name_; }
  int numRows() const override { return 1; }
  void coordinates(std::vector<PetscInt> &dofs) const override { dofs.assign(1, slack_); }
  void velocityBreakpoints(std::vector<double> &out) const override { d_.velocityBreakpoints(out); }
  void accelerationBreakpoints(std::vector<double> &out) const override { d_.accelerationBreakpoints(out); }
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override
  {
    out.C.setConstant(1, q[0] - s0_ - d_.value(t));
    out.Cq.setOnes(1, 1);
    if (v) {
      out.gamma.setConstant(1, -d_.accel(t));
      out.Ct.setConstant(1, -d_.rate(t));
    }
    if (w) out.H.setZero(1, 1);
  }

private:
  std::string name_;
  PetscInt slack_;
  double s0_;
  TimeFunction d_;
};

} // namespace boomdyn
