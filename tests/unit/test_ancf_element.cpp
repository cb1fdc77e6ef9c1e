// Planar ANCF cable element: forces against the energy, tangent against
// central finite differences, rigid-motion invariance, exact mass moments.
#include "boomdyn/ancf_element.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace boomdyn::ancf;

namespace {

const Section kSteelBox{2.1e11 * 4.0e-3, 2.1e11 * 2.5e-5, 7850 * 4.0e-3};

// A straight element rotated by `angle`, with a random deformation of relative size `amp`.
Vec8 deformedState(std::mt19937 &rng, double l, double amp)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double angle = 3.0 * u(rng);
  Vec8 e = straightElement(Vec2(u(rng), u(rng)), Vec2(std::cos(angle), std::sin(angle)), l);
  for (int k = 0; k < 8; ++k) e[k] += amp * u(rng) * ((k % 4) < 2 ? l : 1.0);
  return e;
}

double relErr(const Eigen::MatrixXd &a, const Eigen::MatrixXd &b) { return (a - b).norm() / b.norm(); }

// The sections and element lengths of the bit-identity tests, in the order
// the tests draw their random states: every axial treatment; the assumed
// strain both slender (beam length 100 m: projection active) and stocky
// (length 0: gamma = 1, no projection); a long and a very short element;
// with material damping or without.
struct KernelCase {
  Section sec;
  double l;
};

std::vector<KernelCase> kernelCases(bool damped)
{
  std::vector<KernelCase> cases;
  for (AxialIntegration axial : {AxialIntegration::Full, AxialIntegration::Reduced, AxialIntegration::Assumed})
    for (double beamLength : {0.0, 100.0}) {
      Section sec = kSteelBox;
      sec.axialIntegration = axial;
      sec.length = beamLength;
      if (damped) sec.etaA = 1e-3, sec.etaB = 2e-3;
      for (double l : {0.25, 1e-3}) cases.push_back({sec, l});
    }
  return cases;
}

} // namespace

TEST(AncfElement, InternalForceIsEnergyGradient)
{
  std::mt19937 rng(1);
  const double l = 0.25;
  for (int trial = 0; trial < 6; ++trial) {
    const Vec8 e = deformedState(rng, l, 0.05);
    Vec8 f;
    internalForce(kSteelBox, l, e, f, nullptr);
    Vec8 fd;
    for (int k = 0; k < 8; ++k) {
      const double h = 1e-6 * ((k % 4) < 2 ? l : 1.0);
      Vec8 ep = e, em = e;
      ep[k] += h, em[k] -= h;
      fd[k] = (strainEnergy(kSteelBox, l, ep) - strainEnergy(kSteelBox, l, em)) / (2 * h);
    }
    EXPECT_LT(relErr(f, fd), 1e-6) << "trial " << trial;
  }
}

TEST(AncfElement, TangentMatchesCentralDifferences)
{
  std::mt19937 rng(2);
  const double l = 0.25;
  for (int trial = 0; trial < 8; ++trial) {
    const Vec8 e = deformedState(rng, l, trial < 4 ? 0.02 : 0.2);
    Vec8 f;
    Mat8 K;
    internalForce(kSteelBox, l, e, f, &K);
    Mat8 fd;
    for (int k = 0; k < 8; ++k) {
      const double h = 1e-7 * ((k % 4) < 2 ? l : 1.0);
      Vec8 ep = e, em = e, fp, fm;
      ep[k] += h, em[k] -= h;
      internalForce(kSteelBox, l, ep, fp, nullptr);
      internalForce(kSteelBox, l, em, fm, nullptr);
      fd.col(k) = (fp - fm) / (2 * h);
    }
    EXPECT_LT(relErr(K, fd), 1e-6) << "trial " << trial;
    EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm()) << "tangent must be symmetric";
  }
}

