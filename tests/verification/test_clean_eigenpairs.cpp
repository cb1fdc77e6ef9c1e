// Clean eigenpairs (issue 13, item 3): on small models the infinite
// eigenvalues of the singular mass pencil (constraint rows, massless
// coordinates) must never be reported as modes. Every analysis returns
// exactly the requested number of finite, positive modes, each equal to the
// discrete value of an independent reference written here: the ANCF element
// linearized at its straight, unstrained state is a cubic Hermite bar
// (axial, EA u'^2) plus a Hermite Euler-Bernoulli beam (transverse, EI v''^2)
// with consistent mass, so the constrained discrete eigenvalues follow from
// dense Eigen algebra after removing the clamped entries (null-space
// reduction). Cantilevers with 1-4 elements (down to all their finite modes)
// with and without a tip mass, and the paper's telescope (pad-coupled
// bending from tests/telescope_reference.hpp, axial bars coupled by the
// drive and the rope).
#include "support.hpp"
#include "telescope_reference.hpp"

#include "boomdyn/eigen_solver.hpp"

#include <Eigen/Dense>
#include <slepcsys.h>

#include <algorithm>
#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double kEA = 8.5176e8, kEI = 4.9531e6, kRhoA = 31.8396;

// Hermite element matrices of a scalar field w with entries (w_i, w'_i, w_j, w'_j).
Eigen::Matrix4d hermiteMass(double rhoA, double h)
{
  Eigen::Matrix4d m;
  m << 156, 22 * h, 54, -13 * h, 22 * h, 4 * h * h, 13 * h, -3 * h * h, 54, 13 * h, 156, -22 * h, -13 * h, -3 * h * h,
    -22 * h, 4 * h * h;
  return m * rhoA * h / 420.0;
}
Eigen::Matrix4d hermiteBending(double EI, double h)
{
  Eigen::Matrix4d k;
  k << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h, 6 * h, 2 * h * h, -6 * h,
    4 * h * h;
  return k * EI / (h * h * h);
}
Eigen::Matrix4d hermiteAxial(double EA, double h) // EA * integral of S'^T S'
{
  Eigen::Matrix4d k;
  k << 36, 3 * h, -36, 3 * h, 3 * h, 4 * h * h, -3 * h, -h * h, -36, -3 * h, 36, -3 * h, 3 * h, -h * h, -3 * h,
    4 * h * h;
  return k * EA / (30.0 * h);
}

// Lowest `count` frequencies (Hz) of K v = w^2 M v on the null space of C.
std::vector<double> constrainedFrequencies(const Eigen::MatrixXd &K, const Eigen::MatrixXd &M, const Eigen::MatrixXd &C,
                                           int count)
{
  const Eigen::MatrixXd Z = C.rows() ? Eigen::MatrixXd(C.fullPivLu().kernel()) : Eigen::MatrixXd::Identity(K.rows(), K.rows());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Z.transpose() * K * Z, Z.transpose() * M * Z);
  std::vector<double> f;
  for (int k = 0; k < count && k < es.eigenvalues().size(); ++k) f.push_back(std::sqrt(es.eigenvalues()[k]) / (2 * M_PI));
  return f;
}

// Clamped cantilever of n elements, node entries (x, y, x', y'); the clamp
// fixes x, y and y' at the root (x' stays free); a point mass at the tip.
std::vector<double> cantileverReference(int n, double tipMass, int count)
{
  const double h = 2.0 / n;
  const int nd = 4 * (n + 1);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nd, nd), M = Eigen::MatrixXd::Zero(nd, nd);
  const Eigen::Matrix4d me = hermiteMass(kRhoA, h), kb = hermiteBending(kEI, h), ka = hermiteAxial(kEA, h);
  for (int e = 0; e < n; ++e) {
    const int u[4] = {4 * e, 4 * e + 2, 4 * e + 4, 4 * e + 6}, v[4] = {4 * e + 1, 4 * e + 3, 4 * e + 5, 4 * e + 7};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        K(u[i], u[j]) += ka(i, j), M(u[i], u[j]) += me(i, j);
        K(v[i], v[j]) += kb(i, j), M(v[i], v[j]) += me(i, j);
      }
  }
  M(4 * n, 4 * n) += tipMass, M(4 * n + 1, 4 * n + 1) += tipMass;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, nd);
  C(0, 0) = C(1, 1) = C(2, 3) = 1.0;
  return constrainedFrequencies(K, M, C, count);
}

