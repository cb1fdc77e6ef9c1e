#include "boomdyn/hydraulic_cylinder_item.hpp"

#include "boomdyn/schema.hpp"

#include <unsupported/Eigen/AutoDiff>

#include <array>
#include <cmath>

namespace boomdyn {

namespace {
// Derivatives over the item's unknowns: two 8-coordinate ends and four
// states, on the stack (as LuGre friction does).
constexpr int kMaxUnknowns = 20;
using Derivatives = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxUnknowns, 1>;
using AD = Eigen::AutoDiffScalar<Derivatives>;
} // namespace

HydraulicCylinderItem::HydraulicCylinderItem(std::string name, End base, End rod, double closedLength,
                                             HydraulicCylinderData cylinder, ValveData valve, States states,
                                             double initialStroke, double initialRodPressure)
  : name_(std::move(name)), ends_{base, rod}, l0_(closedLength), cylinder_(cylinder), valve_(std::move(valve)),
    states_(states), s0_(initialStroke), p2Initial_(initialRodPressure)
{
  for (int e = 0; e < 2; ++e)
    if (ends_[e].body) loc_[e] = ends_[e].body->locate(ends_[e].s), nEnds_ += loc_[e].count;
}

void HydraulicCylinderItem::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.clear();
  for (int e = 0; e < 2; ++e)
    if (ends_[e].body) dofs.insert(dofs.end(), loc_[e].dofs.begin(), loc_[e].dofs.begin() + loc_[e].count);
  dofs.push_back(states_.p1);
  dofs.push_back(states_.p2);
  dofs.push_back(states_.stroke);
  if (states_.spool >= 0) dofs.push_back(states_.spool);
}

void HydraulicCylinderItem::stroke(const double *q, const double *v, double *s, double *sdot) const
{
  Vec2 r[2], w[2];
  int offset = 0;
  for (int e = 0; e < 2; ++e) {
    r[e] = ends_[e].ground, w[e] = Vec2::Zero();
    if (!ends_[e].body) continue;
    CenterlineSample p;
    ends_[e].body->sample(loc_[e], ends_[e].s, q + offset, p);
    r[e] = p.r[0];
    if (v)
      for (int m = 0; m < loc_[e].count; ++m) w[e] += p.r_q[0].col(m) * v[offset + m];
    offset += loc_[e].count;
  }
  const Vec2 d = r[1] - r[0];
  const double l = d.norm();
  *s = l - l0_;
  if (sdot) *sdot = d.dot(w[1] - w[0]) / l;
}

HydraulicCylinderItem::State HydraulicCylinderItem::state(double t, const double *q, const double *v) const
{
  State st;
  stroke(q, v, &st.stroke, &st.strokeRate);
  const int n = nEnds_;
  const double p[2] = {q[n], q[n + 1]}, pdot[2] = {v[n], v[n + 1]};
  st.p1 = p[0], st.p2 = p[1];
  st.spool = states_.spool >= 0 ? q[n + 3] : valve_.spoolCommand(t);
  double dF, dFs, dFv, dQdu[2], dQdp[2][2], Q[2];
  st.friction = cylinder_.friction(st.strokeRate, &dF);
  st.endStop = cylinder_.endStop(st.stroke, st.strokeRate, &dFs, &dFv);
  st.force = p[0] * cylinder_.pistonArea - p[1] * cylinder_.rodSideArea - st.friction + st.endStop;
  valve_.flows(t, st.spool, p, Q, dQdu, dQdp);
  if (valve_.mode == ValveData::Mode::FlowSource) // the rod chamber: what its continuity row implies (open to tank)
    Q[1] = cylinder_.capacitance(1, q[n + 2]) * pdot[1] - cylinder_.rodSideArea * v[n + 2];
  st.Q1 = Q[0], st.Q2 = Q[1];
  st.hydraulicPower = p[0] * Q[0] + p[1] * Q[1];
  st.compressionPower =
      p[0] * cylinder_.capacitance(0, q[n + 2]) * pdot[0] + p[1] * cylinder_.capacitance(1, q[n + 2]) * pdot[1];
  st.frictionPower = st.friction * st.strokeRate;
  return st;
}

