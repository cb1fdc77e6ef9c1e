// Pin: a material point of body a coincides with a fixed ground point
// (2 rows: r_a(s_a) - p = 0) or with a material point of body b
// (r_a(s_a) - r_b(s_b) = 0).
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/constraint.hpp"

namespace boomdyn {

class Pin : public Constraint {
public:
  Pin(std::string name, const Body &a, double sa, Vec2 ground);
  Pin(std::string name, const Body &a, double sa, const Body &b, double sb);
  std::string name() const override { return name_; }
  int numRows() const override { return 2; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override;
  bool dependsOnTime() const override { return false; }

private:
  std::string name_;
  const Body *a_, *b_ = nullptr;
  double sa_, sb_ = 0;
  CenterlineLocation la_, lb_;
  Vec2 ground_ = Vec2::Zero();
};

} // namespace boomdyn
