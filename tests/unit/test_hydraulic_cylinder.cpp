// The hydraulic cylinder (hydraulic_cylinder.hpp, hydraulic_cylinder_item.hpp)
// as a kernel:
//  - the orifice law: odd, laminar (linear) at small drops with the slope
//    5/(4 sqrt(dp_lam)), equal to sign(dp) sqrt(|dp|) from dp_lam on, and C1
//    at dp_lam (value and slope from both sides to 1e-12);
//  - the capacitance C = V/B_oil + V_h/B_hose + (V - V_h)/B_wall against the
//    series formula 1/beta = 1/B_oil + (V_h/V)/B_hose + ((V - V_h)/V)/B_wall;
//  - the item's Jacobian against central finite differences of its
//    residual, every block (end coordinates q and v, pressures and their
//    rates, stroke memory, spool and its rate), in the dynamic map and its
//    q-only and v-only parts and in statics: both flow directions of the
//    valve, the laminar region and both sides of its limit, reverse flow
//    (chamber above supply), both end stops (inside and beyond the damping
//    ramp), closed valve and flow source; the cylinder joins a rigid body
//    (nonlinear centerline) and an ANCF beam;
//  - the eigen pencil's stiffness block is symmetric, and eliminating the
//    pressures from it adds k_h s_q s_q^T, k_h = A1^2/C1 + A2^2/C2.
#include "boomdyn/hydraulic_cylinder_item.hpp"
#include "rope_test_bodies.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace boomdyn;

namespace {

HydraulicCylinderData cylinderData()
{
  HydraulicCylinderData c;
  c.pistonArea = 7.85e-3, c.rodSideArea = 5.39e-3, c.strokeLength = 0.6;
  c.deadVolume[0] = 2e-4, c.deadVolume[1] = 1.5e-4, c.hoseVolume[0] = 3e-4, c.hoseVolume[1] = 2.5e-4;
  c.bulkOil = 1.65e9, c.bulkHose = 7e8, c.bulkWall = 3.15e10;
  c.coulomb = 210, c.coulombVelocity = 5e-3, c.viscous = 330;
  c.stopStiffness = 1e7, c.stopDamping = 5e3, c.stopDampingDepth = 8e-3;
  return c;
}

ValveData proportionalValve(double command)
{
  ValveData v;
  v.mode = ValveData::Mode::Proportional;
  v.command = TimeFunction::constant(command);
  v.spoolTimeConstant = 1.0 / (2 * M_PI * 35);
  v.flowCoefficient = 6.67e-4 / std::sqrt(35e5);
  v.laminarPressureDrop = 2e5;
  v.supplyPressure = 160e5, v.tankPressure = 1e5;
  return v;
}

struct Mount {
  rope_test::Bodies bodies;
  // Rod end on the ANCF beam b1 inside an element, base on the rigid body b3.
  HydraulicCylinderItem::End base() const { return {&bodies.b3, 1.5, Vec2::Zero()}; }
  HydraulicCylinderItem::End rod() const { return {&bodies.b1, 0.2, Vec2::Zero()}; }
  double length() const
  {
    const double *q = bodies.q0.data();
    CenterlineSample a, b;
    bodies.b3.sample(bodies.b3.locate(1.5), 1.5, q + 40, a);
    bodies.b1.sample(bodies.b1.locate(0.2), 0.2, q + 0, b);
    return (b.r[0] - a.r[0]).norm();
  }
};

struct Residual {
  std::vector<double> r, J;
};

Residual evaluate(const HydraulicCylinderItem &item, const Kinematics &kin, const std::vector<double> &q,
                  const std::vector<double> &v, bool pencil = false)
{
  const std::size_t n = q.size();
  Residual out{std::vector<double>(n, 0.0), std::vector<double>(n * n, 0.0)};
  AssemblyContext ctx;
  ctx.t = 0.3;
  ctx.kin = kin;
  ctx.sigma = 1e6;
  ctx.pencil = pencil;
  const std::vector<double> a(n, 0.0);
  item.evaluate(ctx, ItemValues{q.data(), v.data(), a.data(), nullptr}, out.r.data(), out.J.data());
  return out;
}

// The largest column-scaled error |J_ij - FD_ij| X_j relative to the row's
// scale max_k |J_ik| X_k, over all rows, for the map x -> (q = cQ x, v = cV x
// on the coordinates, cZ x on the states): X_j is a typical size of unknown j.
double finiteDifferenceError(const HydraulicCylinderItem &item, const Kinematics &kin, const std::vector<double> &q,
                             const std::vector<double> &v, int nc, const std::vector<double> &X)
{
  const std::size_t n = q.size();
  const Residual at = evaluate(item, kin, q, v);
  std::vector<double> rowScale(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) rowScale[i] = std::max(rowScale[i], std::abs(at.J[i * n + j]) * X[j]);
  double worst = 0;
  for (std::size_t j = 0; j < n; ++j) {
    // A step that moves q and v (cV, cZ up to 2000) by about 1e-5 of their sizes.
    const double cv = static_cast<int>(j) < nc ? kin.cV : kin.cZ;
    const double h = 1e-5 * X[j] / std::max({kin.cQ, cv, 1.0});
    // Fourth-order central differences: the smoothed Coulomb law's tanh
    // (velocity scale 5 mm/s) has large third derivatives.
    auto at_ = [&](double step) {
      std::vector<double> qs = q, vs = v;
      qs[j] += kin.cQ * step, vs[j] += cv * step;
      return evaluate(item, kin, qs, vs).r;
    };
    const std::vector<double> r1 = at_(h), rm1 = at_(-h), r2 = at_(2 * h), rm2 = at_(-2 * h);
    for (std::size_t i = 0; i < n; ++i) {
      if (rowScale[i] == 0) continue;
      const double fd = (8 * (r1[i] - rm1[i]) - (r2[i] - rm2[i])) / (12 * h);
      const double e = std::abs(fd - at.J[i * n + j]) * X[j] / rowScale[i];
      worst = std::max(worst, e);
    }
  }
  return worst;
}

} // namespace

