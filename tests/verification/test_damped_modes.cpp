// Damped modes by SLEPc PEP (include/boomdyn/damped_eigen_solver.hpp):
// (a) stiffness-proportional Kelvin-Voigt damping of a clamped cantilever,
//     D = eta K at the unstressed state, where every mode has exactly
//     zeta_n = eta omega_n / 2 and omega_d = omega_n sqrt(1 - zeta_n^2);
// (b) non-proportional damping (a spring-damper at the tip) against an
//     independent dense solution: M, D, K assembled here, the clamp rows
//     removed by a null-space basis, a scaled linearization solved by Eigen's QZ.
#include "boomdyn/assembler.hpp"
#include "boomdyn/damped_eigen_solver.hpp"
#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/scene_reader.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <slepcsys.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

using namespace boomdyn;

namespace {

std::string cantilever(int elements, const std::string &damping, const std::string &extra = "")
{
  return "name: damped-cantilever\nanalysis: modal\nbodies:\n  - name: boom\n    length: 2.0\n    elements: " +
         std::to_string(elements) + "\n    section: {EA: 8.5176e8, EI: 4.9531e6, rhoA: 31.8396" + damping + "}\n" +
         "constraints:\n  - {type: clamp, body: boom, at: start}\nmodal: {count: 3}\n" + extra;
}

// A model at its initial state, with the vectors the solvers take.
struct Linearization {
  Scene scene;
  Model model;
  Assembler assembler;
  Vec q = nullptr, lambda = nullptr;
  explicit Linearization(const std::string &text)
    : scene(parseScene(text, "damped-cantilever.yaml")), model(scene), assembler(model)
  {
    PetscCallAbort(PETSC_COMM_WORLD, SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
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
  }
  ~Linearization()
  {
    VecDestroy(&q);
    VecDestroy(&lambda);
  }
};

Eigen::MatrixXd dense(Mat A)
{
  Mat Ad;
  PetscInt m, n;
  const PetscScalar *a;
  PetscCallAbort(PETSC_COMM_WORLD, MatConvert(A, MATSEQDENSE, MAT_INITIAL_MATRIX, &Ad));
  PetscCallAbort(PETSC_COMM_WORLD, MatGetSize(Ad, &m, &n));
  PetscCallAbort(PETSC_COMM_WORLD, MatDenseGetArrayRead(Ad, &a));
  Eigen::MatrixXd out = Eigen::Map<const Eigen::MatrixXd>(a, m, n); // column major, lda = m
  PetscCallAbort(PETSC_COMM_WORLD, MatDenseRestoreArrayRead(Ad, &a));
  MatDestroy(&Ad);
  return out;
}

} // namespace

TEST(DampedModes, StiffnessProportionalCantileverHasExactRatios)
{
  // Undamped frequencies first: they fix eta = zeta1 / (pi f1) and the exact ratios.
  Linearization undamped(cantilever(16, ""));
  ModalResult modes;
  ASSERT_EQ(solveModes(undamped.assembler, 0.0, undamped.q, undamped.lambda, 3, &modes), 0);
  const double zeta1 = 0.02, f1 = modes.frequencyHz[0], eta = zeta1 / (M_PI * f1);
  char damping[128];
  std::snprintf(damping, sizeof damping, ", damping_ratio: %.17g, damping_frequency: %.17g", zeta1, f1);
  Linearization damped(cantilever(16, damping));
  DampedModalResult dm;
  ASSERT_EQ(solveDampedModes(damped.assembler, 0.0, damped.q, damped.lambda, 3, &dm), 0);
  ASSERT_EQ(dm.dampedOmega.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const double omega = std::sqrt(modes.omega2[k]), zeta = eta * omega / 2;
    const double omegaD = omega * std::sqrt(1 - zeta * zeta);
    const double eZeta = std::abs(dm.dampingRatio[k] - zeta) / zeta, eD = std::abs(dm.dampedOmega[k] - omegaD) / omegaD;
    PetscPrintf(PETSC_COMM_WORLD,
                "  mode %d: omega %.6f rad/s, zeta PEP %.10f exact %.10f (rel %.1e), omega_d PEP %.6f exact %.6f (rel %.1e)\n",
                k + 1, omega, dm.dampingRatio[k], zeta, eZeta, dm.dampedOmega[k], omegaD, eD);
    EXPECT_LT(eZeta, 1e-4) << "mode " << k + 1;
    EXPECT_LT(eD, 1e-4) << "mode " << k + 1;
    EXPECT_LT(std::abs(dm.omega[k] - omega) / omega, 1e-4) << "mode " << k + 1;
  }
}

TEST(DampedModes, TipDamperMatchesDenseReference)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size > 1) GTEST_SKIP() << "dense reference on one rank";
  // Non-proportional damping: light material damping plus a strong damper at the tip.
  Linearization lin(cantilever(4, ", eta_axial: 1e-4, eta_bending: 2e-4",
                               "springs:\n  - {name: s, body: boom, at: 2.0, point: [2.0, -1.0], stiffness: 1e5, "
                               "damping: 3000}\n"));
  const int count = 4;
  DampedModalResult dm;
  ASSERT_EQ(solveDampedModes(lin.assembler, 0.0, lin.q, lin.lambda, count, &dm), 0);

  Mat K, D, M;
  ASSERT_EQ(lin.assembler.createMatrix(&K), 0);
  ASSERT_EQ(lin.assembler.createMatrix(&D), 0);
  ASSERT_EQ(lin.assembler.createMatrix(&M), 0);
  ASSERT_EQ(assembleDamping(lin.assembler, 0.0, lin.q, lin.lambda, D), 0);
  ASSERT_EQ(assemblePencil(lin.assembler, 0.0, lin.q, lin.lambda, K, M), 0);
  const Eigen::MatrixXd Kf = dense(K), Df = dense(D), Mf = dense(M);
  MatDestroy(&K), MatDestroy(&D), MatDestroy(&M);
  const int nq = lin.model.numCoordinates(), nc = lin.model.numMultipliers();
  ASSERT_EQ(Kf.rows(), nq + nc);
  // Constraint rows C (any scale) and a basis Z of their null space: q = Z p.
  const Eigen::MatrixXd C = Kf.block(nq, 0, nc, nq);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
  const int rank = (int)(svd.singularValues().array() > 1e-12 * svd.singularValues()(0)).count();
  ASSERT_EQ(rank, nc);
  const Eigen::MatrixXd Z = svd.matrixV().rightCols(nq - nc);
  const Eigen::MatrixXd Kr = Z.transpose() * Kf.topLeftCorner(nq, nq) * Z, Dr = Z.transpose() * Df.topLeftCorner(nq, nq) * Z,
                        Mr = Z.transpose() * Mf.topLeftCorner(nq, nq) * Z;
  const int n = nq - nc;
  // Linearization A z = mu B z with A = [0 I; -K -s D], B = [I 0; 0 s^2 M],
  // lambda = s mu, s = sqrt(|K| / |M|) (Fan-Lin-Van Dooren scaling): solved
  // by the real QZ algorithm, no inverse of M.
  const double s = std::sqrt(Kr.norm() / Mr.norm());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n), B = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n) = Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(n, n) = -Kr;
  A.bottomRightCorner(n, n) = -s * Dr;
  B.topLeftCorner(n, n) = Eigen::MatrixXd::Identity(n, n);
  B.bottomRightCorner(n, n) = s * s * Mr;
  Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> qz(A, B, false);
  std::vector<std::complex<double>> ref;
  for (int i = 0; i < 2 * n; ++i) {
    const std::complex<double> lambda = s * qz.alphas()(i) / qz.betas()(i);
    // Modes: one of each conjugate pair (Im > 0) and the real eigenvalues
    // (overdamped motions, kept by the modal analysis since issue 40).
    if (lambda.imag() > 1e-10 * std::abs(lambda)) ref.push_back(lambda);
    else if (std::abs(lambda.imag()) <= 1e-10 * std::abs(lambda)) ref.push_back(lambda.real());
  }
  // The QZ values carry errors of ~1e-7 here (the ANCF gradient and position
  // coordinates make P badly scaled); Newton's method on det P(lambda),
  // lambda <- lambda - 1 / trace(P^-1 P'), refines each to round-off.
  for (std::complex<double> &lambda : ref) {
    const std::complex<double> fromQZ = lambda;
    const bool isReal = lambda.imag() == 0;
    for (int it = 0; it < 8; ++it) {
      const Eigen::MatrixXcd P = (lambda * lambda) * Mr.cast<std::complex<double>>() + lambda * Dr.cast<std::complex<double>>() +
                                 Kr.cast<std::complex<double>>();
      const Eigen::MatrixXcd dP = (2.0 * lambda) * Mr.cast<std::complex<double>>() + Dr.cast<std::complex<double>>();
      const std::complex<double> step = 1.0 / Eigen::FullPivLU<Eigen::MatrixXcd>(P).solve(dP).trace();
      lambda -= step;
      // Quadratic convergence: after a step below 1e-6 |lambda| the error is at
      // round-off, and P is then singular to working precision (a further
      // step would be noise).
      if (std::abs(step) < 1e-6 * std::abs(lambda)) break;
    }
    if (isReal) lambda = lambda.real(); // a real root of a real polynomial
    EXPECT_LT(std::abs(lambda - fromQZ), 1e-5 * std::abs(fromQZ)) << "Newton left the QZ eigenvalue";
  }
  // Ascending |lambda|, the order of the modal analysis (the damper makes
  // one real eigenvalue among the four smallest).
  std::sort(ref.begin(), ref.end(), [](auto a, auto b) { return std::abs(a) < std::abs(b); });
  ASSERT_GE((int)ref.size(), count);
  ASSERT_EQ((int)dm.decayRates.size(), count);
  int real = 0;
  for (int k = 0; k < count; ++k) {
    const double eRate = std::abs(dm.decayRates[k][0] + ref[k].real()) / std::abs(ref[k].real());
    if (ref[k].imag() == 0) { // overdamped: no oscillation, no ratio of its own
      ++real;
      PetscPrintf(PETSC_COMM_WORLD, "  mode %d: real, decay rate PEP %.10f dense %.10f (rel %.1e), f_d %g\n", k + 1,
                  dm.decayRates[k][0], -ref[k].real(), eRate, dm.dampedOmega[k]);
      EXPECT_EQ(dm.dampedOmega[k], 0.0) << "mode " << k + 1;
      EXPECT_TRUE(std::isnan(dm.dampingRatio[k])) << "mode " << k + 1;
      EXPECT_LT(eRate, 1e-8) << "mode " << k + 1;
      continue;
    }
    const double zetaRef = -ref[k].real() / std::abs(ref[k]);
    const double eD = std::abs(dm.dampedOmega[k] - ref[k].imag()) / ref[k].imag();
    const double eZ = std::abs(dm.dampingRatio[k] - zetaRef) / zetaRef;
    PetscPrintf(PETSC_COMM_WORLD, "  mode %d: omega_d PEP %.10f dense %.10f (rel %.1e), zeta PEP %.10f dense %.10f (rel %.1e)\n",
                k + 1, dm.dampedOmega[k], ref[k].imag(), eD, dm.dampingRatio[k], zetaRef, eZ);
    EXPECT_LT(eD, 1e-8) << "mode " << k + 1;
    EXPECT_LT(eZ, 1e-8) << "mode " << k + 1;
    EXPECT_LT(eRate, 1e-8) << "mode " << k + 1;
  }
  EXPECT_EQ(real, 1) << "the damper's real eigenvalue is reported as an overdamped mode, not dropped";
}

