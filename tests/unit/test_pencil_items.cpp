// WorkItem::evaluatePencil (the eigen-analysis' stiffness, mass and damping
// blocks of an item in one call, Assembler::evaluatePencil) against the three
// evaluate() calls it replaces, for every item type that shares work between
// the passes (damped beam element, elastic rope, pad): the blocks must be
// equal bit for bit, at the pencil's own state (v = 0), at states with
// velocities, and when the passes' q differ in the sign of a zero entry
// (where the items fall back to separate kernels). Also the damping kernel's
// rest shortcut (Kq set to zero at edot = 0) against the summed Kq, and the
// beam's fused kernel at rest (stiffnessAndDampingAtRest) against the two.
#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/beam_element_item.hpp"
#include "boomdyn/elastic_rope.hpp"
#include "boomdyn/pad_contact.hpp"
#include "boomdyn/sliding_joint.hpp"
#include "rope_test_bodies.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <random>

using namespace boomdyn;

namespace {

// The three passes' values of one item: q, v, a per pass (n entries each).
struct PassValues {
  std::vector<double> q[kPencilPasses], v[kPencilPasses], a[kPencilPasses];
};

// The pencil's passes as Assembler::evaluatePencil sets them up.
void setContexts(PencilPass (&pass)[kPencilPasses], double t)
{
  for (PencilPass &p : pass) {
    p.ctx.t = t;
    p.ctx.sigma = 2.5;
    p.ctx.residualWanted = false;
  }
  pass[0].ctx.kin = {1.0, 0.0, 0.0, 0.0};
  pass[1].ctx.kin = {0.0, 0.0, 1.0, 0.0};
  pass[2].ctx.kin = {0.0, 1.0, 0.0, 0.0};
  pass[1].ctx.constraintBlocks = pass[2].ctx.constraintBlocks = false;
}

// Entries of the one-call blocks that differ in bits from the three
// evaluate() calls' (the mass block optional: withMass).
int differingBits(const WorkItem &item, const PassValues &vals, int n, double t, bool withMass)
{
  PencilPass pass[kPencilPasses];
  setContexts(pass, t);
  std::vector<double> one(kPencilPasses * n * n, 0.0), three(kPencilPasses * n * n, 0.0), scratch(n, 0.0);
  for (int p = 0; p < kPencilPasses; ++p) {
    pass[p].in = ItemValues{vals.q[p].data(), vals.v[p].data(), vals.a[p].data(), nullptr};
    pass[p].J = p == 1 && !withMass ? nullptr : one.data() + p * n * n;
  }
  item.evaluatePencil(pass, n, scratch.data());
  for (int p = 0; p < kPencilPasses; ++p) {
    if (!pass[p].J) continue;
    std::vector<double> r(n, 0.0);
    item.evaluate(pass[p].ctx, pass[p].in, r.data(), three.data() + p * n * n);
  }
  int differ = 0;
  for (std::size_t i = 0; i < one.size(); ++i) differ += std::memcmp(&one[i], &three[i], sizeof(double)) != 0;
  return differ;
}

// Values of the three passes at state q: the pencil's own (v = 0, a = 0 or
// q), or with velocities v (the same in the stiffness and damping passes,
// as the sharing needs) and accelerations.
PassValues pencilValues(const std::vector<double> &q, const std::vector<double> *v, std::mt19937 &rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::size_t n = q.size();
  PassValues out;
  for (int p = 0; p < kPencilPasses; ++p) {
    out.q[p] = q;
    out.v[p] = v ? *v : std::vector<double>(n, 0.0);
    out.a[p] = p == 1 ? q : std::vector<double>(n, 0.0);
    if (v)
      for (double &x : out.a[p]) x = 10.0 * u(rng);
  }
  return out;
}

} // namespace

