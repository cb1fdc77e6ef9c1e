// One-sided compliant contact of a material point of a body with the
// horizontal ground line y = y_g (docs/model.md §7.4): with the gap
// g = y(q) - y_g and its rate g' = y_q v,
//     F = -k g - c g',   F_n = F if g < 0 and F > 0, else 0,
// pushes the point up (generalized force y_q^T F_n; residual -F_n y_q^T).
// No friction: the ground takes vertical force only. While in contact the
// Jacobian is exact: cQ (k y_q^T y_q + c y_q^T (H_y v)^T - F H_y) + cV c
// y_q^T y_q, H_y the curvature of a rigid body's centerline (zero on ANCF
// beams); in lift-off it adds nothing.
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/work_item.hpp"

namespace boomdyn {

class GroundContact : public WorkItem {
public:
  ModeEnergyKind modeEnergyKind() const override { return ModeEnergyKind::Contact; } // mode labels
  GroundContact(std::string name, const Body &body, double s, double level, double stiffness, double damping);
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  // Strain energy k g^2 / 2 while g < 0; dissipation -F_n g' - (k g)_- g' >= 0.
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;

  struct State {
    double gap = 0, rate = 0; // g, g'
    double force = 0;         // F_n >= 0
    bool contact = false;
  };
  State state(const double *q, const double *v) const;

private:
  std::string name_;
  const Body *body_;
  double s_;
  CenterlineLocation loc_;
  double level_, k_, c_;
};

} // namespace boomdyn