TEST(HydraulicCylinder, OrificeLawIsLaminarAtSmallDropsAndC1AtTheLimit)
{
  ValveData v = proportionalValve(1.0);
  const double L = v.laminarPressureDrop;
  double s0, sa, sb;
  const double f0 = v.orifice(0.0, &s0);
  EXPECT_EQ(f0, 0.0);
  EXPECT_NEAR(s0, 1.25 / std::sqrt(L), 1e-15);
  const double below = v.orifice(L * (1 - 1e-12), &sa), above = v.orifice(L * (1 + 1e-12), &sb);
  EXPECT_NEAR(below / std::sqrt(L), 1.0, 1e-11);
  EXPECT_NEAR(above / std::sqrt(L), 1.0, 1e-11);
  EXPECT_NEAR(sa / sb, 1.0, 1e-11); // C1 at dp_lam
  double s;
  EXPECT_NEAR(v.orifice(9 * L, &s), 3 * std::sqrt(L), 1e-9);
  EXPECT_NEAR(v.orifice(-0.3 * L, &s), -v.orifice(0.3 * L, &sa), 1e-15); // odd
  // Nearly linear in the laminar region: at dp_lam / 10 within 1 % of the slope at 0.
  EXPECT_NEAR(v.orifice(0.1 * L, &s) / (0.1 * L * s0), 1.0, 0.01);
}

TEST(HydraulicCylinder, CapacitanceIsTheSeriesBulkModulus)
{
  const HydraulicCylinderData c = cylinderData();
  for (int chamber = 0; chamber < 2; ++chamber)
    for (double s : {0.0, 0.2, 0.6}) {
      const double V = c.volume(chamber, s), Vh = c.hoseVolume[chamber];
      const double beta = 1.0 / (1.0 / c.bulkOil + (Vh / V) / c.bulkHose + ((V - Vh) / V) / c.bulkWall);
      EXPECT_NEAR(c.effectiveBulkModulus(chamber, s) / beta, 1.0, 1e-14);
      double dC;
      c.capacitance(chamber, s, &dC);
      const double h = 1e-6, fd = (c.capacitance(chamber, s + h) - c.capacitance(chamber, s - h)) / (2 * h);
      EXPECT_NEAR(dC / fd, 1.0, 1e-8);
    }
}

