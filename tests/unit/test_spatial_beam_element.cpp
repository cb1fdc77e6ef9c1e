// Spatial ANCF beam element with twist (docs/model.md §1.7): the kinematics
// (triad, strains as the triad's rotation rates, derivatives of the section
// frame), the internal and damping forces and their Jacobians against central
// differences at random deformed and twisted states for every axial-strain
// treatment, zero force and power in rigid motions, and objectivity.
#include "boomdyn/spatial_beam_element.hpp"
#include "spatial_beam_states.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace boomdyn;
using namespace boomdyn::spatial_beam;
using namespace boomdyn::spatial_beam::states;

namespace {

const AxialIntegration kAxialOptions[] = {AxialIntegration::Full, AxialIntegration::Reduced,
                                          AxialIntegration::Assumed};

Vec14 force(const Section &sec, const Geometry &geo, const Vec14 &e)
{
  Vec14 f;
  internalForce(sec, geo, e, f, nullptr);
  return f;
}

Vec14 damping(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 &v)
{
  Vec14 f;
  dampingForce(sec, geo, e, v, f, nullptr, nullptr);
  return f;
}

} // namespace

TEST(SpatialBeamKinematics, TriadIsOrthonormalAndEqualsTheNodeTriadsAtTheEnds)
{
  std::mt19937 rng(1);
  for (int trial = 0; trial < 10; ++trial) {
    const State s = deformedState(rng, 0.5, 0.2, 2.0);
    for (double xi : {0.0, 0.3, 1.0}) {
      const SectionFrame f = sectionFrame(s.geo, s.e, xi);
      EXPECT_LT((f.d.transpose() * f.d - Mat3::Identity()).norm(), 1e-14);
      EXPECT_NEAR(f.d.determinant(), 1.0, 1e-14);
      const Vec3 r1 = ancf::shapeValues(xi, s.geo.l, 1)[0] * s.e.segment<3>(0) +
                      ancf::shapeValues(xi, s.geo.l, 1)[1] * s.e.segment<3>(3) +
                      ancf::shapeValues(xi, s.geo.l, 1)[2] * s.e.segment<3>(7) +
                      ancf::shapeValues(xi, s.geo.l, 1)[3] * s.e.segment<3>(10);
      EXPECT_LT((f.d.col(0) - r1.normalized()).norm(), 1e-14);
    }
    for (int a = 0; a < 2; ++a) {
      const Mat3 node = nodeTriad(s.geo.node[a], s.e.segment<3>(slopeIndex(a)), s.e[twistIndex(a)]);
      EXPECT_LT((sectionFrame(s.geo, s.e, a).d - node).norm(), 1e-13) << "node " << a;
    }
  }
}

// The torsion and curvatures are the components, in the section frame, of
// the triad's rotation rate along x: Omega = 1/2 sum_j d_j x d_j,x, taken here
// by central differences of the triad in xi.
TEST(SpatialBeamKinematics, StrainsAreTheTriadsRotationRates)
{
  std::mt19937 rng(2);
  for (int trial = 0; trial < 10; ++trial) {
    const State s = deformedState(rng, 0.5, 0.3, 2.0);
    for (double xi : {0.1, 0.5, 0.83}) {
      const double h = 1e-5;
      const Mat3 d = sectionFrame(s.geo, s.e, xi).d;
      const Mat3 dx = (sectionFrame(s.geo, s.e, xi + h).d - sectionFrame(s.geo, s.e, xi - h).d) / (2 * h * s.geo.l);
      Vec3 omega = Vec3::Zero();
      for (int j = 0; j < 3; ++j) omega += 0.5 * d.col(j).cross(dx.col(j));
      const Strains k = strainsAt(s.geo, s.e, xi);
      const Vec3 expected = d.transpose() * omega;
      EXPECT_LT((Vec3(k.torsion, k.curvature2, k.curvature3) - expected).norm(), 1e-8 * (1 + expected.norm()))
          << "trial " << trial << " xi " << xi;
    }
  }
}

