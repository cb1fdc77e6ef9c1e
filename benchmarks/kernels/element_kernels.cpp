// Micro-benchmarks of single kernels: the ANCF element (internal force,
// internal force + tangent, mass matrix), and the evaluate() of single work
// items taken from a small model built from a scene: a beam element, the
// LuGre friction item and a sliding-joint constraint item, each for the
// residual alone and residual + Jacobian at a deformed state in a dynamic
// iteration context.
#include "bench_support.hpp"

#include "boomdyn/ancf_element.hpp"
#include "boomdyn/beam_element_item.hpp"
#include "boomdyn/lugre_friction.hpp"
#include "boomdyn/sliding_joint.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

using namespace boomdyn;

namespace {

// The steel box of inputs/cantilever_dynamic.yaml, 16 elements over 2 m.
const ancf::Section kSection{8.5176e8, 4.9531e6, 31.84};
constexpr double kLength = 2.0 / 16;

// An element of benchmarks/scenes/long_boom.yaml (100 m in 10^5 elements):
// slender, so the assumed axial strain is projected (the 2 m cantilever's
// stocky elements skip it).
ancf::Section longBoomSection()
{
  ancf::Section s{8.5176e8, 4.9531e6, 31.84};
  s.axialIntegration = ancf::AxialIntegration::Assumed;
  s.length = 100.0;
  return s;
}
const ancf::Section kLongSection = longBoomSection();
constexpr double kLongLength = 1e-3;

// A straight element rotated by 0.3 rad, bent and stretched by a few per mille
// (a state like a deflected boom's, away from the trivial undeformed one).
ancf::Vec8 deformedElement(double length = kLength)
{
  const double angle = 0.3;
  ancf::Vec8 e = ancf::straightElement(Vec2(0.4, 0.1), Vec2(std::cos(angle), std::sin(angle)), length);
  const double d[8] = {1e-4, -2e-4, 3e-3, -4e-3, -2e-4, 3e-4, -2e-3, 5e-3};
  for (int k = 0; k < 8; ++k) e[k] += d[k] * ((k % 4) < 2 ? length : 1.0);
  return e;
}

void BM_AncfInternalForce(benchmark::State &state)
{
  const ancf::Vec8 e = deformedElement();
  ancf::Vec8 f;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e);
    ancf::internalForce(kSection, kLength, e, f, nullptr);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_AncfInternalForce);

void BM_AncfInternalForceTangent(benchmark::State &state)
{
  const ancf::Vec8 e = deformedElement();
  ancf::Vec8 f;
  ancf::Mat8 K;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e);
    ancf::internalForce(kSection, kLength, e, f, &K);
    benchmark::DoNotOptimize(f);
    benchmark::DoNotOptimize(K);
  }
}
BENCHMARK(BM_AncfInternalForceTangent);

void BM_AncfInternalForceAssumed(benchmark::State &state)
{
  const ancf::Vec8 e = deformedElement(kLongLength);
  ancf::Vec8 f;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e);
    ancf::internalForce(kLongSection, kLongLength, e, f, nullptr);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_AncfInternalForceAssumed);

void BM_AncfInternalForceTangentAssumed(benchmark::State &state)
{
  const ancf::Vec8 e = deformedElement(kLongLength);
  ancf::Vec8 f;
  ancf::Mat8 K;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e);
    ancf::internalForce(kLongSection, kLongLength, e, f, &K);
    benchmark::DoNotOptimize(f);
    benchmark::DoNotOptimize(K);
  }
}
BENCHMARK(BM_AncfInternalForceTangentAssumed);

void BM_AncfMassMatrix(benchmark::State &state)
{
  double rhoA = kSection.rhoA;
  for (auto _ : state) {
    benchmark::DoNotOptimize(rhoA);
    ancf::Mat8 M = ancf::massMatrix(rhoA, kLength);
    benchmark::DoNotOptimize(M);
  }
}
BENCHMARK(BM_AncfMassMatrix);

void BM_AncfStrainEnergy(benchmark::State &state)
{
  const ancf::Vec8 e = deformedElement();
  for (auto _ : state) {
    benchmark::DoNotOptimize(e);
    double U = ancf::strainEnergy(kSection, kLength, e);
    benchmark::DoNotOptimize(U);
  }
}
BENCHMARK(BM_AncfStrainEnergy);