TEST(DampedModes, OnlyPhysicalDampingTakesTheDampedPath)
{
  // Viscous LuGre friction (sigma1, sigma2) at the pads of two nested booms
  // is a slip law, not a damping of the vibration: the model keeps the
  // symmetric eigen-analysis. A Kelvin-Voigt section or a spring damper
  // selects the damped (PEP) one (Model::hasPhysicalDamping, used by the
  // modal analysis and the frequency tracking instead of a norm of D).
  auto booms = [](const std::string &damping) {
    return "name: nested\nanalysis: modal\ngravity: [0, -9.81]\nbodies:\n"
           "  - {name: boom1, length: 2.0, elements: 4, section: {E: 2.1e11, A: 6.944e-3, I: 3.6753355e-5, rho: 7850" +
           damping +
           "}}\n"
           "  - {name: boom2, length: 2.0, elements: 4, origin: [0.5, 0], section: {E: 2.1e11, A: 5.264e-3, I: "
           "2.1380634e-5, rho: 7850}}\n"
           "constraints:\n  - {type: clamp, name: base, body: boom1, at: start}\n"
           "  - {type: sliding_joint, name: j1, body: boom1, at: end, track: boom2, friction: {mu_s: 0.15, mu_c: 0.1, "
           "v_s: 1.0e-3, sigma0: 1.0e5, sigma1: 300, sigma2: 50}}\n"
           "  - {type: sliding_joint, name: j2, body: boom2, at: start, track: boom1, friction: {mu_s: 0.15, mu_c: "
           "0.1, v_s: 1.0e-3, sigma0: 1.0e5, sigma1: 300, sigma2: 50}}\nmodal: {count: 3}\n";
  };
  Linearization friction(booms(""));
  EXPECT_FALSE(friction.model.hasPhysicalDamping());
  EXPECT_TRUE(Linearization(booms(", eta_bending: 1.0e-4")).model.hasPhysicalDamping());
  const std::string spring = "springs:\n  - {name: s, body: boom, at: 2.0, point: [2.0, -1.0], stiffness: 1e5";
  EXPECT_TRUE(Linearization(cantilever(4, "", spring + ", damping: 3000}\n")).model.hasPhysicalDamping());
  EXPECT_FALSE(Linearization(cantilever(4, "", spring + "}\n")).model.hasPhysicalDamping());
  EXPECT_FALSE(Linearization(cantilever(4, "")).model.hasPhysicalDamping());
}

