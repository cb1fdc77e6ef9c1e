// Spatial kernels against central finite differences at random states:
// Euler-parameter rotation and its derivatives, the spatial rigid body's
// inertia (mass, damping-like gyroscopic and stiffness-like blocks of the
// Newton matrix), the Euler normalization row, the spatial joints and
// drives (C_q, the multiplier-weighted Hessian and gamma, body-ground and
// body-body), point loads (fixed, follower, moments) and point masses with
// rotary inertia.
#include "spatial_test_frames.hpp"
#include "boomdyn/euler_parameters.hpp"
#include "boomdyn/spatial_ancf_beam.hpp"
#include "boomdyn/spatial_joint.hpp"
#include "boomdyn/spatial_point_load.hpp"
#include "boomdyn/spatial_rigid_body.hpp"
#include "constraint_derivative_check.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace boomdyn;

using spatial_test::axesOf;

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Mat3 someInertia()
{
  Mat3 J;
  J << 2.0, 0.1, -0.2, 0.1, 3.0, 0.15, -0.2, 0.15, 4.0;
  return J;
}

// Two rigid bodies with offsets of the centre of mass, at general orientations.
struct TwoBodies {
  SpatialRigidBody a{"a", 2.0, 3.0, someInertia(), Vec3(0.8, 0.1, -0.05), Vec3(0.1, 0.2, 0.3),
                     axesOf(Vec3(1, 0.3, 0.2), Vec3(0, 1, 0.4)), 0};
  SpatialRigidBody b{"b", 1.5, 2.0, someInertia(), Vec3(0.7, 0, 0), Vec3(-0.4, 0.5, 0.1),
                     axesOf(Vec3(-0.2, 1, 0.5), Vec3(0.3, 0, 1)), 7};
  std::vector<double> q0 = std::vector<double>(14);
  TwoBodies()
  {
    a.initialCoordinates(q0.data());
    b.initialCoordinates(q0.data() + 7);
  }
};

// A random state near q0 whose Euler parameters are off the unit sphere by a
// few percent (the Jacobians must hold off it as well).
constexpr double kSpread = 0.3;

std::vector<double> randomState(const std::vector<PetscInt> &dofs, const std::vector<double> &q0, std::mt19937 &rng)
{
  return boomdyn::testing::randomNear(dofs, q0, rng, kSpread);
}

void checkConstraint(const Constraint &c, const std::vector<double> &q0, unsigned seed)
{
  boomdyn::testing::checkConstraintDerivatives(c, q0, seed, kSpread);
}

// The Newton blocks of a work item: d(residual)/dq, /dv, /da by central
// differences, each against evaluate() with the one coefficient set.
void checkItem(const WorkItem &item, const std::vector<double> &q0, unsigned seed, double tolerance = 1e-6)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<PetscInt> dofs;
  item.coordinates(dofs);
  const int n = static_cast<int>(dofs.size());
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> q = randomState(dofs, q0, rng), v(n), a(n);
    for (auto *vec : {&v, &a})
      for (double &x : *vec) x = u(rng);
    AssemblyContext ctx;
    ctx.t = 0.3;
    auto residual = [&](const std::vector<double> &qq, const std::vector<double> &vv, const std::vector<double> &aa) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
      ItemValues in{qq.data(), vv.data(), aa.data(), nullptr};
      item.evaluate(ctx, in, r.data(), nullptr);
      return r;
    };
    const Kinematics blocks[3] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    for (int which = 0; which < 3; ++which) {
      ctx.kin = blocks[which];
      RowMajor J = RowMajor::Zero(n, n);
      Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
      ItemValues in{q.data(), v.data(), a.data(), nullptr};
      item.evaluate(ctx, in, r.data(), J.data());
      Eigen::MatrixXd fd(n, n);
      const double h = 1e-6;
      for (int j = 0; j < n; ++j) {
        auto plus = std::vector<std::vector<double>>{q, v, a}, minus = plus;
        plus[which][j] += h, minus[which][j] -= h;
        fd.col(j) = (residual(plus[0], plus[1], plus[2]) - residual(minus[0], minus[1], minus[2])) / (2 * h);
      }
      EXPECT_LT((Eigen::MatrixXd(J) - fd).norm(), tolerance * (1.0 + fd.norm()))
          << item.name() << " block " << "qva"[which] << "\n" << Eigen::MatrixXd(J) - fd;
    }
  }
}

} // namespace