TEST(HydraulicCylinder, JacobianMatchesFiniteDifferencesInEveryBlock)
{
  const Mount setup;
  const double l = setup.length();
  const HydraulicCylinderData c = cylinderData();
  std::vector<PetscInt> dofs;
  std::mt19937 rng(38);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double h = 1e-3, gammaP = 0.6 / (h * 0.3025), betaP = 0.5 / (h * h * 0.3025);
  const Kinematics dynamic{1.0, gammaP, betaP, 1.0 / h}, qOnly{1.0, 0.0, 0.0, 1.0 / h}, vOnly{0.0, 1.0, 0.0, 1.0 / h},
      statics{1.0, 0.0, 0.0, 0.0};
  struct Case {
    const char *what;
    double stroke;     // where the cylinder is (sets closed_length)
    ValveData valve;
    double p1, p2, u;  // states
  };
  const ValveData pv = proportionalValve(0.4);
  ValveData closed;
  closed.mode = ValveData::Mode::Closed;
  ValveData source;
  source.mode = ValveData::Mode::FlowSource;
  source.flow = TimeFunction::ramp(0.0, 1.0, 0.0, 1e-3);
  source.tankPressure = 1e5;
  const double ps = pv.supplyPressure, pt = pv.tankPressure, L = pv.laminarPressureDrop;
  const std::vector<Case> cases = {
      {"u > 0, turbulent both edges", 0.3, pv, 80e5, 30e5, 0.6},
      {"u < 0, turbulent both edges", 0.3, pv, 80e5, 30e5, -0.6},
      {"u > 0, feed laminar", 0.3, pv, ps - 0.5 * L, 30e5, 0.6},
      {"u > 0, feed just below the laminar limit", 0.3, pv, ps - 0.999 * L, 30e5, 0.6},
      {"u > 0, feed just above the laminar limit", 0.3, pv, ps - 1.001 * L, 30e5, 0.6},
      {"u < 0, drain laminar", 0.3, pv, pt + 0.3 * L, ps - 0.2 * L, -0.6},
      {"u > 0, reverse flow (chamber above supply)", 0.3, pv, ps + 3 * L, 30e5, 0.6},
      {"retracted end stop inside the damping ramp", -0.5 * c.stopDampingDepth, pv, 80e5, 30e5, 0.6},
      {"retracted end stop beyond the damping ramp", -2 * c.stopDampingDepth, pv, 80e5, 30e5, -0.6},
      {"extended end stop inside the damping ramp", c.strokeLength + 0.5 * c.stopDampingDepth, pv, 80e5, 30e5, 0.6},
      {"extended end stop beyond the damping ramp", c.strokeLength + 2 * c.stopDampingDepth, pv, 80e5, 30e5, -0.6},
      {"closed valve", 0.3, closed, 80e5, 30e5, 0.0},
      {"flow source", 0.3, source, 80e5, 1e5, 0.0},
  };
  for (const Case &k : cases) {
    HydraulicCylinderItem::States states{43, 44, 45, k.valve.mode == ValveData::Mode::Proportional ? 46 : -1};
    const HydraulicCylinderItem item("cyl", setup.base(), setup.rod(), l - k.stroke, c, k.valve, states, 0.3, 30e5);
    item.coordinates(dofs);
    const int nc = item.numEndCoordinates(), n = static_cast<int>(dofs.size());
    std::vector<double> q(n), v(n), X(n, 1.0);
    for (int i = 0; i < nc; ++i) {
      q[i] = setup.bodies.q0[dofs[i]] + 1e-5 * unit(rng); // a slightly deformed state: the stroke stays put
      v[i] = 0.05 * unit(rng);
    }
    q[nc] = k.p1, q[nc + 1] = k.p2, q[nc + 2] = k.stroke + 1e-4, X[nc] = X[nc + 1] = 1e7;
    v[nc] = 3e6 * unit(rng), v[nc + 1] = 2e6 * unit(rng), v[nc + 2] = 0.05 * unit(rng);
    if (n > nc + 3) q[nc + 3] = k.u, v[nc + 3] = 2.0 * unit(rng);
    double worst = 0;
    for (const Kinematics &kin : {dynamic, qOnly, vOnly, statics})
      worst = std::max(worst, finiteDifferenceError(item, kin, q, v, nc, X));
    PetscPrintf(PETSC_COMM_WORLD, "  cylinder FD (%s): largest scaled |J - FD| %.2e\n", k.what, worst);
    EXPECT_LT(worst, 1e-6) << k.what;
  }
}

TEST(HydraulicCylinder, PencilStiffnessIsSymmetricAndAddsTheOilColumn)
{
  const Mount setup;
  const double l = setup.length();
  const HydraulicCylinderData c = cylinderData();
  ValveData closed;
  const HydraulicCylinderItem item("cyl", setup.base(), setup.rod(), l - 0.3, c, closed, {43, 44, 45, -1}, 0.3, 0.0);
  std::vector<PetscInt> dofs;
  item.coordinates(dofs);
  const int nc = item.numEndCoordinates(), n = static_cast<int>(dofs.size());
  std::vector<double> q(n), v(n, 0.0);
  for (int i = 0; i < nc; ++i) q[i] = setup.bodies.q0[dofs[i]];
  q[nc] = 50e5, q[nc + 1] = 20e5, q[nc + 2] = 0.3;
  const Residual A = evaluate(item, {1.0, 0.0, 0.0, 0.0}, q, v, true);
  double asym = 0, scale = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      asym = std::max(asym, std::abs(A.J[i * n + j] - A.J[j * n + i]));
      scale = std::max(scale, std::abs(A.J[i * n + j]));
    }
  EXPECT_LT(asym, 1e-13 * scale);
  // Schur complement on the coordinates: K_qq - K_qp K_pp^-1 K_pq must add
  // k_h s_q s_q^T to K_qq, with s_q from finite differences of the stroke.
  std::vector<double> sq(nc);
  for (int j = 0; j < nc; ++j) {
    std::vector<double> qa = q, qb = q;
    qa[j] += 1e-7, qb[j] -= 1e-7;
    double sa, sb;
    item.stroke(qa.data(), nullptr, &sa, nullptr);
    item.stroke(qb.data(), nullptr, &sb, nullptr);
    sq[j] = (sa - sb) / 2e-7;
  }
  const double C1 = c.capacitance(0, 0.3), C2 = c.capacitance(1, 0.3);
  const double kh = c.pistonArea * c.pistonArea / C1 + c.rodSideArea * c.rodSideArea / C2;
  double worst = 0, size = 0;
  for (int i = 0; i < nc; ++i)
    for (int j = 0; j < nc; ++j) {
      double added = 0;
      for (int p : {nc, nc + 1}) added -= A.J[i * n + p] * A.J[p * n + j] / A.J[p * n + p];
      worst = std::max(worst, std::abs(added - kh * sq[i] * sq[j]));
      size = std::max(size, kh * std::abs(sq[i] * sq[j]));
    }
  EXPECT_LT(worst, 1e-6 * size);
}