void HydraulicCylinderItem::evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const
{
  const Kinematics &k = ctx.kin;
  const int nc = nEnds_, ip1 = nc, ip2 = nc + 1, isg = nc + 2, iu = nc + 3;
  const bool lag = states_.spool >= 0;
  const int n = nc + (lag ? 4 : 3);
  const bool dynamics = k.cZ > 0, accelerationLevel = ctx.accelerationLevel;
  const bool pencil = ctx.pencil && !accelerationLevel;
  // The pencil's mass pass: no inertia in a cylinder.
  if (pencil && k.cQ == 0 && k.cV == 0) return;

  auto constant = [&](double v) { return AD(v, Derivatives::Zero(n)); };
  auto variable = [&](double value, int index, double coefficient) {
    AD a(value, n, index);
    a.derivatives() *= coefficient;
    return a;
  };

  // Geometry: positions, velocities and the entries r_q as AD numbers (as Spring).
  int offset[2] = {0, 0};
  for (int e = 0, m = 0; e < 2; ++e) offset[e] = m, m += ends_[e].body ? loc_[e].count : 0;
  AD r[2][2], w[2][2];
  std::array<std::array<std::array<AD, 8>, 2>, 2> rq;
  for (int e = 0; e < 2; ++e) {
    for (int c = 0; c < 2; ++c) r[e][c] = constant(ends_[e].ground[c]), w[e][c] = constant(0.0);
    if (!ends_[e].body) continue;
    const int m0 = offset[e], cnt = loc_[e].count;
    CenterlineSample p;
    ends_[e].body->sample(loc_[e], ends_[e].s, in.q + m0, p);
    Eigen::Matrix<double, 8, 8> H[2];
    for (int c = 0; c < 2; ++c) {
      H[c].setZero();
      if (!p.linear) ends_[e].body->curvatureTerm(loc_[e], ends_[e].s, in.q + m0, 0, Vec2::Unit(c), H[c]);
      r[e][c] = constant(p.r[0][c]);
      for (int m = 0; m < cnt; ++m) {
        r[e][c].derivatives()[m0 + m] += k.cQ * p.r_q[0](c, m);
        AD entry = constant(p.r_q[0](c, m));
        for (int j = 0; j < cnt; ++j) entry.derivatives()[m0 + j] += k.cQ * H[c](m, j);
        rq[e][c][m] = entry;
        w[e][c] += entry * variable(in.v[m0 + m], m0 + m, k.cV);
      }
    }
  }
  const AD dx = r[1][0] - r[0][0], dy = r[1][1] - r[0][1];
  const AD l = sqrt(dx * dx + dy * dy);
  const AD ux = dx / l, uy = dy / l;
  const AD s = l - l0_;
  const AD sdot = ux * (w[1][0] - w[0][0]) + uy * (w[1][1] - w[0][1]);

  // The pencil's pressure unknowns are scaled, x_pi = p_i / rho_i with
  // rho_i = A_i / C_i (Pa per m): a closed chamber's pressure follows the
  // stroke as dp_i = -+rho_i ds, so x_pi is a length of the stroke's size and
  // the p rows' entries are the chamber's stiffness A_i^2 / C_i. In Pa, a
  // mode's pressure entries were ~1e10 times its displacements: its vector
  // was the pressures alone to round-off, and the damped solves lost the
  // mechanical part (damping ratios of either sign, the refinement's
  // functional iteration never met its test).
  const bool flowSource = valve_.mode == ValveData::Mode::FlowSource;
  const double A1 = cylinder_.pistonArea, A2 = cylinder_.rodSideArea;
  double rho[2] = {1.0, 1.0};
  if (pencil)
    for (int i = 0; i < 2; ++i) rho[i] = (i == 0 ? A1 : A2) / cylinder_.capacitance(i, in.q[isg]);
  const AD p1 = variable(in.q[ip1], ip1, k.cQ * rho[0]), p2 = variable(in.q[ip2], ip2, k.cQ * rho[1]);
  const AD sigma = variable(in.q[isg], isg, k.cQ);
  const double t = ctx.t;
  const AD u = lag ? variable(in.q[iu], iu, k.cQ) : constant(valve_.spoolCommand(t));

  // The axial force (extending positive).
  double dFf, dFs, dFv;
  const double Ff = cylinder_.friction(sdot.value(), &dFf);
  const double Fs = cylinder_.endStop(s.value(), sdot.value(), &dFs, &dFv);
  // A flow source holds p2 at the tank pressure (dp2 = 0): in the pencil p2
  // does not move the force, as its row does not move with the stroke.
  AD force = p1 * A1 - (pencil && flowSource ? constant(p2.value()) : p2) * A2;
  force += AD(Fs - Ff, dFs * s.derivatives() + (dFv - dFf) * sdot.derivatives());
  // The impulsive step of a velocity projection is forceless: the cylinder acts through finite forces only.
  if (ctx.velocityLevel) force = constant(0.0);

  std::array<AD, kMaxUnknowns> row;
  for (int i = 0; i < n; ++i) row[i] = constant(0.0);
  // +F u on the rod end b, -F u on the base a; residual = -Q.
  for (int e = 0; e < 2; ++e) {
    if (!ends_[e].body) continue;
    const double sign = e == 0 ? 1.0 : -1.0;
    for (int m = 0; m < loc_[e].count; ++m) row[offset[e] + m] = sign * force * (rq[e][0][m] * ux + rq[e][1][m] * uy);
  }

  // The state rows.
  if (accelerationLevel) {
    // The states are not unknowns at acceleration level: their x is a dummy 0.
    for (int i : {ip1, ip2, isg}) row[i] = ctx.sigma * variable(in.a[i], i, k.cA);
    if (lag) row[iu] = ctx.sigma * variable(in.a[iu], iu, k.cA);
  } else if (pencil) {
    // Stiffness pass: closed chambers linearized about the state, the rows
    // scaled by rho_i, symmetric with the force's dF/dx_p = A_i rho_i (C at
    // its value); sigma and u frozen (rows of the constraint scale).
    if (k.cQ != 0) {
      const double C1 = cylinder_.capacitance(0, in.q[isg]), C2 = cylinder_.capacitance(1, in.q[isg]);
      row[ip1] = -rho[0] * (C1 * p1 + A1 * s);
      row[ip2] = flowSource ? AD(-rho[1] * C2 * p2) : AD(-rho[1] * (C2 * p2 - A2 * s));
      row[isg] = ctx.sigma * sigma;
      if (lag) row[iu] = ctx.sigma * u;
    }
  } else if (!dynamics) {
    // Statics: the stroke held at its initial value by the piston pressure,
    // the rod pressure at its initial value, the spool at its command.
    row[isg] = ctx.sigma * (sigma - s);
    row[ip1] = ctx.sigma * (sigma - s0_);
    double dC2;
    const double C2 = cylinder_.capacitance(1, in.q[isg], &dC2);
    row[ip2] = -AD(C2, dC2 * sigma.derivatives()) * (p2 - p2Initial_);
    if (lag) row[iu] = u - valve_.spoolCommand(t);
  } else {
    double dC[2];
    const double C[2] = {cylinder_.capacitance(0, in.q[isg], &dC[0]), cylinder_.capacitance(1, in.q[isg], &dC[1])};
    const AD C1 = AD(C[0], dC[0] * sigma.derivatives()), C2 = AD(C[1], dC[1] * sigma.derivatives());
    const AD p1dot = variable(in.v[ip1], ip1, k.cZ), p2dot = variable(in.v[ip2], ip2, k.cZ);
    const AD sigmadot = variable(in.v[isg], isg, k.cZ);
    double Q[2], dQdu[2], dQdp[2][2];
    const double p[2] = {p1.value(), p2.value()};
    valve_.flows(t, u.value(), p, Q, dQdu, dQdp);
    const AD Q1 = AD(Q[0], dQdu[0] * u.derivatives() + dQdp[0][0] * p1.derivatives() + dQdp[0][1] * p2.derivatives());
    const AD Q2 = AD(Q[1], dQdu[1] * u.derivatives() + dQdp[1][0] * p1.derivatives() + dQdp[1][1] * p2.derivatives());
    const double weight = 1.0 / k.cZ;
    row[isg] = ctx.sigma * (sigma - s);
    row[ip1] = -weight * (C1 * p1dot + A1 * sigmadot - Q1);
    row[ip2] = flowSource ? AD(-C2 * (p2 - valve_.tankPressure)) : AD(-weight * (C2 * p2dot - A2 * sigmadot - Q2));
    if (lag) {
      const AD udot = variable(in.v[iu], iu, k.cZ);
      row[iu] = valve_.spoolTimeConstant * udot + u - valve_.spoolCommand(t);
    }
  }

  for (int i = 0; i < n; ++i) {
    residual[i] += row[i].value();
    if (J)
      for (int j = 0; j < n; ++j) J[i * n + j] += row[i].derivatives()[j];
  }
}

void HydraulicCylinderItem::energy(const AssemblyContext &, const ItemValues &in, EnergyParts &e) const
{
  // The end stops' springs store energy; every other cylinder force (the
  // pressures, friction, the stops' damping) does work on the mechanism
  // like a load: their power is an input. The hydraulic side's balance is
  // the outputs' (hydraulic_power - compression_power - friction_power).
  double s, sdot, dF, dFs, dFv;
  stroke(in.q, in.v, &s, &sdot);
  const int n = nEnds_;
  const double stop = cylinder_.endStop(s, sdot, &dFs, &dFv), stopSpring = cylinder_.endStop(s, 0.0, &dFs, &dFv);
  const double pressure = in.q[n] * cylinder_.pistonArea - in.q[n + 1] * cylinder_.rodSideArea;
  e.strain += cylinder_.stopEnergy(s);
  e.inputPower += (pressure - cylinder_.friction(sdot, &dF) + (stop - stopSpring)) * sdot;
}

} // namespace boomdyn