TEST(EulerParameters, RotationDerivativesAndRoundTrip)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    euler::Vec4 p(u(rng), u(rng), u(rng), u(rng));
    const Vec3 w(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const double h = 1e-6;
    Eigen::Matrix<double, 3, 4> fd;
    Eigen::Matrix4d fdH;
    for (int j = 0; j < 4; ++j) {
      euler::Vec4 pp = p, pm = p;
      pp[j] += h, pm[j] -= h;
      fd.col(j) = (euler::rotation(pp) * c - euler::rotation(pm) * c) / (2 * h);
      fdH.col(j) = (euler::rotationDerivative(pp, c).transpose() * w - euler::rotationDerivative(pm, c).transpose() * w) /
                   (2 * h);
    }
    EXPECT_LT((euler::rotationDerivative(p, c) - fd).norm(), 1e-8);
    EXPECT_LT((euler::rotationHessian(w, c) - fdH).norm(), 1e-8);
    p.normalize();
    const Mat3 R = euler::rotation(p);
    EXPECT_LT((R.transpose() * R - Mat3::Identity()).norm(), 1e-14);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
    const euler::Vec4 back = euler::fromRotation(R);
    EXPECT_LT(std::min((back - p).norm(), (back + p).norm()), 1e-14);
    // omega = 2 E(p) pdot is the rate of R: dR/dt = [omega]x R.
    const euler::Vec4 pd(u(rng), u(rng), u(rng), u(rng));
    const euler::Vec4 pdot = pd - pd.dot(p) * p; // tangent to |p| = 1
    const Mat3 Rdot = (euler::rotation(p + h * pdot) - euler::rotation(p - h * pdot)) / (2 * h);
    EXPECT_LT((Rdot - euler::skew(2.0 * euler::globalRateMatrix(p) * pdot) * R).norm(), 1e-8);
  }
}

TEST(SpatialRigidBody, InertiaBlocksMatchFiniteDifferences)
{
  TwoBodies bodies;
  SpatialRigidInertia item(bodies.a, Vec3(0.5, -9.81, 1.0));
  checkItem(item, bodies.q0, 21);
}

TEST(SpatialRigidBody, SampleDerivativesMatchFiniteDifferences)
{
  TwoBodies bodies;
  std::mt19937 rng(5);
  const SpatialLocation loc = bodies.a.locate(1.3);
  std::vector<PetscInt> dofs(loc.dofs.begin(), loc.dofs.begin() + loc.count);
  const std::vector<double> q = randomState(dofs, bodies.q0, rng);
  SpatialSample p;
  bodies.a.sample(loc, 1.3, q.data(), p);
  const Vec3 w(0.3, -0.7, 0.2);
  const double h = 1e-6;
  for (int field = 0; field < 4; ++field) {
    auto value = [&](const std::vector<double> &qq) {
      SpatialSample s;
      bodies.a.sample(loc, 1.3, qq.data(), s);
      return field == 0 ? Vec3(s.r) : Vec3(s.triad.col(field - 1));
    };
    auto jac = [&](const std::vector<double> &qq) {
      SpatialSample s;
      bodies.a.sample(loc, 1.3, qq.data(), s);
      return Eigen::MatrixXd(field == 0 ? s.r_q.leftCols(7) : s.d_q[field - 1].leftCols(7));
    };
    Eigen::MatrixXd fd(3, 7), fdH(7, 7);
    for (int j = 0; j < 7; ++j) {
      auto qp = q, qm = q;
      qp[j] += h, qm[j] -= h;
      fd.col(j) = (value(qp) - value(qm)) / (2 * h);
      fdH.col(j) = (jac(qp).transpose() * w - jac(qm).transpose() * w) / (2 * h);
    }
    EXPECT_LT((jac(q) - fd).norm(), 1e-8) << "field " << field;
    SpatialHessian H;
    bodies.a.curvatureTerm(loc, 1.3, q.data(), static_cast<SpatialField>(field), w, H);
    EXPECT_LT((Eigen::MatrixXd(H.topLeftCorner(7, 7)) - fdH).norm(), 1e-7) << "field " << field;
  }
  // At the initial state: the placement given.
  bodies.a.sample(loc, 1.3, bodies.q0.data(), p);
  EXPECT_LT((p.r - bodies.a.initialPosition(1.3)).norm(), 1e-14);
  EXPECT_LT((p.triad - bodies.a.initialTriad(1.3)).norm(), 1e-14);
}