// Axial motion of the telescope: three Hermite bars; boom 1 clamped
// (u = 0 at its root), the drive holds boom 2's root on boom 1's material
// point under it, the rope (boom 1 root - pulley at boom 2's end - boom 3's
// root) keeps 2 u_pulley = u_boom1root + u_boom3root; the pads slide freely.
std::vector<double> telescopeAxialReference(const TelescopeReference &ref, int count)
{
  const int n = ref.elements(), perBoom = 2 * (n + 1), nd = 3 * perBoom;
  const double h = ref.h;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nd, nd), M = Eigen::MatrixXd::Zero(nd, nd);
  auto dof = [&](int b, int node, int k) { return b * perBoom + 2 * node + k; };
  for (int b = 0; b < 3; ++b) {
    const Eigen::Matrix4d me = hermiteMass(ref.rho * ref.A[b], h), ka = hermiteAxial(ref.E * ref.A[b], h);
    for (int e = 0; e < n; ++e) {
      const int d[4] = {dof(b, e, 0), dof(b, e, 1), dof(b, e + 1, 0), dof(b, e + 1, 1)};
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) K(d[i], d[j]) += ka(i, j), M(d[i], d[j]) += me(i, j);
    }
  }
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, nd);
  C(0, dof(0, 0, 0)) = 1.0;
  C(1, dof(1, 0, 0)) = 1.0, C(1, dof(0, static_cast<int>(std::lround(ref.x0[1] / h)), 0)) = -1.0;
  C(2, dof(1, n, 0)) = 2.0, C(2, dof(0, 0, 0)) = -1.0, C(2, dof(2, 0, 0)) = -1.0;
  return constrainedFrequencies(K, M, C, count);
}

// The model's modes at its initial (unloaded) state; throws if the analysis fails.
ModalResult modelModes(const std::string &text, int count)
{
  const Scene scene = parseScene(text, "clean-eigenpairs.yaml");
  Model model(scene);
  Assembler assembler(model);
  Vec x, lambda;
  check(assembler.setUp(PETSC_COMM_WORLD));
  check(assembler.createVector(&x));
  check(assembler.createVector(&lambda));
  check(assembler.initialState(x));
  check(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  ModalResult modes;
  const PetscErrorCode ierr = solveModes(assembler, 0.0, x, lambda, count, &modes);
  VecDestroy(&x);
  VecDestroy(&lambda);
  check(ierr);
  return modes;
}

std::string cantilever(int elements, double tipMass)
{
  std::string s = "name: clean-eigenpairs\nanalysis: modal\nbodies:\n  - {name: boom, length: 2.0, elements: " +
                  std::to_string(elements) + ", section: {EA: 8.5176e8, EI: 4.9531e6, rhoA: 31.8396}}\n" +
                  "constraints:\n  - {type: clamp, body: boom, at: start}\nmodal: {count: 4}\n";
  if (tipMass > 0) s += "masses:\n  - {body: boom, at: end, mass: " + std::to_string(tipMass) + "}\n";
  return s;
}

void expectFiniteModesMatch(const ModalResult &modes, const std::vector<double> &reference, int count, const char *what)
{
  ASSERT_EQ(static_cast<int>(modes.frequencyHz.size()), count) << what;
  ASSERT_EQ(static_cast<int>(reference.size()), count) << what;
  for (int k = 0; k < count; ++k) {
    EXPECT_TRUE(std::isfinite(modes.omega2[k]) && modes.omega2[k] > 0) << what << " mode " << k + 1 << ": omega^2 = " << modes.omega2[k];
    const double rel = std::abs(modes.frequencyHz[k] - reference[k]) / reference[k];
    PetscPrintf(PETSC_COMM_WORLD, "  %s mode %d: %.9f Hz, Hermite reference %.9f Hz, relative difference %.1e\n", what,
                k + 1, modes.frequencyHz[k], reference[k], rel);
    EXPECT_LT(rel, 1e-8) << what << " mode " << k + 1;
  }
}

} // namespace

