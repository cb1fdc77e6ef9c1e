// Selective reduced integration of the ANCF element's axial term
// (AxialIntegration::Reduced): exact gradient and tangent against central
// differences, damping consistent with the reduced axial strain, and no
// spurious zero-energy modes (a free element has exactly 3 rigid-body zeros).
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

Section reducedSection(double etaA = 0, double etaB = 0)
{
  Section s{2.1e11 * 4.0e-3, 2.1e11 * 2.5e-5, 7850 * 4.0e-3, etaA, etaB};
  s.axialIntegration = AxialIntegration::Reduced;
  return s;
}


} // namespace

TEST(AncfReducedAxial, InternalForceIsEnergyGradient)
{
  const Section sec = reducedSection();
  std::mt19937 rng(11);
  const double l = 0.25;
  for (int trial = 0; trial < 6; ++trial)
    EXPECT_LT(energyGradientError(sec, l, deformedState(rng, l, 0.05)), 1e-6) << "trial " << trial;
}

TEST(AncfReducedAxial, TangentMatchesCentralDifferences)
{
  const Section sec = reducedSection();
  std::mt19937 rng(12);
  const double l = 0.25;
  for (int trial = 0; trial < 8; ++trial) {
    double asymmetry;
    EXPECT_LT(tangentError(sec, l, deformedState(rng, l, trial < 4 ? 0.02 : 0.2), &asymmetry), 1e-6) << "trial " << trial;
    EXPECT_LT(asymmetry, 1e-12) << "tangent must be symmetric";
  }
}

TEST(AncfReducedAxial, DiffersFromFullOnlyWhereTheStrainIsNotUniform)
{
  Section full = reducedSection();
  full.axialIntegration = AxialIntegration::Full;
  const Section reduced = reducedSection();
  const double l = 0.4;
  // Uniform stretch: eps is constant, every rule integrates it exactly.
  const double stretch = 1.001;
  Vec8 stretched;
  stretched << Vec2(0.1, 0.2), stretch * Vec2(0.6, 0.8), Vec2(0.1, 0.2) + stretch * l * Vec2(0.6, 0.8), stretch * Vec2(0.6, 0.8);
  EXPECT_NEAR(strainEnergy(reduced, l, stretched), strainEnergy(full, l, stretched),
              1e-12 * strainEnergy(full, l, stretched));
  // Bent: eps^2 is a polynomial of degree 8, which 3 points do not integrate exactly.
  std::mt19937 rng(13);
  const Vec8 bent = deformedState(rng, l, 0.1);
  EXPECT_GT(std::abs(strainEnergy(reduced, l, bent) - strainEnergy(full, l, bent)), 1e-6 * strainEnergy(full, l, bent));
}

TEST(AncfReducedAxial, DampingJacobiansMatchCentralDifferences)
{
  const Section sec = reducedSection(2.0e-4, 3.0e-3);
  std::mt19937 rng(14);
  const double l = 0.25;
  for (int trial = 0; trial < 6; ++trial) {
    const Vec8 e = deformedState(rng, l, trial < 3 ? 0.02 : 0.2), v = randomVelocity(rng, l, 1.0);
    double errorQ, errorV, asymmetry;
    dampingJacobianErrors(sec, l, e, v, &errorQ, &errorV, &asymmetry);
    EXPECT_LT(errorQ, 1e-6) << "trial " << trial;
    EXPECT_LT(errorV, 1e-6) << "trial " << trial;
  }
}

TEST(AncfReducedAxial, AxialDampingUsesTheReducedStrainRate)
{
  // Axial damping only: the dissipated power must be sum_p w_p l EA etaA epsdot_p^2
  // over the 3 reduced points, with epsdot_p from differences of axialStrain().
  const Section sec = reducedSection(2.0e-4, 0.0);
  std::mt19937 rng(15);
  const double l = 0.3;
  const double x3[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
  const double w3[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  for (int trial = 0; trial < 4; ++trial) {
    const Vec8 e = deformedState(rng, l, 0.1), v = randomVelocity(rng, l, 1.0);
    Vec8 f;
    const double power = dampingForce(sec, l, e, v, f, nullptr, nullptr);
    double expected = 0;
    const double h = 1e-6;
    for (int p = 0; p < 3; ++p) {
      const double rate = (axialStrain(e + h * v, x3[p], l) - axialStrain(e - h * v, x3[p], l)) / (2 * h);
      expected += w3[p] * l * sec.EA * sec.etaA * rate * rate;
    }
    EXPECT_NEAR(power, expected, 1e-6 * expected) << "trial " << trial;
    EXPECT_NEAR(v.dot(f), power, 1e-10 * power);
  }
  // Straight, unstrained: D = eta K with etaA = etaB = eta, as with full integration.
  Section both = reducedSection(2.5e-3, 2.5e-3);
  const Vec8 e = straightElement(Vec2(0.2, 0.1), Vec2(std::cos(0.4), std::sin(0.4)), l);
  Vec8 f, fd;
  Mat8 K, Dv;
  internalForce(both, l, e, f, &K);
  dampingForce(both, l, e, Vec8::Zero(), fd, nullptr, &Dv);
  EXPECT_LT(relErr(Dv, 2.5e-3 * K), 1e-12);
}

TEST(AncfReducedAxial, FreeElementHasExactlyThreeZeroEnergyModes)
{
  // K v = omega^2 M v of one free element: 3 rigid-body zeros (2 translations,
  // 1 rotation) and 5 deformation modes. Too few axial points (2) would add a
  // zero-energy axial mode; 3 points integrate the linear axial stiffness exactly.
  for (AxialIntegration rule : {AxialIntegration::Full, AxialIntegration::Reduced}) {
    Section sec = reducedSection();
    sec.axialIntegration = rule;
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
      // Lowest deformation mode, bending or axial: omega^2 well above
      // min(EI / (rhoA l^4), EA / (rhoA l^2)) (constants of O(10..100)); a
      // spurious mode would sit at round-off like the rigid ones.
      const double scale = std::min(sec.EI / (sec.rhoA * l * l * l * l), sec.EA / (sec.rhoA * l * l));
      EXPECT_GT(w2[3], scale) << "l = " << l;
      EXPECT_GT(w2[3], 1e-6 * top) << "l = " << l;
    }
  }
}