TEST(SpatialBeamKinematics, SectionFrameDerivativesMatchCentralDifferences)
{
  std::mt19937 rng(3);
  for (int trial = 0; trial < 6; ++trial) {
    const State s = deformedState(rng, 0.5, 0.2, 2.0);
    const double xi = 0.37;
    const SectionFrame f = sectionFrame(s.geo, s.e, xi);
    const Vec3 w(0.3, -1.1, 0.7);
    for (int i = 0; i < 3; ++i) {
      Mat3x14 fdGrad, fdR;
      Mat14 fdHess;
      for (int k = 0; k < kCoordinates; ++k) {
        const double h = 1e-6 * coordinateScale(k, s.geo.l);
        Vec14 ep = s.e, em = s.e;
        ep[k] += h, em[k] -= h;
        const SectionFrame p = sectionFrame(s.geo, ep, xi), m = sectionFrame(s.geo, em, xi);
        fdGrad.col(k) = (p.d.col(i) - m.d.col(i)) / (2 * h);
        fdR.col(k) = (p.r - m.r) / (2 * h);
        fdHess.col(k) = (p.dGrad[i].transpose() * w - m.dGrad[i].transpose() * w) / (2 * h);
      }
      EXPECT_LT(relErr(f.dGrad[i], fdGrad), 1e-8) << "director " << i;
      EXPECT_LT(relErr(f.rGrad, fdR), 1e-10);
      const Mat14 H = sectionFrameHessian(s.geo, s.e, xi, i, w);
      EXPECT_LT(relErr(H, fdHess), 1e-6) << "director " << i;
      EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
    }
  }
}

// A moment M on a section does the work M . delta psi, delta psi = 1/2 sum_i
// d_i x delta d_i: Q . de equals that with delta d_i by central differences
// of the triad along random de; dQ/de against central differences of Q.
TEST(SpatialBeamKinematics, SectionMomentForceIsWorkConjugateToTheSectionRotation)
{
  std::mt19937 rng(9);
  for (int trial = 0; trial < 6; ++trial) {
    const State s = deformedState(rng, 0.5, 0.2, 2.0);
    const double xi = trial % 2 ? 1.0 : 0.42;
    const Vec3 M(1.5, -0.7, 2.2);
    Vec14 Q;
    Mat14 dQ;
    sectionMomentForce(s.geo, s.e, xi, M, Q, &dQ);
    const Vec14 de = randomVelocity(rng, s.geo.l, 1.0);
    const double h = 1e-6;
    const Mat3 dp = sectionFrame(s.geo, s.e + h * de, xi).d, dm = sectionFrame(s.geo, s.e - h * de, xi).d;
    const Mat3 d = sectionFrame(s.geo, s.e, xi).d;
    Vec3 psi = Vec3::Zero();
    for (int i = 0; i < 3; ++i) psi += 0.5 * d.col(i).cross((dp.col(i) - dm.col(i)) / (2 * h));
    EXPECT_NEAR(Q.dot(de), M.dot(psi), 1e-8 * M.norm() * psi.norm()) << "trial " << trial;
    Mat14 fdQ;
    for (int k = 0; k < kCoordinates; ++k) {
      const double hk = 1e-6 * coordinateScale(k, s.geo.l);
      Vec14 ep = s.e, em = s.e, Qp, Qm;
      ep[k] += hk, em[k] -= hk;
      sectionMomentForce(s.geo, ep, xi, M, Qp, nullptr);
      sectionMomentForce(s.geo, em, xi, M, Qm, nullptr);
      fdQ.col(k) = (Qp - Qm) / (2 * hk);
    }
    EXPECT_LT(relErr(dQ, fdQ), 1e-6) << "trial " << trial;
  }
}

TEST(SpatialBeamKinematics, RebasingTheReferenceChangesNoStrain)
{
  std::mt19937 rng(4);
  const Section sec = steelBox(AxialIntegration::Assumed);
  for (int trial = 0; trial < 5; ++trial) {
    const State s = deformedState(rng, 0.5, 0.3, 2.0);
    Geometry rebased = s.geo;
    for (int a = 0; a < 2; ++a) rebased.node[a] = rebasedNodeFrame(s.geo.node[a], s.e.segment<3>(slopeIndex(a)));
    const double U = strainEnergy(sec, s.geo, s.e);
    EXPECT_NEAR(strainEnergy(sec, rebased, s.e), U, 1e-12 * U);
    for (double xi : {0.0, 0.6, 1.0})
      EXPECT_LT((sectionFrame(rebased, s.e, xi).d - sectionFrame(s.geo, s.e, xi).d).norm(), 1e-13);
  }
}

