// Micro-benchmarks of the spatial beam element with twist (docs/model.md
// §1.7) beside the planar element's (element_kernels.cpp): internal force,
// force + tangent, and the damped residual and Jacobian blocks, for one
// element of the 2 m steel-box cantilever at a deformed and twisted state.
#include "boomdyn/ancf_element.hpp"
#include "boomdyn/spatial_beam_element.hpp"

#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

using namespace boomdyn;
using namespace boomdyn::spatial_beam;

namespace {

// The planar benchmarks' section (inputs/cantilever_dynamic.yaml) with
// EIz = EI, EIy = 0.6 EI, GJ and rotary inertia of a comparable box.
Section spatialSection()
{
  Section s;
  s.EA = 8.5176e8, s.EIz = 4.9531e6, s.EIy = 0.6 * 4.9531e6, s.GJ = 3.0e6;
  s.rhoA = 31.84, s.rhoIp = 0.05;
  s.etaA = 2e-4, s.etaB = 3e-3, s.etaT = 1e-3;
  return s;
}
constexpr double kLength = 2.0 / 16;

// A straight element turned by 0.3 rad about an oblique axis, bent,
// stretched and twisted by a few per mille (as the planar benchmark's state).
struct SpatialState {
  Geometry geo;
  Vec14 e, edot;
};
SpatialState deformedState()
{
  const Mat3 R = Eigen::AngleAxisd(0.3, Vec3(0.2, 0.5, 1.0).normalized()).toRotationMatrix();
  SpatialState s{straightGeometry(R, kLength), straightElement(Vec3(0.4, 0.1, -0.2), R, kLength), Vec14::Zero()};
  for (int k = 0; k < kCoordinates; ++k) {
    s.e[k] += 3e-3 * std::sin(1.7 * k + 0.3) * ((k % 7) < 3 ? kLength : 1.0);
    s.edot[k] = 0.5 * std::cos(0.9 * k);
  }
  return s;
}

void BM_SpatialBeamInternalForce(benchmark::State &state)
{
  const Section sec = spatialSection();
  const SpatialState s = deformedState();
  Vec14 f;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.e);
    internalForce(sec, s.geo, s.e, f, nullptr);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_SpatialBeamInternalForce);

void BM_SpatialBeamInternalForceTangent(benchmark::State &state)
{
  const Section sec = spatialSection();
  const SpatialState s = deformedState();
  Vec14 f;
  Mat14 K;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.e);
    internalForce(sec, s.geo, s.e, f, &K);
    benchmark::DoNotOptimize(f);
    benchmark::DoNotOptimize(K);
  }
}
BENCHMARK(BM_SpatialBeamInternalForceTangent);

void BM_SpatialBeamDampingForce(benchmark::State &state)
{
  const Section sec = spatialSection();
  const SpatialState s = deformedState();
  Vec14 fd;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.e);
    benchmark::DoNotOptimize(dampingForce(sec, s.geo, s.e, s.edot, fd, nullptr, nullptr));
    benchmark::DoNotOptimize(fd);
  }
}
BENCHMARK(BM_SpatialBeamDampingForce);

void BM_SpatialBeamDampingJacobians(benchmark::State &state)
{
  const Section sec = spatialSection();
  const SpatialState s = deformedState();
  Vec14 fd;
  Mat14 Kq, Dv;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.e);
    benchmark::DoNotOptimize(dampingForce(sec, s.geo, s.e, s.edot, fd, &Kq, &Dv));
    benchmark::DoNotOptimize(Kq);
    benchmark::DoNotOptimize(Dv);
  }
}
BENCHMARK(BM_SpatialBeamDampingJacobians);

void BM_SpatialBeamInternalAndDampingJacobians(benchmark::State &state)
{
  const Section sec = spatialSection();
  const SpatialState s = deformedState();
  Vec14 f, fd;
  Mat14 K, Kq, Dv;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.e);
    benchmark::DoNotOptimize(internalAndDampingForce(sec, s.geo, s.e, s.edot, f, &K, fd, &Kq, &Dv));
    benchmark::DoNotOptimize(K);
    benchmark::DoNotOptimize(Kq);
  }
}
BENCHMARK(BM_SpatialBeamInternalAndDampingJacobians);

void BM_SpatialBeamInternalAndDampingForce(benchmark::State &state)
{
  const Section sec = spatialSection();
  const SpatialState s = deformedState();
  Vec14 f, fd;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.e);
    benchmark::DoNotOptimize(internalAndDampingForce(sec, s.geo, s.e, s.edot, f, nullptr, fd, nullptr, nullptr));
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_SpatialBeamInternalAndDampingForce);

// The jet oracle (spatial_beam::reference: 12-variable jets through every
// operation) on the same state, for the cost of what the kernels replace.
void BM_SpatialBeamJetInternalForce(benchmark::State &state)
{
  const Section sec = spatialSection();
  const SpatialState s = deformedState();
  Vec14 f;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.e);
    reference::internalForce(sec, s.geo, s.e, f, nullptr);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_SpatialBeamJetInternalForce);

void BM_SpatialBeamJetInternalForceTangent(benchmark::State &state)
{
  const Section sec = spatialSection();
  const SpatialState s = deformedState();
  Vec14 f;
  Mat14 K;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.e);
    reference::internalForce(sec, s.geo, s.e, f, &K);
    benchmark::DoNotOptimize(f);
    benchmark::DoNotOptimize(K);
  }
}
BENCHMARK(BM_SpatialBeamJetInternalForceTangent);

void BM_SpatialBeamJetDampingJacobians(benchmark::State &state)
{
  const Section sec = spatialSection();
  const SpatialState s = deformedState();
  Vec14 fd;
  Mat14 Kq, Dv;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.e);
    benchmark::DoNotOptimize(reference::dampingForce(sec, s.geo, s.e, s.edot, fd, &Kq, &Dv));
    benchmark::DoNotOptimize(Kq);
    benchmark::DoNotOptimize(Dv);
  }
}
BENCHMARK(BM_SpatialBeamJetDampingJacobians);

} // namespace
