// Cantilever frequencies against Euler-Bernoulli theory: the first three
// bending frequencies of a clamped-free beam, with and without a tip mass
// (frequency equation solved here by bisection), at 16 elements.
#include "boomdyn/assembler.hpp"
#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/scene_reader.hpp"

#include <gtest/gtest.h>
#include <slepcsys.h>

#include <cmath>
#include <functional>

using namespace boomdyn;

namespace {

// 2 m steel box boom (docs/scenes.md): EI = 4.9531e6 N m^2, rhoA = 31.84 kg/m.
// EA/EI large: the axial modes sit far above the first bending modes.
constexpr double L = 2.0, EI = 4.9531e6, EA = 8.5176e8, rhoA = 31.8396;

std::string cantilever(int elements, double tipMass)
{
  std::string s = "name: cantilever-modes\nanalysis: modal\nbodies:\n  - name: boom\n    length: 2.0\n    elements: " +
                  std::to_string(elements) + "\n    section: {EA: 8.5176e8, EI: 4.9531e6, rhoA: 31.8396}\n" +
                  "constraints:\n  - {type: clamp, body: boom, at: start}\nmodal: {count: 6}\n";
  if (tipMass > 0) s += "masses:\n  - {body: boom, at: end, mass: " + std::to_string(tipMass) + "}\n";
  return s;
}

// Roots of f on (a, b) by bisection, scanning for sign changes.
std::vector<double> roots(const std::function<double(double)> &f, double a, double b, int count)
{
  std::vector<double> out;
  const int scan = 20000;
  double x0 = a, f0 = f(a);
  for (int i = 1; i <= scan && (int)out.size() < count; ++i) {
    const double x1 = a + (b - a) * i / scan, f1 = f(x1);
    if (f0 * f1 < 0) {
      double lo = x0, hi = x1;
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (f(lo) * f(mid) <= 0 ? hi : lo) = mid;
      }
      out.push_back(0.5 * (lo + hi));
    }
    x0 = x1, f0 = f1;
  }
  return out;
}

// Bending frequencies (Hz) of the model, axial modes filtered out by their shape:
// a bending mode moves the nodes mostly transversally (y).
std::vector<double> modelBendingFrequencies(const std::string &text, int count)
{
  Scene scene = parseScene(text, "cantilever-modes.yaml");
  Model model(scene);
  Assembler assembler(model);
  Vec q, lambda;
  PetscCallAbort(PETSC_COMM_WORLD, assembler.setUp(PETSC_COMM_WORLD));
  PetscCallAbort(PETSC_COMM_WORLD, assembler.createVector(&q));
  PetscCallAbort(PETSC_COMM_WORLD, assembler.createVector(&lambda));
  const std::vector<double> q0 = model.initialCoordinates();
  PetscInt lo, hi;
  PetscCallAbort(PETSC_COMM_WORLD, VecGetOwnershipRange(q, &lo, &hi));
  for (PetscInt i = lo; i < std::min<PetscInt>(hi, model.numCoordinates()); ++i)
    PetscCallAbort(PETSC_COMM_WORLD, VecSetValue(q, i, q0[i], INSERT_VALUES));
  PetscCallAbort(PETSC_COMM_WORLD, VecAssemblyBegin(q));
  PetscCallAbort(PETSC_COMM_WORLD, VecAssemblyEnd(q));
  PetscCallAbort(PETSC_COMM_WORLD, SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  ModalResult modes;
  PetscCallAbort(PETSC_COMM_WORLD, solveModes(assembler, 0.0, q, lambda, count + 3, &modes));
  std::vector<double> bending;
  for (std::size_t k = 0; k < modes.frequencyHz.size() && (int)bending.size() < count; ++k) {
    bool transverse = true;
    if (!modes.shapes.empty()) { // rank 0 decides from the shape
      double ux = 0, uy = 0;
      for (std::size_t i = 0; i + 3 < modes.shapes[k].size(); i += 4) ux += std::abs(modes.shapes[k][i]), uy += std::abs(modes.shapes[k][i + 1]);
      transverse = uy > ux;
    }
    int flag = transverse;
    MPI_Bcast(&flag, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    if (flag) bending.push_back(modes.frequencyHz[k]);
  }
  VecDestroy(&q);
  VecDestroy(&lambda);
  return bending;
}

} // namespace

TEST(CantileverModes, FirstThreeMatchEulerBernoulli)
{
  // 1 + cos(bL) cosh(bL) = 0
  const auto bl = roots([](double x) { return 1.0 + std::cos(x) * std::cosh(x); }, 0.5, 12.0, 3);
  ASSERT_EQ(bl.size(), 3u);
  const std::vector<double> f = modelBendingFrequencies(cantilever(16, 0.0), 3);
  ASSERT_EQ(f.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const double exact = bl[k] * bl[k] / (L * L) * std::sqrt(EI / rhoA) / (2 * M_PI);
    const double rel = std::abs(f[k] - exact) / exact;
    PetscPrintf(PETSC_COMM_WORLD, "  cantilever mode %d: model %.6f Hz, Euler-Bernoulli %.6f Hz, relative error %.2e\n", k + 1, f[k], exact, rel);
    EXPECT_LT(rel, 1e-3) << "mode " << k + 1;
  }
}

TEST(CantileverModes, TipMassMatchesFrequencyEquation)
{
  const double m = 100.0, ratio = m / (rhoA * L);
  // 1 + cos cosh + ratio * bL (cos sinh - sin cosh) = 0
  const auto bl = roots(
    [&](double x) { return 1.0 + std::cos(x) * std::cosh(x) + ratio * x * (std::cos(x) * std::sinh(x) - std::sin(x) * std::cosh(x)); },
    0.3, 12.0, 3);
  ASSERT_EQ(bl.size(), 3u);
  const std::vector<double> f = modelBendingFrequencies(cantilever(16, m), 3);
  ASSERT_EQ(f.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const double exact = bl[k] * bl[k] / (L * L) * std::sqrt(EI / rhoA) / (2 * M_PI);
    const double rel = std::abs(f[k] - exact) / exact;
    PetscPrintf(PETSC_COMM_WORLD, "  tip mass %.0f kg, mode %d: model %.6f Hz, theory %.6f Hz, relative error %.2e\n", m, k + 1, f[k], exact, rel);
    EXPECT_LT(rel, 1e-3) << "mode " << k + 1;
  }
}