TEST(SpatialBeamElement, ForceIsTheEnergyGradientAndTangentMatchesCentralDifferences)
{
  for (const AxialIntegration axial : kAxialOptions) {
    const Section sec = steelBox(axial);
    std::mt19937 rng(5);
    for (int trial = 0; trial < 6; ++trial) {
      const double l = trial < 3 ? 0.25 : 0.8;
      const State s = deformedState(rng, l, trial % 3 == 0 ? 0.02 : 0.2, 3.0);
      Vec14 f;
      Mat14 K;
      internalForce(sec, s.geo, s.e, f, &K);
      Vec14 fdU;
      Mat14 fdK;
      for (int k = 0; k < kCoordinates; ++k) {
        const double h = 1e-6 * coordinateScale(k, l);
        Vec14 ep = s.e, em = s.e;
        ep[k] += h, em[k] -= h;
        fdU[k] = (strainEnergy(sec, s.geo, ep) - strainEnergy(sec, s.geo, em)) / (2 * h);
        fdK.col(k) = (force(sec, s.geo, ep) - force(sec, s.geo, em)) / (2 * h);
      }
      EXPECT_LT(relErr(f, fdU), 1e-6) << "axial " << int(axial) << " trial " << trial;
      // The residual path (first-order jets) gives the force of the tangent path (second-order jets).
      EXPECT_LT(relErr(force(sec, s.geo, s.e), f), 1e-14);
      EXPECT_LT(relErr(K, fdK), 1e-6) << "axial " << int(axial) << " trial " << trial;
      EXPECT_LT((K - K.transpose()).norm(), 1e-14 * K.norm());
    }
  }
}

TEST(SpatialBeamElement, DampingJacobiansMatchCentralDifferences)
{
  for (const AxialIntegration axial : kAxialOptions) {
    const Section sec = steelBox(axial);
    std::mt19937 rng(6);
    for (int trial = 0; trial < 5; ++trial) {
      const double l = 0.4;
      const State s = deformedState(rng, l, 0.2, 3.0);
      const Vec14 v = randomVelocity(rng, l, 2.0 / l);
      Vec14 fd;
      Mat14 Kq, Dv;
      const double power = dampingForce(sec, s.geo, s.e, v, fd, &Kq, &Dv);
      Mat14 fdQ, fdV;
      for (int k = 0; k < kCoordinates; ++k) {
        const double hq = 1e-6 * coordinateScale(k, l), hv = 1e-3 * coordinateScale(k, l);
        Vec14 ep = s.e, em = s.e, vp = v, vm = v;
        ep[k] += hq, em[k] -= hq, vp[k] += hv, vm[k] -= hv;
        fdQ.col(k) = (damping(sec, s.geo, ep, v) - damping(sec, s.geo, em, v)) / (2 * hq);
        fdV.col(k) = (damping(sec, s.geo, s.e, vp) - damping(sec, s.geo, s.e, vm)) / (2 * hv);
      }
      EXPECT_LT(relErr(Kq, fdQ), 1e-6) << "axial " << int(axial) << " trial " << trial;
      EXPECT_LT(relErr(Dv, fdV), 1e-9) << "axial " << int(axial) << " trial " << trial;
      EXPECT_LT((Dv - Dv.transpose()).norm(), 1e-14 * Dv.norm());
      EXPECT_LT(relErr(fd, Dv * v), 1e-12);
      Vec14 fdResidual;
      Mat14 DvResidual;
      dampingForce(sec, s.geo, s.e, v, fdResidual, nullptr, &DvResidual); // first-order path
      EXPECT_LT(relErr(fdResidual, fd), 1e-14);
      EXPECT_LT(relErr(DvResidual, Dv), 1e-14);
      // One pass for both: the same values as the two calls, bit for bit.
      Vec14 f1, f2, fd2;
      Mat14 K1, K2, Kq2, Dv2;
      internalForce(sec, s.geo, s.e, f1, &K1);
      EXPECT_EQ(internalAndDampingForce(sec, s.geo, s.e, v, f2, &K2, fd2, &Kq2, &Dv2), power);
      EXPECT_EQ(f2, f1);
      EXPECT_EQ(K2, K1);
      EXPECT_EQ(fd2, fd);
      EXPECT_EQ(Kq2, Kq);
      EXPECT_EQ(Dv2, Dv);
      internalAndDampingForce(sec, s.geo, s.e, v, f2, nullptr, fd2, nullptr, nullptr);
      EXPECT_EQ(f2, force(sec, s.geo, s.e));
      EXPECT_EQ(fd2, fdResidual);
      EXPECT_NEAR(power, v.dot(fd), 1e-12 * std::abs(power));
      EXPECT_GT(power, 0.0);
    }
  }
}