TEST(AncfElement, RigidMotionsGiveNoElasticForce)
{
  const double l = 0.5;
  for (double angle : {0.0, 0.3, 1.7, -2.9}) {
    const Vec8 e = straightElement(Vec2(1.3, -0.4), Vec2(std::cos(angle), std::sin(angle)), l);
    Vec8 f;
    Mat8 K;
    internalForce(kSteelBox, l, e, f, &K);
    EXPECT_LT(f.norm(), 1e-9 * kSteelBox.EA) << "angle " << angle;
    EXPECT_NEAR(strainEnergy(kSteelBox, l, e), 0.0, 1e-12);
    // Rigid translations are in the null space of the tangent of an unstrained element.
    Vec8 tx, ty;
    tx << 1, 0, 0, 0, 1, 0, 0, 0;
    ty << 0, 1, 0, 0, 0, 1, 0, 0;
    EXPECT_LT((K * tx).norm(), 1e-9 * K.norm());
    EXPECT_LT((K * ty).norm(), 1e-9 * K.norm());
  }
}

TEST(AncfElement, MassMatrixReproducesMassAndMoments)
{
  const double l = 0.7, rhoA = 31.4;
  const Mat8 M = massMatrix(rhoA, l);
  Vec8 translation, linear;
  translation << 1, 0, 0, 0, 1, 0, 0, 0;                 // r(x) = (1, 0)
  linear = straightElement(Vec2(0, 0), Vec2(1, 0), l);   // r(x) = (x, 0)
  EXPECT_NEAR(translation.dot(M * translation), rhoA * l, 1e-14 * rhoA * l);
  EXPECT_NEAR(translation.dot(M * linear), rhoA * l * l / 2, 1e-14 * rhoA * l * l);
  EXPECT_NEAR(linear.dot(M * linear), rhoA * l * l * l / 3, 1e-14 * rhoA * l * l * l);
  // Mass matrix against 5-point Gauss quadrature of rhoA S^T S (exact for degree 6).
  Mat8 Mq = Mat8::Zero();
  const double x[5] = {0.04691007703066800, 0.2307653449471585, 0.5, 0.7692346550528415, 0.9530899229693320};
  const double w[5] = {0.1184634425280945, 0.2393143352496832, 0.2844444444444444, 0.2393143352496832, 0.1184634425280945};
  for (int p = 0; p < 5; ++p) {
    const Mat28 S = shapeMatrix(x[p], l);
    Mq += w[p] * l * rhoA * S.transpose() * S;
  }
  EXPECT_LT((M - Mq).norm(), 1e-12 * M.norm());
  // Gravity is the mass matrix applied to a uniform field.
  Vec8 g8;
  g8 << 0, -9.81, 0, 0, 0, -9.81, 0, 0;
  EXPECT_LT((gravityForce(rhoA, l, Vec2(0, -9.81)) - M * g8).norm(), 1e-12 * (M * g8).norm());
}

TEST(AncfElement, ShapeFunctionDerivativesMatchDifferences)
{
  const double l = 0.3, h = 1e-6;
  for (double xi : {1e-3, 0.17, 0.5, 0.93, 1.0 - 1e-3}) {
    for (int d = 0; d < 3; ++d) {
      const Eigen::Vector4d fd = (shapeValues(xi + h, l, d) - shapeValues(xi - h, l, d)) / (2 * h * l);
      EXPECT_LT((shapeValues(xi, l, d + 1) - fd).norm(), 1e-6 * (1 + fd.norm())) << "xi " << xi << " d " << d;
    }
  }
  // Interpolation: nodal values and slopes.
  const Vec8 e = straightElement(Vec2(0.2, 0.1), Vec2(0.6, 0.8), l);
  EXPECT_LT((position(e, 0.0, l) - Vec2(0.2, 0.1)).norm(), 1e-15);
  EXPECT_LT((position(e, 1.0, l) - Vec2(0.2 + 0.6 * l, 0.1 + 0.8 * l)).norm(), 1e-15);
  EXPECT_LT((position(e, 0.4, l, 1) - Vec2(0.6, 0.8)).norm(), 1e-14);
}