TEST(PencilItems, DampedBeamElementEqualsThreeEvaluationsBitwise)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto axial : {ancf::AxialIntegration::Full, ancf::AxialIntegration::Reduced, ancf::AxialIntegration::Assumed})
    for (double l : {0.5, 1e-2}) {
      ancf::Section sec{2.1e11 * 4.0e-3, 2.1e11 * 2.5e-5, 7850 * 4.0e-3, 1e-3, 2e-3, axial};
      if (axial == ancf::AxialIntegration::Assumed) sec.EI *= 1e-4; // EA L^2/EI above the stabilization: projected
      const int elements = 4;
      const AncfBeam beam("boom", l * elements, elements, sec, Vec2(0.3, -0.2), 0.4, 0);
      auto mass = std::make_shared<const ancf::Mat8>(ancf::massMatrix(sec.rhoA, l));
      const BeamElementItem item(beam, 1, mass, Vec2(0.0, -9.81));
      for (int trial = 0; trial < 50; ++trial) {
        ancf::Vec8 e = ancf::straightElement(Vec2(u(rng), u(rng)), Vec2(std::cos(0.4), std::sin(0.4)), l);
        std::vector<double> q(8), v(8);
        for (int k = 0; k < 8; ++k) {
          q[k] = e[k] + 1e-2 * u(rng) * ((k % 4) < 2 ? l : 1.0);
          v[k] = u(rng) * std::exp(3 * u(rng));
        }
        const PassValues atRest = pencilValues(q, nullptr, rng), moving = pencilValues(q, &v, rng);
        EXPECT_EQ(differingBits(item, atRest, 8, 0.0, true), 0) << "at rest, l " << l << ", trial " << trial;
        EXPECT_EQ(differingBits(item, atRest, 8, 0.0, false), 0) << "no mass block, l " << l << ", trial " << trial;
        EXPECT_EQ(differingBits(item, moving, 8, 0.0, true), 0) << "moving, l " << l << ", trial " << trial;
        // A zero entry of opposite signs in the stiffness and damping passes' q
        // (how the assembler's maps can differ): the separate kernels.
        PassValues signedZero = atRest;
        signedZero.q[0][3] = 0.0, signedZero.q[1][3] = signedZero.q[2][3] = -0.0;
        EXPECT_EQ(differingBits(item, signedZero, 8, 0.0, true), 0) << "signed zero, trial " << trial;
      }
    }
}

TEST(PencilItems, DampingKernelAtRestSetsTheSummedZerosAndTheFusedKernelAgrees)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto axial : {ancf::AxialIntegration::Full, ancf::AxialIntegration::Reduced, ancf::AxialIntegration::Assumed})
    for (double l : {0.5, 1e-3}) {
      ancf::Section sec{8.5e8, 4.9e6, 31.8, 2e-3, 5e-3, axial};
      if (axial == ancf::AxialIntegration::Assumed) sec.EI *= 1e-4;
      for (int trial = 0; trial < 50; ++trial) {
        ancf::Vec8 e = ancf::straightElement(Vec2(u(rng), u(rng)), Vec2(std::cos(1.1), std::sin(1.1)), l);
        for (int k = 0; k < 8; ++k) e[k] += 1e-2 * u(rng) * ((k % 4) < 2 ? l : 1.0);
        ancf::Vec8 rest = ancf::Vec8::Zero(), f1, f2;
        if (trial % 2) rest[2] = -0.0, rest[5] = -0.0; // zeros of either sign
        ancf::Mat8 K1, D1, K2, D2;
        const double p1 = ancf::dampingForce(sec, l, e, rest, f1, &K1, &D1);
        const double p2 = ancf::dampingForceSummed(sec, l, e, rest, f2, &K2, &D2);
        EXPECT_EQ(std::memcmp(&p1, &p2, sizeof p1), 0);
        EXPECT_EQ(std::memcmp(f1.data(), f2.data(), sizeof(double) * 8), 0);
        EXPECT_EQ(std::memcmp(K1.data(), K2.data(), sizeof(double) * 64), 0) << "trial " << trial;
        EXPECT_EQ(std::memcmp(D1.data(), D2.data(), sizeof(double) * 64), 0) << "trial " << trial;
        // The fused kernel of the pencil: internalForce's tangent and these, bitwise.
        ancf::Mat8 Kt, Kt3, K3, D3;
        ancf::Vec8 f;
        ancf::internalForce(sec, l, e, f, &Kt);
        ASSERT_TRUE(ancf::stiffnessAndDampingAtRest(sec, l, e, rest, Kt3, K3, D3)) << "trial " << trial;
        EXPECT_EQ(std::memcmp(Kt.data(), Kt3.data(), sizeof(double) * 64), 0) << "trial " << trial;
        EXPECT_EQ(std::memcmp(K2.data(), K3.data(), sizeof(double) * 64), 0) << "trial " << trial;
        EXPECT_EQ(std::memcmp(D2.data(), D3.data(), sizeof(double) * 64), 0) << "trial " << trial;
      }
    }
}