// Rigid motions: a straight untwisted element anywhere, in any orientation,
// spun about its axis with equal nodal twists, carries no elastic force;
// a deformed twisted element moved rigidly (translation, rotation about any
// axis, with the twist rates that turn its sections along) has zero strain
// rates: no damping force, no power of the elastic force.
TEST(SpatialBeamElement, RigidMotionsGiveNoForceAndNoPower)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const AxialIntegration axial : kAxialOptions) {
    const Section sec = steelBox(axial);
    for (int trial = 0; trial < 5; ++trial) {
      const double l = 0.5;
      const Mat3 R = randomRotation(rng, 3.1);
      const Geometry geo = straightGeometry(Mat3::Identity(), l);
      // The straight element rotated by R, its references fixed, then spun by psi about its axis.
      State s{geo, straightElement(Vec3(u(rng), u(rng), u(rng)), Mat3::Identity(), l)};
      s.e = rotatedWithFixedReferences(s, R);
      const double psi = 3.0 * u(rng);
      s.e[twistIndex(0)] += psi, s.e[twistIndex(1)] += psi;
      const Vec14 f = force(sec, s.geo, s.e);
      EXPECT_LT(f.norm(), 1e-6 * sec.GJ / l) << "axial " << int(axial) << " trial " << trial; // N; EA ~ 3e9 N
      EXPECT_LT(strainEnergy(sec, s.geo, s.e), 1e-18 * sec.EA * l);
      // Spin rate about the axis alone: no strain rate.
      Vec14 spin = Vec14::Zero();
      spin[twistIndex(0)] = spin[twistIndex(1)] = 5.0;
      Vec14 fd;
      EXPECT_LT(dampingForce(sec, s.geo, s.e, spin, fd, nullptr, nullptr), 1e-20);
      EXPECT_LT(fd.norm(), 1e-12 * sec.GJ);

      const State d = deformedState(rng, l, 0.2, 2.0);
      const Vec3 w(u(rng), u(rng), u(rng)), v(u(rng), u(rng), u(rng));
      const Vec14 edot = rigidVelocity(d, 3.0 * w, v);
      const Vec14 fe = force(sec, d.geo, d.e);
      EXPECT_LT(std::abs(fe.dot(edot)), 1e-10 * fe.norm() * edot.norm()) << "elastic power";
      Vec14 fdd;
      const double power = dampingForce(sec, d.geo, d.e, edot, fdd, nullptr, nullptr);
      const double scale = dampingForce(sec, d.geo, d.e, randomVelocity(rng, l, 3.0), fd, nullptr, nullptr);
      EXPECT_LT(power, 1e-20 * scale);
      EXPECT_LT(fdd.norm(), 1e-10 * fd.norm());
    }
  }
}

