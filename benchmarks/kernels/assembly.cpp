// Assembly micro-benchmarks: Assembler::evaluate (residual only; residual +
// Jacobian) on the cantilever of inputs/cantilever_dynamic.yaml with N
// elements and on the 100 m boom of benchmarks/scenes/long_boom.yaml (whose
// elements use the assumed axial strain, which the 2 m cantilever's stocky
// elements skip), in a generalized-α iteration context at a deformed state, and,
// for comparison, the bare loop over the work items' evaluate() with their
// values gathered beforehand (no scatter, no COO insertion). Times are
// reported per call and per element (counter `per_element`).
#include "bench_support.hpp"

#include "boomdyn/assembler.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <vector>
#include <memory>
#include <string>
#include <utility>

using namespace boomdyn;

namespace boomdyn::bench {

namespace {

struct AssemblyFixture {
  explicit AssemblyFixture(const Scene &scene) : model(scene), assembler(model) {}
  ~AssemblyFixture()
  {
    if (x) (void)VecDestroy(&x);
    if (F) (void)VecDestroy(&F);
    if (J) (void)MatDestroy(&J);
  }
  Model model;
  Assembler assembler;
  GlobalState state;
  Vec x = nullptr, F = nullptr;
  Mat J = nullptr;
  std::vector<ItemBuffers> items; // for the bare item loop
  int elements = 0;
};

// Built once per size and kept: Google Benchmark calls a benchmark function
// several times (to pick the iteration count), and setting up 65536 elements
// is far slower than one evaluation.
std::map<std::pair<std::string, int>, std::unique_ptr<AssemblyFixture>> &fixtures()
{
  static std::map<std::pair<std::string, int>, std::unique_ptr<AssemblyFixture>> f;
  return f;
}

// The scene's boom with N elements, deformed by `size` (a few per mille of an element's length).
AssemblyFixture &boom(const std::string &file, int elements, double size)
{
  auto &slot = fixtures()[{file, elements}];
  if (slot) return *slot;
  Scene scene = sceneFromFile(file);
  scene.bodies.at(0).elements = elements;
  slot = std::make_unique<AssemblyFixture>(scene);
  AssemblyFixture &f = *slot;
  f.elements = elements;
  f.state = deformedState(f.model, 1, size);
  PetscCallAbort(PETSC_COMM_WORLD, f.assembler.setUp(PETSC_COMM_WORLD));
  PetscCallAbort(PETSC_COMM_WORLD, f.assembler.createVector(&f.x));
  PetscCallAbort(PETSC_COMM_WORLD, f.assembler.createVector(&f.F));
  PetscCallAbort(PETSC_COMM_WORLD, f.assembler.createMatrix(&f.J));
  PetscCallAbort(PETSC_COMM_WORLD, f.assembler.setOffsets(nullptr, nullptr, nullptr));
  // x = the deformed state (one rank: the local array is the whole vector).
  PetscScalar *xa;
  PetscInt lo, hi;
  PetscCallAbort(PETSC_COMM_WORLD, VecGetOwnershipRange(f.x, &lo, &hi));
  PetscCallAbort(PETSC_COMM_WORLD, VecGetArray(f.x, &xa));
  for (PetscInt i = lo; i < hi; ++i) xa[i - lo] = f.state.x[i];
  PetscCallAbort(PETSC_COMM_WORLD, VecRestoreArray(f.x, &xa));
  // One warm-up evaluation (first MatSetValuesCOO, page faults of the buffers).
  PetscCallAbort(PETSC_COMM_WORLD, f.assembler.evaluate(dynamicContext(), f.x, f.F, f.J));
  for (const auto &item : f.model.items()) f.items.push_back(gatherItem(*item, f.state));
  return f;
}

AssemblyFixture &cantilever(int elements) { return boom("inputs/cantilever_dynamic.yaml", elements, 1e-3); }
AssemblyFixture &longBoom(int elements) { return boom("benchmarks/scenes/long_boom.yaml", elements, 1e-6); }

void perElement(benchmark::State &state, const AssemblyFixture &f)
{
  const int elements = f.elements;
  // Inverted rate: seconds per element (printed with an SI prefix, e.g. "55n s").
  state.counters["per_element"] =
    benchmark::Counter(static_cast<double>(elements), benchmark::Counter::kIsIterationInvariantRate |
                                                          benchmark::Counter::kInvert);
  state.counters["unknowns"] = static_cast<double>(f.model.size());
}

void assembly(benchmark::State &state, AssemblyFixture &f, bool residual, bool jacobian)
{
  const AssemblyContext ctx = dynamicContext();
  for (auto _ : state)
    PetscCallAbort(PETSC_COMM_WORLD, f.assembler.evaluate(ctx, f.x, residual ? f.F : nullptr, jacobian ? f.J : nullptr));
  perElement(state, f);
}

void BM_Assembly_Residual(benchmark::State &s) { assembly(s, cantilever(static_cast<int>(s.range(0))), true, false); }
void BM_Assembly_ResidualJacobian(benchmark::State &s)
{
  assembly(s, cantilever(static_cast<int>(s.range(0))), true, true);
}
// The same with the caches flushed before every evaluation (128 MB written
// outside the timing), as in a run, where the triangular solves of the
// factors (~100 MB at 10^5 elements) come between two residuals.
void BM_LongBoom_ResidualCold(benchmark::State &state)
{
  AssemblyFixture &f = longBoom(static_cast<int>(state.range(0)));
  const AssemblyContext ctx = dynamicContext();
  std::vector<double> flush(16 << 20);
  for (auto _ : state) {
    state.PauseTiming();
    for (std::size_t i = 0; i < flush.size(); i += 8) flush[i] += 1.0;
    benchmark::ClobberMemory();
    state.ResumeTiming();
    PetscCallAbort(PETSC_COMM_WORLD, f.assembler.evaluate(ctx, f.x, f.F, nullptr));
  }
  perElement(state, f);
}

// What the solvers ask for on the long boom: residuals, and the Jacobian alone (SNES's formJacobian).
void BM_LongBoom_Residual(benchmark::State &s) { assembly(s, longBoom(static_cast<int>(s.range(0))), true, false); }
void BM_LongBoom_Jacobian(benchmark::State &s) { assembly(s, longBoom(static_cast<int>(s.range(0))), false, true); }

// The work items alone: what the assembler's loop costs without the scatter,
// the gather and the insertion into PETSc.
void itemLoop(benchmark::State &state, AssemblyFixture &f, bool jacobian)
{
  const AssemblyContext ctx = dynamicContext();
  for (auto _ : state) {
    for (ItemBuffers &b : f.items) {
      std::fill(b.residual.begin(), b.residual.end(), 0.0);
      if (jacobian) std::fill(b.J.begin(), b.J.end(), 0.0);
      b.item->evaluate(ctx, b.values(), b.residual.data(), jacobian ? b.J.data() : nullptr);
    }
    benchmark::ClobberMemory();
  }
  perElement(state, f);
}

void BM_ItemsOnly_Residual(benchmark::State &s) { itemLoop(s, cantilever(static_cast<int>(s.range(0))), false); }
void BM_ItemsOnly_ResidualJacobian(benchmark::State &s) { itemLoop(s, cantilever(static_cast<int>(s.range(0))), true); }
void BM_LongBoomItemsOnly_Residual(benchmark::State &s) { itemLoop(s, longBoom(static_cast<int>(s.range(0))), false); }

void sizes(benchmark::internal::Benchmark *b)
{
  for (int n : {16, 256, 4096, 65536}) b->Arg(n);
  b->Unit(benchmark::kMicrosecond);
}

} // namespace

BENCHMARK(BM_Assembly_Residual)->Apply(sizes);
BENCHMARK(BM_Assembly_ResidualJacobian)->Apply(sizes);
BENCHMARK(BM_ItemsOnly_Residual)->Apply(sizes);
BENCHMARK(BM_ItemsOnly_ResidualJacobian)->Apply(sizes);
BENCHMARK(BM_LongBoom_Residual)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LongBoom_Jacobian)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LongBoom_ResidualCold)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LongBoomItemsOnly_Residual)->Arg(100000)->Unit(benchmark::kMicrosecond);

void releaseAssemblyFixtures() { fixtures().clear(); }

} // namespace boomdyn::bench
