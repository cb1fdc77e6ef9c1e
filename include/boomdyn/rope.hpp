// Wire rope over a pulley (docs/model.md §2.2): points P (body 1), Q (pulley,
// body 2) and R (body 3) with a rope of constant length L:
//     C = L - |r_P - r_Q| - |r_Q - r_R| = 0
// It makes the third body extend relative to the second as fast as the second
// relative to the first. The multiplier is the rope tension in N: a negative
// value means the rope would have to push (slack rope) and is flagged.
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/constraint.hpp"

namespace boomdyn {

class Rope : public Constraint {
public:
  struct Point {
    const Body *body;
    double s;
  };
  Rope(std::string name, Point p, Point q, Point r, double length);
  std::string name() const override { return name_; }
  int numRows() const override { return 1; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override;
  bool dependsOnTime() const override { return false; }
  // Length of the rope when the points are at the given coordinates (values in coordinates() order).
  double spannedLength(const double *q) const;

private:
  std::string name_;
  Point pts_[3];
  CenterlineLocation loc_[3];
  double length_;
};

} // namespace boomdyn