// Objectivity: a state rotated as a whole by a large rotation about an
// arbitrary axis, its node references with it, has the same energy and the
// rotated force and tangent; with the references held fixed (the twists
// recomputed for the rotated sections) the same energy.
TEST(SpatialBeamElement, RotatedStateHasTheRotatedForce)
{
  std::mt19937 rng(8);
  for (const AxialIntegration axial : kAxialOptions) {
    const Section sec = steelBox(axial);
    for (int trial = 0; trial < 5; ++trial) {
      const State s = deformedState(rng, 0.5, 0.2, 3.0);
      const Mat3 R = randomRotation(rng, 3.1);
      const Mat14 T = rotationOfCoordinates(R);
      State r = s;
      for (auto &node : r.geo.node) node.tangent = R * node.tangent, node.normal = R * node.normal;
      r.e = T * s.e;
      Vec14 f, fr;
      Mat14 K, Kr;
      internalForce(sec, s.geo, s.e, f, &K);
      internalForce(sec, r.geo, r.e, fr, &Kr);
      const double U = strainEnergy(sec, s.geo, s.e);
      EXPECT_NEAR(strainEnergy(sec, r.geo, r.e), U, 1e-10 * U);
      EXPECT_LT(relErr(fr, T * f), 1e-10) << "axial " << int(axial) << " trial " << trial;
      EXPECT_LT(relErr(Kr, T * K * T.transpose()), 1e-10);
      // The same rotation with the references fixed: a different chart of the same state.
      const Vec14 eFixed = rotatedWithFixedReferences(s, R);
      EXPECT_NEAR(strainEnergy(sec, s.geo, eFixed), U, 1e-10 * U);
    }
  }
}

TEST(SpatialBeamElement, MassMatrixCarriesTheMassAndTheRotaryInertia)
{
  const Section sec = steelBox(AxialIntegration::Assumed);
  const double l = 0.7;
  const Mat14 M = massMatrix(sec, l);
  EXPECT_LT((M - M.transpose()).norm(), 1e-15 * M.norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat14>(M).eigenvalues().minCoeff(), 0.0);
  // A translation by unit speed in each direction: kinetic energy 1/2 m.
  for (int d = 0; d < 3; ++d) {
    const Vec14 v = rigidVelocity({straightGeometry(Mat3::Identity(), l), straightElement(Vec3::Zero(), Mat3::Identity(), l)},
                                  Vec3::Zero(), Vec3::Unit(d));
    EXPECT_NEAR(v.dot(M * v), sec.rhoA * l, 1e-13 * sec.rhoA * l);
  }
  // A uniform spin about the axis: 1/2 rhoIp l omega^2.
  Vec14 spin = Vec14::Zero();
  spin[twistIndex(0)] = spin[twistIndex(1)] = 1.0;
  EXPECT_NEAR(spin.dot(M * spin), sec.rhoIp * l, 1e-13 * sec.rhoIp * l);
  // Gravity is the mass matrix applied to a uniform acceleration.
  const Vec3 g(0.3, -9.81, 1.2);
  const Vec14 a = rigidVelocity({straightGeometry(Mat3::Identity(), l), straightElement(Vec3::Zero(), Mat3::Identity(), l)},
                                Vec3::Zero(), g);
  EXPECT_LT(relErr(gravityForce(sec, l, g), M * a), 1e-14);
}

TEST(SpatialBeamSection, BoxSectionUsesBredtsTorsionConstant)
{
  // A square box of side b and wall t: J = b^3 t (3/4 of the polar moment 4/3 b^3 t).
  const double b = 0.3, t = 0.01;
  const Section s = boxSection(1.0, 1.0, 1.0, b, b, t);
  EXPECT_NEAR(s.GJ, b * b * b * t, 1e-15);
  EXPECT_NEAR(s.rhoIp, 4.0 / 3.0 * b * b * b * t, 1e-15);
  EXPECT_NEAR(s.EIy, 2.0 / 3.0 * b * b * b * t, 1e-15);
  EXPECT_NEAR(s.EA, 4 * b * t, 1e-15);
}