TEST(SpatialJoints, RowsMatchFiniteDifferences)
{
  TwoBodies bodies;
  const SpatialEnd a = SpatialEnd::onBody(bodies.a, 0.4), b = SpatialEnd::onBody(bodies.b, 1.1);
  const SpatialEnd ground = SpatialEnd::ground(Vec3(0.2, -0.1, 0.4));
  SpatialDotRow r1{Vec3(0.2, 0.9, -0.3), Vec3::Zero(), Vec3(0.5, 0.1, 0.8), TimeFunction::constant(0.0)};
  SpatialDotRow r2{Vec3(-0.6, 0.2, 0.7), Vec3::Zero(), Vec3(0.1, -0.9, 0.2), TimeFunction::constant(0.0)};
  SpatialDotRow drive{Vec3(0.3, 0.8, 0.1), Vec3(1, 0, 0.2), Vec3(0, 1, -0.3), TimeFunction::sine(0.4, 0.7, 0.2, 0.1)};
  SpatialDotRow profile = drive;
  profile.theta = TimeFunction::accelLimited(0.2, 0.0, 1.2, 0.8, 0.5, 2.0);
  checkConstraint(SpatialJoint("spherical_ground", a, ground, true, {}), bodies.q0, 31);
  checkConstraint(SpatialJoint("spherical_bodies", a, b, true, {}), bodies.q0, 32);
  checkConstraint(SpatialJoint("revolute_ground", a, ground, true, {r1, r2}), bodies.q0, 33);
  checkConstraint(SpatialJoint("revolute_bodies", a, b, true, {r1, r2}), bodies.q0, 34);
  checkConstraint(SpatialJoint("drive_ground", a, ground, false, {drive}, true), bodies.q0, 35);
  checkConstraint(SpatialJoint("drive_bodies", a, b, false, {drive}, true), bodies.q0, 36);
  checkConstraint(SpatialJoint("drive_profile", a, b, false, {profile}, true), bodies.q0, 37);
  checkConstraint(EulerNormalization("euler", 3), bodies.q0, 38);
}

