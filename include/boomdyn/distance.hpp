// Distance: a material point of body a keeps the distance L from a fixed
// ground point, |r_a(s_a) - p| = L, or from a material point of body b,
// |r_a(s_a) - r_b(s_b)| = L (one row, C = |d| - L: a massless rigid link
// with pin joints at both ends). The points must not coincide.
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/constraint.hpp"

namespace boomdyn {

class Distance : public Constraint {
public:
  Distance(std::string name, const Body &a, double sa, Vec2 ground, double length);
  Distance(std::string name, const Body &a, double sa, const Body &b, double sb, double length);
  std::string name() const override { return name_; }
  int numRows() const override { return 1; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override;
  bool dependsOnTime() const override { return false; }
  // |d| at the values of coordinates() (for the default length).
  double distance(const double *q) const;

private:
  std::string name_;
  const Body *a_, *b_ = nullptr;
  double sa_, sb_ = 0, length_;
  CenterlineLocation la_, lb_;
  Vec2 ground_ = Vec2::Zero();
};

} // namespace boomdyn
