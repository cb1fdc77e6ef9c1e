// Linear spring-damper between a material point a and a material point b of
// another body, or a fixed ground point: tension T = k (l - L0) + c dl/dt
// along the line between them (l = |r_a - r_b|), pulling the points together
// when positive. With L0 = 0 it is the vector spring k (r_a - r_b) + c d/dt
// (r_a - r_b), defined also where the points coincide. Its Jacobian, on ANCF beams and rigid bodies, is computed by
// forward-mode automatic differentiation on the bodies' exact centerline
// derivatives.
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/work_item.hpp"

#include <array>
#include <optional>

namespace boomdyn {

class Spring : public WorkItem {
public:
  ModeEnergyKind modeEnergyKind() const override { return ModeEnergyKind::Spring; } // mode labels
  struct End {
    const Body *body = nullptr; // null: ground point
    double s = 0;
    Vec2 ground = Vec2::Zero();
  };
  Spring(std::string name, End a, End b, double stiffness, double restLength, double damping);
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  bool physicalDamping() const override { return c_ > 0; } // a damper: the damped eigen-analysis

private:
  std::string name_;
  End ends_[2];
  CenterlineLocation loc_[2];
  double k_, L0_, c_;
};

} // namespace boomdyn