TEST(AncfElement, CurvatureOfACircularArc)
{
  // Nodes on a circle of radius R with tangent slopes: K ~ 1/R, eps ~ 0 for small arcs.
  const double R = 2.0, l = 0.05, phi = l / R;
  Vec8 e;
  e << R, 0, 0, 1, R * std::cos(phi), R * std::sin(phi), -std::sin(phi), std::cos(phi);
  EXPECT_NEAR(curvature(e, 0.5, l), 1.0 / R, 1e-4 / R);
  EXPECT_NEAR(axialStrain(e, 0.5, l), 0.0, 1e-5);
}

// The residual's force-only path (scalar code, no tangent) must give the
// force of the general path with the tangent bit for bit: the stored scene
// digests (rtol 1e-9) and every restart rely on the residual not depending on
// whether a Jacobian is formed with it. All three axial treatments, Assumed
// both slender (projection active) and stocky (gamma = 1, no projection),
// small and large deformations, two element lengths.
TEST(AncfElement, ForceOnlyPathIsBitIdentical)
{
  std::mt19937 rng(7);
  for (const KernelCase &c : kernelCases(false)) {
      const Section &sec = c.sec;
      const double l = c.l, beamLength = sec.length;
      const AxialIntegration axial = sec.axialIntegration;
        for (int trial = 0; trial < 50; ++trial) {
          const Vec8 e = deformedState(rng, l, trial % 2 ? 0.2 : 1e-4);
          Vec8 fOnly, fWithTangent;
          Mat8 K;
          internalForce(sec, l, e, fOnly, nullptr);
          internalForce(sec, l, e, fWithTangent, &K);
          for (int k = 0; k < 8; ++k)
            EXPECT_EQ(fOnly[k], fWithTangent[k]) << "axial " << static_cast<int>(axial) << ", L " << beamLength
                                                 << ", l " << l << ", trial " << trial << ", entry " << k;
        }
    }
  // Aliasing: the force may overwrite the state it is computed from.
  Vec8 e = deformedState(rng, 0.25, 0.1), f;
  internalForce(kSteelBox, 0.25, e, f, nullptr);
  internalForce(kSteelBox, 0.25, e, e, nullptr);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(e[k], f[k]);
}

// The batched force kernel (one element per SIMD lane, the residual of a
// long beam) must give every element's force-only internalForce bit for
// bit, for the same cases as above, with the lanes' states drawn at very
// different sizes (so that no lane's rounding is tied to another's), and
// with a lane whose force overwrites its state.
TEST(AncfElement, BatchedForceIsBitIdentical)
{
  std::mt19937 rng(13);
  for (const KernelCase &c : kernelCases(false)) {
      const Section &sec = c.sec;
      const double l = c.l, beamLength = sec.length;
      const AxialIntegration axial = sec.axialIntegration;
        for (int trial = 0; trial < 50; ++trial) {
          Vec8 e[kForceBatch], f[kForceBatch], expected[kForceBatch];
          const double *ep[kForceBatch];
          double *fp[kForceBatch];
          for (int j = 0; j < kForceBatch; ++j) {
            e[j] = deformedState(rng, l, (trial + j) % 2 ? 0.2 : 1e-4 * (j + 1));
            internalForce(sec, l, e[j], expected[j], nullptr);
            ep[j] = e[j].data(), fp[j] = f[j].data();
          }
          if (trial == 0) fp[1] = e[1].data(); // lane 1 in place
          internalForceBatch(sec, l, ep, fp);
          for (int j = 0; j < kForceBatch; ++j)
            for (int k = 0; k < 8; ++k)
              EXPECT_EQ(fp[j][k], expected[j][k]) << "axial " << static_cast<int>(axial) << ", L " << beamLength
                                                  << ", l " << l << ", trial " << trial << ", lane " << j
                                                  << ", entry " << k;
        }
    }
}