// The Assumed axial strain's pointwise weight gamma = min(1, 1e4 min(EIy, EIz)
// / (EA L^2)): a stocky beam (gamma = 1) is the Full element exactly, a
// slender one differs where the strain is not linear along the element.
TEST(SpatialBeamElement, AssumedAxialStrainIsFullForStockyBeams)
{
  std::mt19937 rng(10);
  Section full = steelBox(AxialIntegration::Full), assumed = steelBox(AxialIntegration::Assumed);
  full.length = assumed.length = 5.0; // EA L^2 / EI ~ 1.6e3
  EXPECT_EQ(assumedPointwiseWeight(assumed, 0.5), 1.0);
  const State s = deformedState(rng, 0.5, 0.2, 2.0);
  EXPECT_EQ(strainEnergy(assumed, s.geo, s.e), strainEnergy(full, s.geo, s.e));
  Vec14 fa, ff;
  Mat14 Ka, Kf;
  internalForce(assumed, s.geo, s.e, fa, &Ka);
  internalForce(full, s.geo, s.e, ff, &Kf);
  EXPECT_EQ(fa, ff);
  EXPECT_EQ(Ka, Kf);
  assumed.length = 100.0;
  const double gamma = assumedPointwiseWeight(assumed, 0.5);
  EXPECT_NEAR(gamma, 1e4 * std::min(assumed.EIy, assumed.EIz) / (assumed.EA * 1e4), 1e-15);
  EXPECT_LT(gamma, 0.1);
  EXPECT_GT(std::abs(strainEnergy(assumed, s.geo, s.e) / strainEnergy(full, s.geo, s.e) - 1), 1e-6);
}

// The structured kernels (spatial_beam_forces.cpp: closed-form angle and axial
// strain, 9-variable jets per Gauss point, block-mapped Hessians) equal the
// 12-variable jets carried through every operation (namespace reference) to
// round-off: forces, tangents and both damping blocks, through every entry
// point, at random deformed and twisted states, for every axial treatment
// (Assumed both with the projection, gamma < 1, and without, gamma = 1).
TEST(SpatialBeamElement, StructuredKernelsEqualTheJetOracle)
{
  const double kTol = 1e-12;
  double worst = 0;
  for (const AxialIntegration axial : kAxialOptions)
    for (const double beamLength : {100.0, 5.0}) {
      Section sec = steelBox(axial);
      sec.length = beamLength;
      std::mt19937 rng(11);
      for (int trial = 0; trial < 8; ++trial) {
        const double l = trial < 4 ? 0.25 : 0.8;
        const State s = deformedState(rng, l, trial % 2 == 0 ? 0.02 : 0.3, 3.0);
        const Vec14 v = randomVelocity(rng, l, 2.0);
        Vec14 f, fr, fd, fdr, fa, fda, fb, fdb;
        Mat14 K, Kr, Kq, Kqr, Dv, Dvr, Ka, Kqa, Dva;
        internalForce(sec, s.geo, s.e, f, &K);
        reference::internalForce(sec, s.geo, s.e, fr, &Kr);
        const double power = dampingForce(sec, s.geo, s.e, v, fd, &Kq, &Dv);
        const double powerRef = reference::dampingForce(sec, s.geo, s.e, v, fdr, &Kqr, &Dvr);
        const double powerBoth = internalAndDampingForce(sec, s.geo, s.e, v, fa, &Ka, fda, &Kqa, &Dva);
        const double errors[] = {relErr(f, fr),   relErr(K, Kr),    relErr(fd, fdr),
                                 relErr(Kq, Kqr), relErr(Dv, Dvr),  std::abs(power / powerRef - 1),
                                 relErr(fa, fr),  relErr(Ka, Kr),   relErr(fda, fdr),
                                 relErr(Kqa, Kqr), relErr(Dva, Dvr), std::abs(powerBoth / powerRef - 1)};
        for (const double err : errors) {
          EXPECT_LT(err, kTol) << "axial " << int(axial) << " length " << beamLength << " trial " << trial;
          worst = std::max(worst, err);
        }
        // The first-order paths (no Hessians): residual force, damping force and Dv.
        Mat14 DvResidual;
        internalForce(sec, s.geo, s.e, fb, nullptr);
        dampingForce(sec, s.geo, s.e, v, fdb, nullptr, &DvResidual);
        EXPECT_LT(relErr(fb, fr), kTol);
        EXPECT_LT(relErr(fdb, fdr), kTol);
        EXPECT_LT(relErr(DvResidual, Dvr), kTol);
        internalAndDampingForce(sec, s.geo, s.e, v, fb, nullptr, fdb, nullptr, nullptr);
        EXPECT_LT(relErr(fb, fr), kTol);
        EXPECT_LT(relErr(fdb, fdr), kTol);
      }
    }
  std::printf("largest relative difference structured vs jet kernels: %.2e\n", worst);
}
