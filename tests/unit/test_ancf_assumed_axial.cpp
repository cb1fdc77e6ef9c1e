// Assumed axial strain of the ANCF element (AxialIntegration::Assumed): exact
// gradient and tangent against central differences, damping Jacobians (the
// cQ and cV blocks) against central differences, damping on the same assumed
// strain as the elastic force, no spurious zero-energy mode of a free
// element, and the full element bit for bit for stocky beams.
#include "boomdyn/ancf_element.hpp"
#include "ancf_random_states.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <random>

using namespace boomdyn::ancf;
using namespace boomdyn::ancf::element_states;

namespace {

// Steel tube; a 100 m beam: EA L^2/EI = 1.6e6, pointwise weight gamma = 1e4 / 1.6e6.
Section assumedSection(double etaA = 0, double etaB = 0)
{
  Section s{2.1e11 * 4.0e-3, 2.1e11 * 2.5e-5, 7850 * 4.0e-3, etaA, etaB};
  s.axialIntegration = AxialIntegration::Assumed;
  s.length = 100.0;
  return s;
}

} // namespace

TEST(AncfAssumedAxial, PointwiseWeightFollowsTheBeamsSlenderness)
{
  const Section sec = assumedSection();
  EXPECT_NEAR(assumedPointwiseWeight(sec, 0.25), kAssumedStabilization * sec.EI / (sec.EA * 1e4), 1e-15);
  Section stocky = sec;
  stocky.length = 5.0; // EA L^2/EI = 4000 <= 1e4
  EXPECT_EQ(assumedPointwiseWeight(stocky, 0.25), 1.0);
  Section full = sec;
  full.axialIntegration = AxialIntegration::Full;
  EXPECT_EQ(assumedPointwiseWeight(full, 0.25), 1.0);
}

TEST(AncfAssumedAxial, InternalForceIsEnergyGradient)
{
  const Section sec = assumedSection();
  std::mt19937 rng(21);
  const double l = 0.25;
  for (int trial = 0; trial < 6; ++trial)
    EXPECT_LT(energyGradientError(sec, l, deformedState(rng, l, 0.05)), 1e-6) << "trial " << trial;
}

TEST(AncfAssumedAxial, TangentMatchesCentralDifferences)
{
  const Section sec = assumedSection();
  std::mt19937 rng(22);
  const double l = 0.25;
  for (int trial = 0; trial < 8; ++trial) {
    double asymmetry;
    EXPECT_LT(tangentError(sec, l, deformedState(rng, l, trial < 4 ? 0.02 : 0.2), &asymmetry), 1e-6) << "trial " << trial;
    EXPECT_LT(asymmetry, 1e-12) << "tangent must be symmetric";
  }
}

TEST(AncfAssumedAxial, DampingJacobiansMatchCentralDifferences)
{
  // dfd/de (the cQ block) and dfd/dedot (the cV block) of the Kelvin-Voigt force.
  const Section sec = assumedSection(2.0e-4, 3.0e-3);
  std::mt19937 rng(24);
  const double l = 0.25;
  for (int trial = 0; trial < 6; ++trial) {
    const Vec8 e = deformedState(rng, l, trial < 3 ? 0.02 : 0.2), v = randomVelocity(rng, l, 1.0);
    double errorQ, errorV, asymmetry;
    dampingJacobianErrors(sec, l, e, v, &errorQ, &errorV, &asymmetry);
    EXPECT_LT(errorQ, 1e-6) << "trial " << trial;
    EXPECT_LT(errorV, 1e-6) << "trial " << trial;
    EXPECT_LT(asymmetry, 1e-12);
  }
}