// The batched damped kernel (one element per SIMD lane, the residual of a
// damped beam's elements) must give every element's internalAndDampingForce
// bit for bit (memcmp: the sign of zeros too), forces and power, for the
// same cases as above, with lanes at very different sizes and rates, a lane
// at rest (edot = 0) and lanes whose forces overwrite their state or rate.
TEST(AncfElement, BatchedDampedForceIsBitIdentical)
{
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const KernelCase &c : kernelCases(true)) {
      const Section &sec = c.sec;
      const double l = c.l, beamLength = sec.length;
      const AxialIntegration axial = sec.axialIntegration;
        for (int trial = 0; trial < 50; ++trial) {
          Vec8 e[kForceBatch], edot[kForceBatch], f[kForceBatch], fd[kForceBatch], expF[kForceBatch],
              expFd[kForceBatch];
          double power[kForceBatch], expPower[kForceBatch];
          const double *ep[kForceBatch], *vp[kForceBatch];
          double *fp[kForceBatch], *fdp[kForceBatch];
          for (int j = 0; j < kForceBatch; ++j) {
            e[j] = deformedState(rng, l, (trial + j) % 2 ? 0.2 : 1e-4 * (j + 1));
            for (int k = 0; k < 8; ++k) edot[j][k] = j == 2 && trial % 5 == 0 ? 0.0 : u(rng) * std::exp(4 * u(rng));
            expPower[j] = internalAndDampingForce(sec, l, e[j], edot[j], expF[j], expFd[j]);
            ep[j] = e[j].data(), vp[j] = edot[j].data(), fp[j] = f[j].data(), fdp[j] = fd[j].data();
          }
          if (trial == 0) fp[1] = e[1].data(), fdp[3] = edot[3].data(); // in place
          internalAndDampingForceBatch(sec, l, ep, vp, fp, fdp, power);
          for (int j = 0; j < kForceBatch; ++j) {
            EXPECT_EQ(std::memcmp(&power[j], &expPower[j], sizeof(double)), 0)
                << "axial " << static_cast<int>(axial) << ", L " << beamLength << ", l " << l << ", trial " << trial
                << ", lane " << j << ": " << power[j] << " vs " << expPower[j];
            EXPECT_EQ(std::memcmp(fp[j], expF[j].data(), 8 * sizeof(double)), 0)
                << "force, axial " << static_cast<int>(axial) << ", trial " << trial << ", lane " << j;
            EXPECT_EQ(std::memcmp(fdp[j], expFd[j].data(), 8 * sizeof(double)), 0)
                << "damping force, axial " << static_cast<int>(axial) << ", trial " << trial << ", lane " << j;
          }
        }
    }
}

// The damped residual's one-pass kernel must give internalForce's force,
// dampingForce's force and dampingForce's dissipated power bit for bit: the
// element keeps its force and power for the energy diagnostics of the state
// Newton ends on (BeamElementItem::dampingAt), which would otherwise call
// dampingForce, and the energy balance and the digests must not depend on
// which of the two computed them.
TEST(AncfElement, InternalAndDampingForceIsBitIdentical)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> rate(-1.0, 1.0);
  for (const KernelCase &c : kernelCases(true)) {
      const Section &sec = c.sec;
      const double l = c.l, beamLength = sec.length;
      const AxialIntegration axial = sec.axialIntegration;
        for (int trial = 0; trial < 50; ++trial) {
          const Vec8 e = deformedState(rng, l, trial % 2 ? 0.2 : 1e-4);
          Vec8 edot;
          for (int k = 0; k < 8; ++k) edot[k] = rate(rng);
          Vec8 f1, fd1, f2, fd2;
          const double p1 = internalAndDampingForce(sec, l, e, edot, f1, fd1);
          internalForce(sec, l, e, f2, nullptr);
          const double p2 = dampingForce(sec, l, e, edot, fd2, nullptr, nullptr);
          EXPECT_EQ(p1, p2) << "axial " << static_cast<int>(axial) << ", L " << beamLength << ", l " << l;
          for (int k = 0; k < 8; ++k) {
            EXPECT_EQ(f1[k], f2[k]) << "axial " << static_cast<int>(axial) << ", entry " << k;
            EXPECT_EQ(fd1[k], fd2[k]) << "axial " << static_cast<int>(axial) << ", entry " << k;
          }
        }
    }
}
