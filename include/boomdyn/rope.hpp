// Wire rope over a pulley (docs/model.md §2.2): points P (body 1), Q (pulley,
// body 2) and R (body 3) with a rope of constant length L:
//     C = L - |r_P - r_Q| - |r_Q - r_R| = 0
// It makes the third body extend relative to the second as fast as the second
// relative to the first. The rope's force is T = -lambda (N); an inextensible
// rope stands for an extension/retraction rope pair (rope_type.cpp): T > 0
// is the net pull of the extension rope, T < 0 that of the retraction rope.
// The geometry (l, l_q, l_qq) is RopePath's, shared with the elastic rope.
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/constraint.hpp"
#include "boomdyn/rope_path.hpp"

namespace boomdyn {

class Rope : public Constraint {
public:
  ModeEnergyKind modeEnergyKind() const override { return ModeEnergyKind::Rope; } // mode labels
  using Point = RopePath::Point;
  Rope(std::string name, Point p, Point q, Point r, double length);
  std::string name() const override { return name_; }
  int numRows() const override { return 1; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override;
  bool dependsOnTime() const override { return false; }
  // Length of the rope when the points are at the given coordinates (values in coordinates() order).
  double spannedLength(const double *q) const;
  const RopePath &path() const { return path_; }

private:
  std::string name_;
  RopePath path_;
  double length_;
};

} // namespace boomdyn