TEST(AncfAssumedAxial, AxialDampingUsesTheAssumedStrainRate)
{
  // Axial damping only. The power must be
  //   EA etaA l [(1 - gamma) sum_j alphadot_j^2 + gamma ∫ epsdot^2 dxi],
  // alphadot_j = ∫ phi_j epsdot dxi (phi_0 = 1, phi_1 = sqrt3 (2 xi - 1)),
  // evaluated here independently: epsdot from central differences of
  // axialStrain() (exact: eps is quadratic in e), the integrals with the
  // 3-point rule (exact for ∫ phi_j epsdot, degree 5) and the 5-point rule
  // for ∫ epsdot^2 (degree 8).
  const Section sec = assumedSection(2.0e-4, 0.0);
  const double l = 0.3, gamma = assumedPointwiseWeight(sec, l);
  ASSERT_LT(gamma, 0.1);
  const double a3 = std::sqrt(0.6), x3[3] = {0.5 - 0.5 * a3, 0.5, 0.5 + 0.5 * a3};
  const double w3[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  const double a = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0, b = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  const double wa = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0, wb = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
  const double x5[5] = {0.5 - 0.5 * b, 0.5 - 0.5 * a, 0.5, 0.5 + 0.5 * a, 0.5 + 0.5 * b};
  const double w5[5] = {0.5 * wb, 0.5 * wa, 0.5 * 128.0 / 225.0, 0.5 * wa, 0.5 * wb};
  std::mt19937 rng(25);
  for (int trial = 0; trial < 4; ++trial) {
    const Vec8 e = deformedState(rng, l, 0.1), v = randomVelocity(rng, l, 1.0);
    const double h = 1e-6;
    const auto rate = [&](double xi) { return (axialStrain(e + h * v, xi, l) - axialStrain(e - h * v, xi, l)) / (2 * h); };
    double alphaDot0 = 0, alphaDot1 = 0, pointwise = 0;
    for (int p = 0; p < 3; ++p) {
      alphaDot0 += w3[p] * rate(x3[p]);
      alphaDot1 += w3[p] * std::sqrt(3.0) * (2 * x3[p] - 1) * rate(x3[p]);
    }
    for (int p = 0; p < 5; ++p) pointwise += w5[p] * rate(x5[p]) * rate(x5[p]);
    const double expected = sec.EA * sec.etaA * l *
                            ((1 - gamma) * (alphaDot0 * alphaDot0 + alphaDot1 * alphaDot1) + gamma * pointwise);
    Vec8 f;
    const double power = dampingForce(sec, l, e, v, f, nullptr, nullptr);
    EXPECT_NEAR(power, expected, 1e-6 * expected) << "trial " << trial;
    EXPECT_NEAR(v.dot(f), power, 1e-10 * power);
    // The elastic energy rests on the same assumed strain: the projection,
    // evaluated the same way from axialStrain(), gives strainEnergy().
    double eps0 = 0, eps1 = 0;
    for (int p = 0; p < 3; ++p) {
      eps0 += w3[p] * axialStrain(e, x3[p], l);
      eps1 += w3[p] * std::sqrt(3.0) * (2 * x3[p] - 1) * axialStrain(e, x3[p], l);
    }
    Section axialOnly = sec;
    axialOnly.EI = 0; // no bending, and gamma = c EI / (EA L^2) = 0: the projected energy alone
    const double U = strainEnergy(axialOnly, l, e);
    EXPECT_NEAR(U, 0.5 * sec.EA * l * (eps0 * eps0 + eps1 * eps1), 1e-9 * U) << "trial " << trial;
  }
  // Straight, unstrained: D = eta K with etaA = etaB = eta, as with full integration.
  const Section both = assumedSection(2.5e-3, 2.5e-3);
  const Vec8 e = straightElement(Vec2(0.2, 0.1), Vec2(std::cos(0.4), std::sin(0.4)), l);
  Vec8 f, fd;
  Mat8 K, Dv;
  internalForce(both, l, e, f, &K);
  dampingForce(both, l, e, Vec8::Zero(), fd, nullptr, &Dv);
  EXPECT_LT(relErr(Dv, 2.5e-3 * K), 1e-12);
}

TEST(AncfAssumedAxial, FreeElementHasExactlyThreeZeroEnergyModes)
{
  // The linear projection alone leaves a zero-energy axial mode (u' ∝ P2(xi):
  // equal nodal slope stretch, zero mean and zero first moment); the
  // pointwise part gives it the stiffness of the beam's bending scale.
  for (double L : {1.0, 100.0, 1000.0}) {
    Section sec = assumedSection();
    sec.length = L;
    for (double l : {0.05, 0.5, 5.0}) {
      const Vec8 e = straightElement(Vec2(0.3, -0.2), Vec2(std::cos(0.7), std::sin(0.7)), l);
      Vec8 f;
      Mat8 K;
      internalForce(sec, l, e, f, &K);
      const Eigen::GeneralizedSelfAdjointEigenSolver<Mat8> eig(K, massMatrix(sec.rhoA, l), Eigen::EigenvaluesOnly);
      Eigen::Matrix<double, 8, 1> w2 = eig.eigenvalues();
      std::sort(w2.data(), w2.data() + 8);
      const double top = w2[7];
      for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(w2[i]), 1e-10 * top) << "rigid mode " << i << ", l = " << l;
      // The stabilized mode: stiffness gamma EA l / 5 on a slope-sized mass ~ rhoA l^3 / 100.
      const double gamma = assumedPointwiseWeight(sec, l);
      EXPECT_GT(w2[3], std::min(sec.EI / (sec.rhoA * l * l * l * l), gamma * sec.EA / (sec.rhoA * l * l))) << "L = " << L << ", l = " << l;
      EXPECT_GT(w2[3], 1e-8 * top) << "L = " << L << ", l = " << l;
    }
  }
}

TEST(AncfAssumedAxial, StockyBeamIsTheFullElementBitForBit)
{
  // EA L^2/EI <= kAssumedStabilization (1e4): gamma = 1, no projection at all.
  Section assumed = assumedSection(2.0e-4, 3.0e-3), full = assumed;
  assumed.length = 2.0; // EA L^2/EI = 640
  full.axialIntegration = AxialIntegration::Full;
  std::mt19937 rng(26);
  const double l = 0.25;
  const Vec8 e = deformedState(rng, l, 0.1), v = randomVelocity(rng, l, 1.0);
  Vec8 fa, ff, da, df;
  Mat8 Ka, Kf, Qa, Qf, Va, Vf;
  internalForce(assumed, l, e, fa, &Ka);
  internalForce(full, l, e, ff, &Kf);
  dampingForce(assumed, l, e, v, da, &Qa, &Va);
  dampingForce(full, l, e, v, df, &Qf, &Vf);
  EXPECT_EQ(strainEnergy(assumed, l, e), strainEnergy(full, l, e));
  EXPECT_EQ((fa - ff).norm(), 0.0);
  EXPECT_EQ((Ka - Kf).norm(), 0.0);
  EXPECT_EQ((da - df).norm(), 0.0);
  EXPECT_EQ((Qa - Qf).norm(), 0.0);
  EXPECT_EQ((Va - Vf).norm(), 0.0);
}
