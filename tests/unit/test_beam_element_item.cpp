// The beam element as a work item: its residual M a + f - s g (+ fd) is
// computed with the mass matrix's Kronecker structure (m ⊗ I2); it must equal
// the general matrix expression bit for bit, undamped and damped, since the
// stored scene digests (rtol 1e-9) and bitwise restarts rely on it.
#include "boomdyn/beam_element_item.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>

using namespace boomdyn;

TEST(BeamElementItem, KroneckerMassProductIsBitIdentical)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (bool damped : {false, true})
    for (double l : {0.5, 1e-3}) {
      ancf::Section sec{2.1e11 * 4.0e-3, 2.1e11 * 2.5e-5, 7850 * 4.0e-3};
      if (damped) sec.etaA = 1e-3, sec.etaB = 2e-3;
      const int elements = 4;
      const AncfBeam beam("boom", l * elements, elements, sec, Vec2(0.3, -0.2), 0.4, 0);
      auto mass = std::make_shared<const ancf::Mat8>(ancf::massMatrix(sec.rhoA, l));
      const Vec2 gravity(0.0, -9.81);
      const BeamElementItem item(beam, 2, mass, gravity);
      const ancf::Vec8 g = ancf::gravityForce(sec.rhoA, l, gravity);
      for (int trial = 0; trial < 200; ++trial) {
        ancf::Vec8 q = ancf::straightElement(Vec2(u(rng), u(rng)), Vec2(std::cos(0.4), std::sin(0.4)), l), v, a;
        for (int k = 0; k < 8; ++k) {
          q[k] += 1e-3 * u(rng) * ((k % 4) < 2 ? l : 1.0);
          v[k] = u(rng) * std::exp(5 * u(rng));
          a[k] = u(rng) * std::exp(10 * u(rng));
        }
        AssemblyContext ctx;
        ctx.loadFactor = 0.5 + 0.5 * u(rng);
        ItemValues in;
        in.q = q.data(), in.v = v.data(), in.a = a.data();
        double r[8];
        item.evaluate(ctx, in, r, nullptr);
        ancf::Vec8 f, expected;
        ancf::internalForce(sec, l, q, f, nullptr);
        expected = (*mass) * a + f - ctx.loadFactor * g;
        if (damped) {
          ancf::Vec8 fd;
          ancf::dampingForce(sec, l, q, v, fd, nullptr, nullptr);
          expected += fd;
        }
        for (int k = 0; k < 8; ++k)
          EXPECT_EQ(r[k], expected[k]) << (damped ? "damped" : "undamped") << ", l " << l << ", trial " << trial
                                       << ", entry " << k;
      }
    }
}