TEST(PencilItems, ElasticRopeEqualsThreeEvaluationsBitwise)
{
  const rope_test::Bodies bodies;
  const auto &[b1, b2, b3, q0] = bodies;
  const RopePath path({{&b1, 0.3}, {&b2, 2.0}, {&b3, 0.0}, {&b1, 1.7}});
  std::vector<PetscInt> dofs;
  path.coordinates(dofs);
  std::vector<double> qp;
  for (PetscInt d : dofs) qp.push_back(q0[d]);
  const double l0 = path.length(qp.data());
  const ElasticRope rope("rope", path, 1.2e7, 0.95 * l0, 3.0e4, TimeFunction::ramp(0.5, 2.0, 0.0, -0.1));
  const int n = static_cast<int>(qp.size());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> q = qp, v(n);
    for (int i = 0; i < n; ++i) q[i] += 0.01 * u(rng), v[i] = 0.5 * u(rng);
    ASSERT_TRUE(rope.state(1.0, q.data(), v.data()).taut);
    const PassValues atRest = pencilValues(q, nullptr, rng), moving = pencilValues(q, &v, rng);
    EXPECT_EQ(differingBits(rope, atRest, n, 1.0, true), 0) << "at rest, trial " << trial;
    EXPECT_EQ(differingBits(rope, moving, n, 1.0, true), 0) << "moving, trial " << trial;
    EXPECT_EQ(differingBits(rope, moving, n, 1.0, false), 0) << "no mass block, trial " << trial;
    PassValues signedZero = moving;
    signedZero.q[0][0] = 0.0, signedZero.q[1][0] = signedZero.q[2][0] = -0.0;
    EXPECT_EQ(differingBits(rope, signedZero, n, 1.0, true), 0) << "signed zero, trial " << trial;
  }
  // Slack: nothing in any block, in one call as in three.
  const ElasticRope slack("slack", path, 1.2e7, 1.05 * l0, 3.0e4);
  const PassValues slackValues = pencilValues(qp, nullptr, rng);
  EXPECT_EQ(differingBits(slack, slackValues, n, 0.0, true), 0);
}

TEST(PencilItems, PadEqualsThreeEvaluationsBitwise)
{
  const ancf::Section section{1e8, 1e5, 30};
  const AncfBeam track{"track", 2.0, 4, section, Vec2(0, 0), 0.1, 0};
  const AncfBeam slider{"slider", 1.5, 3, section, Vec2(0.5, 0.05), 0.1, 36};
  auto joint = std::make_shared<SlidingJoint>("slide", track, slider, 0.3, 36 + 32, 0.8, false);
  std::vector<double> q0(69);
  track.initialCoordinates(q0.data());
  slider.initialCoordinates(q0.data() + 36);
  q0[68] = 0.8;
  std::vector<PetscInt> dofs;
  joint->coordinates(dofs);
  const int n = static_cast<int>(dofs.size());
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Clearances: always in contact (0), and one that the random states put
  // the slider inside of or beyond on either side.
  for (double clearance : {0.0, 0.01}) {
    const PadContact pad(joint, PadSpec{2e8, clearance, 4e4});
    int inside = 0, contact = 0;
    for (int trial = 0; trial < 40; ++trial) {
      std::vector<double> q(n), v(n);
      for (int i = 0; i < n; ++i) q[i] = q0[dofs[i]] + 0.02 * u(rng), v[i] = 0.3 * u(rng);
      (pad.state(q.data(), v.data()).side == 0 ? inside : contact) += 1;
      const PassValues atRest = pencilValues(q, nullptr, rng), moving = pencilValues(q, &v, rng);
      EXPECT_EQ(differingBits(pad, atRest, n, 0.0, true), 0) << "at rest, trial " << trial;
      EXPECT_EQ(differingBits(pad, moving, n, 0.0, true), 0) << "moving, trial " << trial;
      PassValues signedZero = moving;
      signedZero.q[0][1] = 0.0, signedZero.q[1][1] = signedZero.q[2][1] = -0.0;
      EXPECT_EQ(differingBits(pad, signedZero, n, 0.0, true), 0) << "signed zero, trial " << trial;
    }
    EXPECT_GT(contact, 0);
    if (clearance > 0) EXPECT_GT(inside, 0) << "the clearance's own tangent was not reached";
  }
}