class CleanEigenpairs : public ::testing::TestWithParam<std::tuple<int, double>> {};

// Before the fix, 2 and 3 elements (and 4 with a tip mass at other counts)
// returned omega^2 ~ -5e36 ("f = 0.000000 Hz") and dropped a real mode.
TEST_P(CleanEigenpairs, CantileverGivesRequestedFiniteModes)
{
  const int n = std::get<0>(GetParam());
  const double tipMass = std::get<1>(GetParam());
  const int finite = 4 * (n + 1) - 3; // all finite modes of the clamped cantilever
  for (int count : {std::min(4, finite), std::min(8, finite), finite}) {
    const ModalResult modes = modelModes(cantilever(n, tipMass), count);
    char what[64];
    std::snprintf(what, sizeof what, "%d el., tip %g kg, %d of %d", n, tipMass, count, finite);
    expectFiniteModesMatch(modes, cantileverReference(n, tipMass, count), count, what);
  }
}

INSTANTIATE_TEST_SUITE_P(ElementsAndTipMass, CleanEigenpairs,
                         ::testing::Combine(::testing::Values(1, 2, 3, 4), ::testing::Values(0.0, 100.0)),
                         [](const auto &info) {
                           return std::to_string(std::get<0>(info.param)) + "Elements" +
                                  (std::get<1>(info.param) > 0 ? "TipMass" : "");
                         });

// More modes than the pencil has finite eigenvalues is a clear error, not a
// list padded with infinite ones.
TEST(CleanEigenpairsErrors, MoreModesThanFiniteEigenvaluesIsRefused)
{
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  EXPECT_THROW(modelModes(cantilever(1, 0.0), 6), PetscCallFailed); // 8 coordinates - 3 clamp rows = 5
  PetscPopErrorHandler();
}

class CleanTelescopeModes : public ::testing::TestWithParam<bool> {};

TEST_P(CleanTelescopeModes, EveryModeMatchesHermiteReference)
{
  const bool extended = GetParam();
  TelescopeReference ref;
  ref.g = 0;
  ref.h = 0.125; // the model's 16 elements per boom: the references are the same discrete system
  if (extended) ref.x0[1] = 1.5, ref.x0[2] = 3.0;
  char text[4096];
  std::snprintf(text, sizeof text, R"(
name: clean-telescope
analysis: modal
bodies:
  - {name: boom1, length: 2.0, elements: 16, origin: [%.12g, 0], section: {E: 2.1e11, rho: 7850, A: 6.944e-3, I: 6.395214e-5}}
  - {name: boom2, length: 2.0, elements: 16, origin: [%.12g, 0], section: {E: 2.1e11, rho: 7850, A: 5.264e-3, I: 3.720306e-5}}
  - {name: boom3, length: 2.0, elements: 16, origin: [%.12g, 0], section: {E: 2.1e11, rho: 7850, A: 3.816e-3, I: 1.986431e-5}}
constraints:
  - {type: clamp, name: base, body: boom1, at: start}
  - {type: sliding_joint, name: j1, body: boom1, at: end, track: boom2}
  - {type: sliding_joint, name: j2, body: boom2, at: start, track: boom1}
  - {type: sliding_joint, name: j3, body: boom2, at: end, track: boom3}
  - {type: sliding_joint, name: j4, body: boom3, at: start, track: boom2}
  - {type: extraction_drive, name: extraction, joint: j2, displacement: 0}
  - {type: rope, name: rope, from: boom1, from_at: start, pulley: boom2, pulley_at: end, to: boom3, to_at: start}
modal: {count: 10}
)",
                ref.x0[0], ref.x0[1], ref.x0[2]);
  const int count = 10;
  std::vector<double> reference = ref.frequencies(count), axial = telescopeAxialReference(ref, count);
  reference.insert(reference.end(), axial.begin(), axial.end());
  std::sort(reference.begin(), reference.end());
  reference.resize(count);
  expectFiniteModesMatch(modelModes(text, count), reference, count, extended ? "telescope extended" : "telescope retracted");
}

INSTANTIATE_TEST_SUITE_P(Configurations, CleanTelescopeModes, ::testing::Values(false, true),
                         [](const auto &info) { return std::string(info.param ? "Extended" : "Retracted"); });
