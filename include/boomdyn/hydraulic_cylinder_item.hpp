// A double-acting hydraulic cylinder between a material point a (the
// cylinder's base) and a material point b of another body or a ground point
// (its rod end), as a planar work item: the stroke is s = |r_b - r_a| - l0
// (l0 the pin-to-pin length fully retracted), the axial force F of the
// hydraulics (hydraulic_cylinder.hpp) pushes the points apart along the
// axis. Its unknowns after the ends' coordinates are its first-order
// states: the chamber pressures p1, p2, a stroke memory sigma and, with a
// spool lag, the spool position u.
//
// Why sigma: the continuity rows take the stroke rate as sigma' of the
// first-order scheme (backward Euler, sigma' = (s_n+1 - s_n)/h with sigma =
// s held by its own row), so that over a step the oil volume changes by
// exactly A ds: a closed chamber is then a spring p(s) to the step's
// accuracy in V, not a first-order drift of the generalized-alpha stroke
// rate against the backward-Euler pressure rate.
//
// Rows by context (docs/model.md §2.6):
//   dynamics (cZ > 0):  sigma row  sigma_s (sigma - s(q))
//                       p1 row     -(C1 p1' + A1 sigma' - Q1) / cZ
//                       p2 row     -(C2 p2' - A2 sigma' - Q2) / cZ    (flow source: -C2 (p2 - p_tank))
//                       u row      tau u' + u - u_cmd(t)
//   statics (the `initial: static` start and static analyses): the stroke is
//   held at its initial value s0, the piston pressure is what holds it, the
//   rod pressure keeps its initial value:
//                       sigma_s (sigma - s(q)),  sigma_s (sigma - s0),  -C2 (p2 - p2_0),  u - u_cmd(t)
//   eigen pencil (stiffness pass): closed chambers, -rho1 (C1 dp1 + A1 ds) = 0 and
//   -rho2 (C2 dp2 - A2 ds) = 0 in the scaled unknowns x_pi = dp_i / rho_i,
//   rho_i = A_i / C_i (symmetric with the force's dF/dx_p), sigma and u frozen;
//   the damping pass carries the friction's slope; the valve's flow gain is left out.
//   acceleration level: the states are not unknowns (their rows fix a dummy 0).
// sigma_s is the constraint-row scale (AssemblyContext::sigma).
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/hydraulic_cylinder.hpp"
#include "boomdyn/work_item.hpp"

namespace boomdyn {

class HydraulicCylinderItem : public WorkItem {
public:
  ModeEnergyKind modeEnergyKind() const override { return ModeEnergyKind::Hydraulic; } // mode labels
  struct End {
    const Body *body = nullptr; // null: ground point
    double s = 0;
    Vec2 ground = Vec2::Zero();
  };
  // The indices of the first-order states (spool -1 without a spool lag).
  struct States {
    PetscInt p1 = -1, p2 = -1, stroke = -1, spool = -1;
  };
  // The cylinder's state at (t, q, v) over coordinates() (outputs).
  struct State {
    double stroke = 0, strokeRate = 0, p1 = 0, p2 = 0, spool = 0;
    double force = 0, friction = 0, endStop = 0;
    double Q1 = 0, Q2 = 0;
    double hydraulicPower = 0;   // p1 Q1 + p2 Q2: what the valve delivers into the chambers
    double compressionPower = 0; // p1 C1 p1' + p2 C2 p2': what goes into compressing the oil
    double frictionPower = 0;    // F_fric s' >= 0
  };

  HydraulicCylinderItem(std::string name, End base, End rod, double closedLength, HydraulicCylinderData cylinder,
                        ValveData valve, States states, double initialStroke, double initialRodPressure);
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  bool physicalDamping() const override { return cylinder_.viscous > 0; }

  // The stroke and its rate from the ends' coordinates and velocities.
  void stroke(const double *q, const double *v, double *s, double *sdot) const;
  State state(double t, const double *q, const double *v) const;
  int numEndCoordinates() const { return nEnds_; }
  const HydraulicCylinderData &cylinder() const { return cylinder_; }
  const ValveData &valve() const { return valve_; }

private:
  std::string name_;
  End ends_[2];
  CenterlineLocation loc_[2];
  int nEnds_ = 0;
  double l0_;
  HydraulicCylinderData cylinder_;
  ValveData valve_;
  States states_;
  double s0_, p2Initial_;
};

} // namespace boomdyn