// The offset rows of the cylindrical and prismatic joints and the slide
// drive, (r_a - r_b) . T_b c - base - f(t), together with the alignment and
// roll rows they come with: body-ground, body-body (large random rotations:
// the Euler parameters move by up to 0.3 each) and a rigid body on a beam
// section (twisted, bent element).
TEST(SpatialJoints, OffsetRowsMatchFiniteDifferences)
{
  TwoBodies bodies;
  const SpatialEnd a = SpatialEnd::onBody(bodies.a, 0.4), b = SpatialEnd::onBody(bodies.b, 1.1);
  const SpatialEnd ground = SpatialEnd::ground(Vec3(0.2, -0.1, 0.4));
  SpatialDotRow r1{Vec3(0.2, 0.9, -0.3), Vec3::Zero(), Vec3(0.5, 0.1, 0.8), TimeFunction::constant(0.0)};
  SpatialDotRow r2{Vec3(-0.6, 0.2, 0.7), Vec3::Zero(), Vec3(0.1, -0.9, 0.2), TimeFunction::constant(0.0)};
  SpatialDotRow roll{Vec3(0.7, -0.1, 0.3), Vec3::Zero(), Vec3(-0.2, 0.4, 0.9), TimeFunction::constant(0.0)};
  SpatialOffsetRow o1{Vec3(0.3, -0.8, 0.5), 0.2, TimeFunction::constant(0.0)};
  SpatialOffsetRow o2{Vec3(-0.9, 0.1, 0.4), -0.1, TimeFunction::constant(0.0)};
  SpatialOffsetRow slide{Vec3(0.4, 0.6, -0.7), 0.3, TimeFunction::sine(0.4, 0.7, 0.2, 0.1)};
  SpatialOffsetRow profile = slide;
  profile.shift = TimeFunction::accelLimited(0.2, 0.0, 1.2, 0.8, 0.5, 2.0);
  checkConstraint(SpatialJoint("cylindrical_ground", a, ground, false, {o1, o2}, {r1, r2}), bodies.q0, 61);
  checkConstraint(SpatialJoint("cylindrical_bodies", a, b, false, {o1, o2}, {r1, r2}), bodies.q0, 62);
  checkConstraint(SpatialJoint("prismatic_ground", a, ground, false, {o1, o2}, {r1, r2, roll}), bodies.q0, 63);
  checkConstraint(SpatialJoint("prismatic_bodies", a, b, false, {o1, o2}, {r1, r2, roll}), bodies.q0, 64);
  checkConstraint(SpatialJoint("slide_ground", a, ground, false, {o1, o2, slide}, {r1, r2, roll}, true), bodies.q0,
                  65);
  checkConstraint(SpatialJoint("slide_bodies", a, b, false, {o1, o2, slide}, {r1, r2}, true), bodies.q0, 66);
  checkConstraint(SpatialJoint("slide_profile", a, b, false, {profile}, {}, true), bodies.q0, 67);
  // A rigid body on a beam section and a beam section on a rigid body: the
  // beam's director Hessians enter the offset rows of b.
  spatial_beam::Section section;
  section.EA = 1e6, section.EIy = 2e3, section.EIz = 3e3, section.GJ = 1e3, section.rhoA = 10, section.rhoIp = 0.1;
  const SpatialAncfBeam beam("beam", 2.0, 2, section, Vec3(0.1, -0.2, 0.3), axesOf(Vec3(1, 0.4, -0.3), Vec3(0, 1, 1)),
                             14);
  std::vector<double> q0 = bodies.q0;
  q0.resize(14 + beam.numCoordinates());
  beam.initialCoordinates(q0.data() + 14);
  const SpatialEnd onBeam = SpatialEnd::onBody(beam, 1.3);
  checkConstraint(SpatialJoint("rigid_on_beam", a, onBeam, false, {o1, o2, slide}, {r1, r2, roll}, true), q0, 68);
  checkConstraint(SpatialJoint("beam_on_rigid", onBeam, b, false, {o1, o2, slide}, {r1, r2, roll}, true), q0, 69);
  // Row units: position, offsets, dot rows.
  const SpatialJoint joint("units", a, b, false, {o1, o2}, {r1, r2, roll});
  EXPECT_EQ(joint.numRows(), 5);
  EXPECT_STREQ(joint.rowUnit(1), "m");
  EXPECT_STREQ(joint.rowUnit(2), "rad");
}

