// The hydraulics of a double-acting cylinder and its 4/3 proportional valve
// (docs/model.md §2.6), independent of how the cylinder is mounted: every law
// is a function of the stroke s, its rate, the chamber pressures p1 (piston
// side) and p2 (rod side), the spool position u and the time, with its
// partial derivatives for Newton. The planar force element
// (hydraulic_cylinder_item.hpp) adds the geometry (s from two material
// points); a spatial crane reuses this file unchanged.
//
//   chamber volumes   V1 = V1dead + V1hose + A1 s,  V2 = V2dead + V2hose + A2 (L - s)
//   capacitances      C_i = V_i / beta_i = V_i / B_oil + V_i,hose / B_hose + (V_i - V_i,hose) / B_wall
//                     (oil, hose and cylinder wall in series, each weighted by its volume fraction)
//   continuity        C1 p1' = Q1 - A1 s',   C2 p2' = Q2 + A2 s'
//   valve (u >= 0: P->A, B->T; u < 0: P->B, A->T)
//                     Q1 = Cv (u+ f(ps - p1) - u- f(p1 - pt)),  Q2 = Cv (u- f(ps - p2) - u+ f(p2 - pt))
//   orifice           f(dp) = sign(dp) sqrt(|dp|) above the laminar limit dp_lam, below it the odd
//                     cubic (5/4) dp / sqrt(dp_lam) - dp^3 / (4 dp_lam^(5/2)), equal in value and slope
//                     at dp_lam (C1) and linear (laminar) at small drops
//   axial force       F = p1 A1 - p2 A2 - F_fric(s') + F_stop(s, s')   (positive: extends)
//   friction          F_fric = F_c tanh(s' / v_c) + c s'
//   end stops         penetration d = -s (retracted) or s - L (extended): k d + c min(d / d_c, 1) d'
//                     pushing back; the damping grows over the depth d_c so the force starts at 0
#pragma once

#include "boomdyn/time_function.hpp"

#include <algorithm>
#include <cmath>

namespace boomdyn {

struct HydraulicCylinderData {
  double pistonArea = 0;   // A1, m^2
  double rodSideArea = 0;  // A2 = A1 - rod area, m^2
  double strokeLength = 0; // L, m
  double deadVolume[2] = {0, 0}, hoseVolume[2] = {0, 0}; // piston, rod side, m^3
  double bulkOil = 1.5e9;  // Pa
  double bulkHose = 0;     // Pa; 0: rigid hoses
  double bulkWall = 0;     // Pa; 0: rigid cylinder wall
  double coulomb = 0;              // F_c, N
  double coulombVelocity = 1e-3;   // v_c of the tanh, m/s
  double viscous = 0;              // c, N s/m
  double stopStiffness = 1e8;      // N/m
  double stopDamping = 0;          // N s/m
  double stopDampingDepth = 1e-3;  // d_c, m

  double area(int chamber) const { return chamber == 0 ? pistonArea : rodSideArea; }
  // Chamber volume and its stroke derivative.
  double volume(int chamber, double s, double *dVds = nullptr) const;
  // Hydraulic capacitance C = V / beta_eff (m^3/Pa) and its stroke derivative.
  double capacitance(int chamber, double s, double *dCds = nullptr) const;
  double effectiveBulkModulus(int chamber, double s) const { return volume(chamber, s) / capacitance(chamber, s); }

  double friction(double sdot, double *dFdsdot) const;
  // The end stops' force (extending positive), its spring part alone
  // (potential ½ k d^2 via stopEnergy) and the partials.
  double endStop(double s, double sdot, double *dFds, double *dFdsdot) const;
  double stopEnergy(double s) const;
};

struct ValveData {
  enum class Mode { Proportional, Closed, FlowSource };
  Mode mode = Mode::Closed;
  TimeFunction command;            // Proportional: spool position (command) in [-1, 1]
  double spoolTimeConstant = 0;    // s; 0: the spool is at its command
  double flowCoefficient = 0;      // Cv of one metering edge fully open, m^3/s/sqrt(Pa)
  double laminarPressureDrop = 2e5; // dp_lam, Pa
  double supplyPressure = 0, tankPressure = 0; // Pa
  TimeFunction flow;               // FlowSource: flow into the piston chamber, m^3/s

  // f(dp) of the orifice law (sqrt(Pa)) and its slope.
  double orifice(double dp, double *slope) const;
  // Flows into the chambers at spool u, time t and pressures p = {p1, p2},
  // with dQ_i/du and dQ_i/dp_j. The rod chamber of a flow source is held at
  // the tank pressure by its own row (no flow law).
  void flows(double t, double u, const double p[2], double Q[2], double dQdu[2], double dQdp[2][2]) const;
  // The spool's target at t (its command; 0 for the other modes).
  double spoolCommand(double t) const { return mode == Mode::Proportional ? command.value(t) : 0.0; }
};

} // namespace boomdyn
