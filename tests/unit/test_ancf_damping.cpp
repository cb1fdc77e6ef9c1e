// Kelvin-Voigt damping of the planar ANCF element (docs/model.md §1.1): the
// damping force and both Jacobian blocks (dfd/de into cQ, dfd/dedot into cV)
// against central differences at random deformed states and velocities,
// the dissipated power, and zero force for rigid motions (objectivity).
#include "boomdyn/ancf_element.hpp"
#include "ancf_random_states.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace boomdyn::ancf;
using namespace boomdyn::ancf::element_states;

namespace {

// Steel box section with retardation times giving ~1-5 % damping in the low modes.
const Section kDamped{2.1e11 * 4.0e-3, 2.1e11 * 2.5e-5, 7850 * 4.0e-3, 2.0e-4, 3.0e-3};


Vec8 force(const Vec8 &e, const Vec8 &v, double l)
{
  Vec8 f;
  dampingForce(kDamped, l, e, v, f, nullptr, nullptr);
  return f;
}

} // namespace

TEST(AncfDamping, JacobiansMatchCentralDifferences)
{
  std::mt19937 rng(7);
  const double l = 0.25;
  for (int trial = 0; trial < 8; ++trial) {
    // Velocities up to ~2 m/s and 2 rad/s.
    const Vec8 e = deformedState(rng, l, trial < 4 ? 0.02 : 0.2), v = randomVelocity(rng, l, 2.0 / l);
    Vec8 f;
    Mat8 Kq, Dv;
    dampingForce(kDamped, l, e, v, f, &Kq, &Dv);
    Mat8 fdQ, fdV;
    for (int k = 0; k < 8; ++k) {
      const double hq = 1e-7 * coordinateScale(k, l), hv = 1e-3 * coordinateScale(k, l);
      Vec8 ep = e, em = e, vp = v, vm = v;
      ep[k] += hq, em[k] -= hq, vp[k] += hv, vm[k] -= hv;
      fdQ.col(k) = (force(ep, v, l) - force(em, v, l)) / (2 * hq);
      fdV.col(k) = (force(e, vp, l) - force(e, vm, l)) / (2 * hv); // linear in v: exact up to round-off
    }
    EXPECT_LT(relErr(Kq, fdQ), 1e-6) << "trial " << trial;
    EXPECT_LT(relErr(Dv, fdV), 1e-6) << "trial " << trial;
    EXPECT_LT((Dv - Dv.transpose()).norm(), 1e-14 * Dv.norm()) << "dfd/dedot must be symmetric";
    // The force is linear in the rate: fd = D edot.
    EXPECT_LT(relErr(f, Dv * v), 1e-12) << "trial " << trial;
  }
}

TEST(AncfDamping, DissipatedPowerIsRateTimesForceAndPositive)
{
  std::mt19937 rng(8);
  const double l = 0.4;
  for (int trial = 0; trial < 6; ++trial) {
    const Vec8 e = deformedState(rng, l, 0.1), v = randomVelocity(rng, l, 2.0 / l);
    Vec8 f;
    const double power = dampingForce(kDamped, l, e, v, f, nullptr, nullptr);
    EXPECT_GT(power, 0.0);
    EXPECT_NEAR(power, v.dot(f), 1e-12 * std::abs(power)) << "trial " << trial;
  }
}

TEST(AncfDamping, RigidMotionsGiveNoDampingForce)
{
  // Rigid translation and rotation at 10 rad/s about an arbitrary point, at
  // a deformed state (the strain rates vanish whatever the strain).
  std::mt19937 rng(9);
  const double l = 0.5, omega = 10.0;
  const Vec2 centre(0.7, -1.2), speed(3.0, -4.0);
  for (int trial = 0; trial < 4; ++trial) {
    const Vec8 e = deformedState(rng, l, trial == 0 ? 0.0 : 0.1);
    Vec8 translation, rotation;
    for (int k = 0; k < 4; ++k) {
      const Vec2 x = e.segment<2>(2 * k);
      const bool slope = (k % 2) == 1; // node entries r, r', r, r'
      translation.segment<2>(2 * k) = slope ? Vec2::Zero() : speed;
      const Vec2 arm = slope ? x : Vec2(x - centre);
      rotation.segment<2>(2 * k) = omega * Vec2(-arm.y(), arm.x());
    }
    // Reference: the force of a pure deformation rate of unit size.
    const Vec8 unit = randomVelocity(rng, l, 2.0 / l);
    const double scale = force(e, unit, l).norm() * (omega * (1.0 + centre.norm()));
    EXPECT_LT(force(e, translation, l).norm(), 1e-12 * scale) << "trial " << trial;
    EXPECT_LT(force(e, rotation, l).norm(), 1e-12 * scale) << "trial " << trial;
    Vec8 f;
    EXPECT_LT(dampingForce(kDamped, l, e, rotation, f, nullptr, nullptr), 1e-20 * scale * scale);
  }
}

TEST(AncfDamping, StraightStateDampingIsEtaTimesStiffness)
{
  // About the straight, unstrained state D = etaA K_axial + etaB K_bending:
  // with etaA = etaB = eta the damping is stiffness-proportional, D = eta K,
  // which gives every mode zeta_n = eta omega_n / 2.
  const double l = 0.3, eta = 2.5e-3;
  Section sec = kDamped;
  sec.etaA = sec.etaB = eta;
  const Vec8 e = straightElement(Vec2(0.2, 0.1), Vec2(std::cos(0.4), std::sin(0.4)), l);
  Vec8 f, fd;
  Mat8 K, Kq, Dv;
  internalForce(sec, l, e, f, &K);
  dampingForce(sec, l, e, Vec8::Zero(), fd, &Kq, &Dv);
  EXPECT_LT(relErr(Dv, eta * K), 1e-12);
  EXPECT_LT(Kq.norm(), 1e-30 + 1e-14 * K.norm()) << "no rate, no dfd/de";
}