// A telescope section: an inner beam sliding in a clamped outer beam at two
// sliding joints, the first with LuGre friction.
const char *kSlidingScene = R"(
name: bench-sliding
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: outer, length: 2.0, elements: 4, section: {EA: 8.5e8, EI: 5.0e6, rhoA: 31.8}}
  - {name: inner, length: 1.5, elements: 3, origin: [0.5, 0.0], section: {EA: 6.0e8, EI: 3.0e6, rhoA: 25.0}}
constraints:
  - {type: clamp, body: outer, at: start}
  - type: sliding_joint
    name: rub
    body: inner
    at: start
    track: outer
    friction: {mu_s: 0.3, mu_c: 0.2, v_s: 0.05, alpha: 2, sigma0: 1.0e4, sigma1: 30, sigma2: 2}
  - {type: sliding_joint, name: rub2, body: inner, at: 1.0, track: outer}
dynamic: {t_end: 1.0, dt: 1.0e-3}
)";

struct SlidingFixture {
  Model model;
  bench::GlobalState state;
  explicit SlidingFixture(const Scene &scene) : model(scene), state(bench::deformedState(model)) {}
};

const SlidingFixture &slidingFixture()
{
  static const SlidingFixture f(parseScene(kSlidingScene, "bench-sliding"));
  return f;
}

template <class Pred> bench::ItemBuffers findItem(Pred pred)
{
  const SlidingFixture &f = slidingFixture();
  for (const auto &item : f.model.items())
    if (pred(*item)) return bench::gatherItem(*item, f.state);
  throw std::runtime_error("benchmark scene has no such work item");
}

bench::ItemBuffers lugreItem()
{
  return findItem([](const WorkItem &w) { return dynamic_cast<const LuGreFriction *>(&w) != nullptr; });
}

bench::ItemBuffers slidingJointItem()
{
  return findItem([](const WorkItem &w) {
    const auto *c = dynamic_cast<const ConstraintItem *>(&w);
    return c && dynamic_cast<const SlidingJoint *>(&c->constraint()) != nullptr;
  });
}

bench::ItemBuffers beamElementItem()
{
  return findItem([](const WorkItem &w) { return dynamic_cast<const BeamElementItem *>(&w) != nullptr; });
}

// evaluate() of one item as the assembler calls it: buffers zeroed, then added to.
void runItem(benchmark::State &state, bench::ItemBuffers b, bool jacobian)
{
  const AssemblyContext ctx = bench::dynamicContext();
  const ItemValues in = b.values();
  for (auto _ : state) {
    std::fill(b.residual.begin(), b.residual.end(), 0.0);
    if (jacobian) std::fill(b.J.begin(), b.J.end(), 0.0);
    b.item->evaluate(ctx, in, b.residual.data(), jacobian ? b.J.data() : nullptr);
    benchmark::DoNotOptimize(b.residual.data());
    benchmark::DoNotOptimize(b.J.data());
    benchmark::ClobberMemory();
  }
  state.counters["item_size"] = b.size();
}

void BM_BeamElementItem_Residual(benchmark::State &s) { runItem(s, beamElementItem(), false); }
void BM_BeamElementItem_ResidualJacobian(benchmark::State &s) { runItem(s, beamElementItem(), true); }
void BM_LuGreFriction_Residual(benchmark::State &s) { runItem(s, lugreItem(), false); }
void BM_LuGreFriction_ResidualJacobian(benchmark::State &s) { runItem(s, lugreItem(), true); }
void BM_SlidingJoint_Residual(benchmark::State &s) { runItem(s, slidingJointItem(), false); }
void BM_SlidingJoint_ResidualJacobian(benchmark::State &s) { runItem(s, slidingJointItem(), true); }
BENCHMARK(BM_BeamElementItem_Residual);
BENCHMARK(BM_BeamElementItem_ResidualJacobian);
BENCHMARK(BM_LuGreFriction_Residual);
BENCHMARK(BM_LuGreFriction_ResidualJacobian);
BENCHMARK(BM_SlidingJoint_Residual);
BENCHMARK(BM_SlidingJoint_ResidualJacobian);

} // namespace
