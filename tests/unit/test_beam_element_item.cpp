// The beam element as a work item: its residual M a + f - s g (+ fd) is
// computed with the mass matrix's Kronecker structure (m ⊗ I2); it must equal
// the general matrix expression bit for bit, undamped and damped, since the
// stored scene digests (rtol 1e-9) and bitwise restarts rely on it.
#include "boomdyn/beam_element_item.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <random>
#include <vector>

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

// Residuals of a beam's elements in one batch (evaluateResiduals, one
// kernel call for four elements; the assembler's residual path) must be
// evaluate()'s residuals bit for bit (memcmp), undamped and damped; a damped
// batch must also leave each item the damping force and power that
// evaluate() keeps (the energy diagnostics and the energy check read them:
// dampingForce, energy's dissipation). Any count other than the kernel's
// width falls back to evaluate().
TEST(BeamElementItem, BatchedResidualsAreBitIdentical)
{
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (bool damped : {false, true})
    for (double l : {0.5, 1e-3}) {
      ancf::Section sec{2.1e11 * 4.0e-3, 2.1e11 * 2.5e-5, 7850 * 4.0e-3};
      sec.axialIntegration = ancf::AxialIntegration::Assumed;
      if (damped) sec.etaA = 1e-3, sec.etaB = 2e-3;
      const int elements = 6;
      const AncfBeam beam("boom", l * elements, elements, sec, Vec2(0.3, -0.2), 0.4, 0);
      auto mass = std::make_shared<const ancf::Mat8>(ancf::massMatrix(sec.rhoA, l));
      std::vector<std::unique_ptr<BeamElementItem>> owned;
      const WorkItem *items[kResidualBatch];
      for (int j = 0; j < kResidualBatch; ++j) {
        owned.push_back(std::make_unique<BeamElementItem>(beam, 1 + j, mass, Vec2(0.0, -9.81)));
        items[j] = owned.back().get();
      }
      // Items evaluated one at a time, for the expected memo.
      std::vector<std::unique_ptr<BeamElementItem>> single;
      for (int j = 0; j < kResidualBatch; ++j)
        single.push_back(std::make_unique<BeamElementItem>(beam, 1 + j, mass, Vec2(0.0, -9.81)));
      EXPECT_NE(items[0]->residualBatchKey(), nullptr);
      EXPECT_EQ(items[0]->residualBatchKey(), items[3]->residualBatchKey());
      for (int count : {kResidualBatch, 3})
        for (int trial = 0; trial < 50; ++trial) {
          ancf::Vec8 q[kResidualBatch], v[kResidualBatch], a[kResidualBatch];
          ItemValues in[kResidualBatch];
          double r[kResidualBatch][8] = {}, expected[kResidualBatch][8] = {};
          double *rp[kResidualBatch];
          AssemblyContext ctx;
          ctx.loadFactor = 0.5 + 0.5 * u(rng);
          for (int j = 0; j < count; ++j) {
            q[j] = ancf::straightElement(Vec2(u(rng), u(rng)), Vec2(std::cos(0.4), std::sin(0.4)), l);
            for (int k = 0; k < 8; ++k) {
              q[j][k] += 1e-3 * u(rng) * ((k % 4) < 2 ? l : 1.0);
              v[j][k] = u(rng) * std::exp(5 * u(rng));
              a[j][k] = u(rng) * std::exp(10 * u(rng));
            }
            in[j].q = q[j].data(), in[j].v = v[j].data(), in[j].a = a[j].data();
            rp[j] = r[j];
            single[j]->evaluate(ctx, in[j], expected[j], nullptr);
          }
          items[0]->evaluateResiduals(ctx, items, in, rp, count);
          for (int j = 0; j < count; ++j) {
            for (int k = 0; k < 8; ++k)
              EXPECT_EQ(std::memcmp(&r[j][k], &expected[j][k], sizeof(double)), 0)
                  << (damped ? "damped" : "undamped") << ", l " << l << ", count " << count << ", trial " << trial
                  << ", item " << j << ", entry " << k << ": " << r[j][k] << " vs " << expected[j][k];
            if (!damped) continue;
            // The memo: kept at this state by both, and read back bit for bit.
            const auto *batched = static_cast<const BeamElementItem *>(items[j]);
            EXPECT_TRUE(batched->dampingKeptAt(in[j])) << "count " << count << ", item " << j;
            EXPECT_TRUE(single[j]->dampingKeptAt(in[j]));
            double fd[8], fdExpected[8];
            ASSERT_TRUE(batched->dampingForce(in[j], fd));
            ASSERT_TRUE(single[j]->dampingForce(in[j], fdExpected));
            EXPECT_EQ(std::memcmp(fd, fdExpected, sizeof fd), 0) << "count " << count << ", item " << j;
            EnergyParts e, eExpected;
            batched->energy(ctx, in[j], e);
            single[j]->energy(ctx, in[j], eExpected);
            EXPECT_EQ(std::memcmp(&e.dissipation, &eExpected.dissipation, sizeof(double)), 0)
                << "power, count " << count << ", item " << j;
          }
        }
    }
}