TEST(DampedModes, HeavyStiffnessProportionalDampingGivesOverdampedModesInClosedForm)
{
  // D = eta K (damping_ratio zeta1 at the first frequency f1, eta = zeta1 /
  // (pi f1)): every undamped mode is an eigenvector of the quadratic problem
  // with zeta_n = eta omega_n / 2 and eigenvalues
  //   lambda = -zeta_n omega_n +- omega_n sqrt(zeta_n^2 - 1),
  // two real decay rates omega_n (zeta_n -+ sqrt(zeta_n^2 - 1)) when
  // zeta_n > 1. zeta1 = 0.1 makes mode 3 overdamped (zeta_3 = 1.75), 1.0 mode
  // 1 critically damped (a double real eigenvalue), 2.0 every mode
  // overdamped. Issue 40: these were refused ("did not converge") or
  // reported with invented MHz modes and negative damping ratios.
  Linearization undamped(cantilever(16, ""));
  ModalResult plain;
  ASSERT_EQ(solveModes(undamped.assembler, 0.0, undamped.q, undamped.lambda, 3, &plain), 0);
  const double f1 = plain.frequencyHz[0];
  for (double zeta1 : {0.1, 1.0, 2.0}) {
    const double eta = zeta1 / (M_PI * f1);
    char damping[128];
    std::snprintf(damping, sizeof damping, ", damping_ratio: %.17g, damping_frequency: %.17g", zeta1, f1);
    Linearization damped(cantilever(16, damping));
    ModalResult modes;
    ModalOptions keep;
    keep.keepVectors = true;
    ASSERT_EQ(solveModes(damped.assembler, 0.0, damped.q, damped.lambda, 3, &modes, keep), 0);
    DampedModalOptions options;
    options.undamped = &modes;
    DampedModalResult dm;
    ASSERT_EQ(solveDampedModes(damped.assembler, 0.0, damped.q, damped.lambda, 3, &dm, options), 0);
    ASSERT_TRUE(dm.classical) << "zeta1 = " << zeta1;
    ASSERT_EQ(dm.decayRates.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      const double omega = std::sqrt(plain.omega2[k]), zeta = eta * omega / 2;
      const bool critical = std::abs(zeta - 1) < 1e-12;
      // Exact decay rates and damped frequency.
      double slow, fast, omegaD = 0;
      if (zeta < 1) {
        slow = fast = zeta * omega;
        omegaD = omega * std::sqrt(1 - zeta * zeta);
      } else {
        const double root = std::sqrt(zeta * zeta - 1);
        fast = omega * (zeta + root);
        slow = omega * omega / fast; // = omega (zeta - root) without cancellation
      }
      // A double root moves by omega sqrt(2 dzeta) for an error dzeta of zeta
      // (1.7e-12 on two ranks: 1.8e-6): 1e-5 there, 1e-8 elsewhere.
      const double tol = critical ? 1e-5 : 1e-8;
      const double eSlow = std::abs(dm.decayRates[k][0] - slow) / slow, eFast = std::abs(dm.decayRates[k][1] - fast) / fast;
      const double eZeta = std::abs(dm.dampingRatio[k] - zeta) / zeta;
      PetscPrintf(PETSC_COMM_WORLD,
                  "  zeta1 %.1f mode %d: zeta %.10f (exact %.10f, rel %.1e), decay rates %.8g %.8g 1/s (exact %.8g %.8g; "
                  "rel %.1e %.1e), f_d %.6g Hz (exact %.6g), residual %.1e\n",
                  zeta1, k + 1, dm.dampingRatio[k], zeta, eZeta, dm.decayRates[k][0], dm.decayRates[k][1], slow, fast,
                  eSlow, eFast, dm.dampedOmega[k] / (2 * M_PI), omegaD / (2 * M_PI), dm.residuals[k]);
      EXPECT_LT(eZeta, 1e-8) << "zeta1 " << zeta1 << " mode " << k + 1;
      EXPECT_LT(eSlow, tol) << "zeta1 " << zeta1 << " mode " << k + 1;
      EXPECT_LT(eFast, tol) << "zeta1 " << zeta1 << " mode " << k + 1;
      EXPECT_LT(std::abs(dm.omega[k] - omega) / omega, 1e-8) << "zeta1 " << zeta1 << " mode " << k + 1;
      if (zeta < 1 && !critical) EXPECT_LT(std::abs(dm.dampedOmega[k] - omegaD) / omegaD, 1e-8);
      // At critical damping omega_d = omega sqrt(1 - zeta^2) moves by
      // omega sqrt(2 dzeta) for an error dzeta of zeta (6.6e-13 here).
      else EXPECT_LE(dm.dampedOmega[k], (critical ? 1e-5 : 0.0) * omega) << "overdamped: no oscillation";
      EXPECT_LT(dm.residuals[k], 1e-8);
    }
  }
}