TEST(SpatialPointLoads, ForcesAndMomentsMatchFiniteDifferences)
{
  TwoBodies bodies;
  SpatialPointLoad::Parts fixed, follower;
  fixed.force = Vec3(1, -2, 3), fixed.moment = Vec3(-0.5, 0.7, 0.2);
  follower.followerForce = Vec3(0.4, 1.1, -0.6), follower.followerMoment = Vec3(0.3, -0.2, 0.9);
  checkItem(SpatialPointLoad("fixed", bodies.a, 1.2, fixed, TimeFunction::constant(1.3)), bodies.q0, 41);
  checkItem(SpatialPointLoad("follower", bodies.a, 0.3, follower, TimeFunction::constant(0.7)), bodies.q0, 42);
  // A moment on a rigid body does the work m . omega: Q_p = 2 E(p)^T m at |p| = 1.
  SpatialPointLoad::Parts moment;
  moment.moment = Vec3(0.3, -1.2, 0.5);
  Eigen::VectorXd Q;
  SpatialPointLoad("moment", bodies.a, 0.5, moment, TimeFunction::constant(1.0)).generalizedForce(bodies.q0.data(), Q,
                                                                                                   nullptr);
  const euler::Vec4 p(bodies.q0[3], bodies.q0[4], bodies.q0[5], bodies.q0[6]);
  EXPECT_LT(Q.head<3>().norm(), 1e-15);
  EXPECT_LT((Q.tail<4>() - 2.0 * euler::globalRateMatrix(p).transpose() * moment.moment).norm(), 1e-14);
}

TEST(SpatialPointMass, InertiaBlocksMatchFiniteDifferences)
{
  TwoBodies bodies;
  Mat3 J = Mat3::Zero();
  J.diagonal() << 0.2, 0.3, 0.4;
  checkItem(SpatialPointMass("mass", bodies.a, 1.7, 2.5, Mat3::Zero(), Vec3(0, 0, -9.81)), bodies.q0, 51);
  checkItem(SpatialPointMass("rotary", bodies.a, 0.2, 1.5, J, Vec3(0.3, 0, -9.81)), bodies.q0, 52);
}

TEST(SpatialPointMass, AtTheCentreOfMassItAddsToTheBody)
{
  // A body of mass m and inertia J carrying a point mass m2 with rotary
  // inertia J2 at its centre of mass moves like one body of m + m2, J + J2:
  // the residuals agree at any state.
  TwoBodies bodies;
  Mat3 J2 = Mat3::Zero();
  J2.diagonal() << 0.2, 0.3, 0.4;
  const double sCenter = 0.8; // the centre of mass of body a lies at (0.8, 0.1, -0.05) in body axes
  SpatialRigidBody onAxis("c", 2.0, 3.0, someInertia(), Vec3(sCenter, 0, 0), Vec3(0.1, 0.2, 0.3),
                          axesOf(Vec3(1, 0.3, 0.2), Vec3(0, 1, 0.4)), 0);
  SpatialRigidBody heavy("h", 2.0, 4.5, someInertia() + J2, Vec3(sCenter, 0, 0), Vec3(0.1, 0.2, 0.3),
                         axesOf(Vec3(1, 0.3, 0.2), Vec3(0, 1, 0.4)), 0);
  const Vec3 g(0, 0, -9.81);
  SpatialRigidInertia own(onAxis, g), whole(heavy, g);
  SpatialPointMass extra("m2", onAxis, sCenter, 1.5, J2, g);
  std::vector<double> q(7), v(7), a(7);
  onAxis.initialCoordinates(q.data());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 7; ++i) v[i] = u(rng), a[i] = u(rng);
  // A motion that keeps |p| = 1: p . pdot = 0 and p . pddot + pdot . pdot = 0
  // (the body's mass along p acts only off such motions).
  Eigen::Map<euler::Vec4> p(q.data() + 3), pd(v.data() + 3), pdd(a.data() + 3);
  pd -= p.dot(pd) * p;
  pdd -= (p.dot(pdd) + pd.dot(pd)) * p;
  AssemblyContext ctx;
  Eigen::VectorXd r1 = Eigen::VectorXd::Zero(7), r2 = Eigen::VectorXd::Zero(7);
  const ItemValues in{q.data(), v.data(), a.data(), nullptr};
  own.evaluate(ctx, in, r1.data(), nullptr);
  extra.evaluate(ctx, in, r1.data(), nullptr);
  whole.evaluate(ctx, in, r2.data(), nullptr);
  EXPECT_LT((r1 - r2).norm(), 1e-12 * r2.norm());
}
