// Static cantilever: small-load tip deflection against P L^3 / (3 EI), and
// large deflections against the inextensible elastica (closed form with
// elliptic integrals, Bisshopp & Drucker 1945), with the mesh-convergence
// rate measured and printed.
#include "support.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

constexpr double L = 2.0, EI = 4.9531e6;

Scene cantilever(int elements, double tipLoad, double EA, int loadSteps)
{
  const std::string text = "name: cantilever\nanalysis: static\nbodies:\n  - name: boom\n    length: 2.0\n    elements: " +
                           std::to_string(elements) + "\n    section: {EA: " + std::to_string(EA) +
                           ", EI: 4.9531e6, rhoA: 31.84}\nconstraints:\n  - {type: clamp, body: boom, at: start}\n"
                           "loads:\n  - {type: point_force, body: boom, at: end, force: [0, " +
                           std::to_string(-tipLoad) + "]}\nstatic: {load_steps: " + std::to_string(loadSteps) +
                           "}\noutput:\n  sensors:\n    - {name: tip, body: boom, at: end}\n";
  return parseScene(text, "cantilever.yaml");
}

// Inextensible elastica, cantilever with a tip force perpendicular to the
// undeformed axis, k = P L^2 / EI. With the tip rotation phi0,
//   sqrt(k) = K(p) - F(theta1, p),  p = sin(pi/4 + phi0/2),  sin(theta1) = 1/(p sqrt 2)
//   v/L = 1 - 2 (E(p) - E(theta1, p)) / sqrt(k)        (vertical tip deflection)
//   x/L = sqrt(2 sin(phi0) / k)                          (horizontal tip position)
struct Elastica {
  double v, u; // deflection and shortening, divided by L
};

Elastica elastica(double k)
{
  auto residual = [&](double phi0) {
    const double p = std::sin(M_PI / 4 + phi0 / 2);
    const double theta1 = std::asin(1.0 / (p * std::sqrt(2.0)));
    return std::comp_ellint_1(p) - std::ellint_1(p, theta1) - std::sqrt(k);
  };
  double lo = 1e-9, hi = M_PI / 2 - 1e-12; // residual increases with phi0
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) < 0 ? lo : hi) = mid;
  }
  const double phi0 = 0.5 * (lo + hi), p = std::sin(M_PI / 4 + phi0 / 2);
  const double theta1 = std::asin(1.0 / (p * std::sqrt(2.0)));
  Elastica e;
  e.v = 1.0 - 2.0 * (std::comp_ellint_2(p) - std::ellint_2(p, theta1)) / std::sqrt(k);
  e.u = 1.0 - std::sqrt(2.0 * std::sin(phi0) / k);
  return e;
}

// Extensible elastica of the element's own continuum model (docs/model.md
// §1.1): r' = lambda (cos th, sin th), Green strain eps = (lambda^2 - 1)/2,
// curvature K = r' x r'' / |r'|^2 = th'. With the tip force (0, -P),
// stationarity of U - F.r(L) gives, with s the undeformed arc length,
//   EA eps lambda = -P sin th   (axial force balance, solved for lambda),
//   EI th'' = P lambda cos th,  th(0) = 0, th'(L) = 0,
// solved by shooting on th'(0) with RK4 on 4000 steps (error ~1e-13).
Elastica extensibleElastica(double k, double axialRatio)
{
  // Lengths in L, forces in EI/L^2: th'' = k lambda cos th, (lambda^3 - lambda)/2 = -(k/axialRatio) sin th.
  const double c = k / axialRatio;
  const auto stretch = [&](double th) {
    double lam = 1.0;
    for (int i = 0; i < 50; ++i) {
      const double g = 0.5 * (lam * lam * lam - lam) + c * std::sin(th), dg = 0.5 * (3 * lam * lam - 1);
      const double step = g / dg;
      lam -= step;
      if (std::abs(step) < 1e-16) break;
    }
    return lam;
  };
  struct State {
    double th, dth, x, y;
  };
  const auto rate = [&](const State &z) {
    const double lam = stretch(z.th);
    return State{z.dth, k * lam * std::cos(z.th), lam * std::cos(z.th), lam * std::sin(z.th)};
  };
  const auto shoot = [&](double slope0) {
    const int steps = 4000;
    const double h = 1.0 / steps;
    State z{0, slope0, 0, 0};
    const auto axpy = [](const State &a, double t, const State &b) {
      return State{a.th + t * b.th, a.dth + t * b.dth, a.x + t * b.x, a.y + t * b.y};
    };
    for (int i = 0; i < steps; ++i) {
      const State k1 = rate(z), k2 = rate(axpy(z, h / 2, k1)), k3 = rate(axpy(z, h / 2, k2)), k4 = rate(axpy(z, h, k3));
      z = State{z.th + h / 6 * (k1.th + 2 * k2.th + 2 * k3.th + k4.th),
                z.dth + h / 6 * (k1.dth + 2 * k2.dth + 2 * k3.dth + k4.dth),
                z.x + h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x), z.y + h / 6 * (k1.y + 2 * k2.y + 2 * k3.y + k4.y)};
    }
    return z;
  };
  // th'(L) grows with th'(0) in [-k lambda_max, 0]: bisection.
  double lo = -2.0 * k, hi = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (shoot(mid).dth < 0 ? lo : hi) = mid;
  }
  const State tip = shoot(0.5 * (lo + hi));
  return Elastica{-tip.y, 1.0 - tip.x};
}

// Relative tip error of a static cantilever run against a reference.
double tipError(const StaticOutcome &out, const Elastica &ref)
{
  const double v = -out.sensors[0].position.y() / L, u = 1.0 - out.sensors[0].position.x() / L;
  return std::hypot(v - ref.v, u - ref.u) / std::hypot(ref.v, ref.u);
}

// Reference of the locking study: extensible below EA L^2/EI = 1e9,
// inextensible from there on (they differ by ~k / (EA L^2/EI)).
Elastica lockingReference(double k, double axialRatio)
{
  return axialRatio < 1e9 ? extensibleElastica(k, axialRatio) : elastica(k);
}

using Axial = SectionSpec::AxialIntegration;

StaticOutcome runCantilever(int elements, double k, double axialRatio, Axial axial)
{
  Scene scene = cantilever(elements, k * EI / (L * L), axialRatio * EI / (L * L), static_cast<int>(2 * k) + 2);
  scene.bodies[0].section.axialIntegration = axial;
  return runStatic(scene);
}

} // namespace

TEST(CantileverStatics, SmallTipLoadMatchesBeamTheory)
{
  // P L^3/(3 EI) is the inextensible linear result; EA/EI = 1e8 keeps axial
  // stretch and geometric nonlinearity (tip slope 2e-4) below 1e-5 relative.
  const double P = 10.0;
  const StaticOutcome out = runStatic(cantilever(8, P, 1e8 * EI / (L * L), 1));
  ASSERT_TRUE(out.converged);
  const double exact = P * L * L * L / (3 * EI);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank) return;
  const double deflection = -out.sensors[0].position.y();
  PetscPrintf(PETSC_COMM_WORLD, "  tip deflection %.10e m, P L^3/(3 EI) = %.10e m, relative error %.2e\n", deflection, exact,
              std::abs(deflection - exact) / exact);
  EXPECT_LT(std::abs(deflection - exact) / exact, 1e-4);
  EXPECT_LT(out.violation, 1e-12);
}

TEST(CantileverStatics, LargeDeflectionMatchesElastica)
{
  // Nearly inextensible (EA L^2 / EI = 1e7) so the extensible ANCF model
  // approaches the inextensible elastica.
  const double EA = 1e7 * EI / (L * L);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (double k : {1.0, 2.0, 3.0, 5.0, 7.5, 10.0}) {
    const Elastica ref = elastica(k);
    const double P = k * EI / (L * L);
    double previous = 0;
    for (int n : {4, 8, 16}) {
      const StaticOutcome out = runStatic(cantilever(n, P, EA, static_cast<int>(2 * k) + 2));
      ASSERT_TRUE(out.converged) << "k = " << k << ", " << n << " elements";
      if (rank) continue;
      const double v = -out.sensors[0].position.y() / L, u = 1.0 - out.sensors[0].position.x() / L;
      const double err = std::hypot(v - ref.v, u - ref.u) / std::hypot(ref.v, ref.u);
      PetscPrintf(PETSC_COMM_WORLD, "  PL^2/EI = %4.1f, %2d elements: v/L = %.6f (elastica %.6f), u/L = %.6f (elastica %.6f), error %.2e%s\n",
                  k, n, v, ref.v, u, ref.u, err,
                  previous > 0 ? (" rate " + std::to_string(std::log2(previous / err))).c_str() : "");
      if (n == 16) {
        EXPECT_LT(std::abs(v - ref.v) / ref.v, 1e-3) << "k = " << k;
        EXPECT_LT(std::abs(u - ref.u) / ref.u, 1e-3) << "k = " << k;
      }
      previous = err;
    }
  }
}

TEST(CantileverStatics, ElasticaReferenceMatchesPublishedTable)
{
  // Guards the closed form itself: tip deflection and shortening of
  // Bisshopp & Drucker (1945), as tabulated by Mattiasson (1981).
  EXPECT_NEAR(elastica(1.0).v, 0.30172, 2e-5);
  EXPECT_NEAR(elastica(1.0).u, 0.05643, 2e-5);
  EXPECT_NEAR(elastica(2.0).v, 0.49346, 2e-5);
  EXPECT_NEAR(elastica(2.0).u, 0.16064, 2e-5);
  EXPECT_NEAR(elastica(10.0).v, 0.81061, 2e-5);
  EXPECT_NEAR(elastica(10.0).u, 0.55500, 2e-5);
}

TEST(CantileverStatics, ExtensibleElasticaApproachesInextensible)
{
  // The shooting reference against the closed form: the difference is the
  // stretch, O(k / (EA L^2/EI)), and the integration error (~1e-13).
  for (double k : {1.0, 3.0, 10.0}) {
    const Elastica inext = elastica(k), ext = extensibleElastica(k, 1e11);
    EXPECT_NEAR(ext.v, inext.v, 1e-9) << "k = " << k;
    EXPECT_NEAR(ext.u, inext.u, 1e-9) << "k = " << k;
    const Elastica soft = extensibleElastica(k, 1e3);
    EXPECT_GT(std::abs(soft.v - inext.v), 1e-4) << "the stretch must show at EA L^2/EI = 1e3";
  }
}

TEST(CantileverStatics, ReducedAxialIntegrationRemovesCoarseMeshLocking)
{
  // docs/verification.md "Membrane locking", PL^2/EI = 3. With the axial
  // energy on 3 Gauss points the error no longer grows with EA L^2/EI: at 8
  // elements it stays <= 3e-3 from 1e5 to 1e11 (full integration: 6.8e-2 at
  // 1e11), at 16 elements <= 8e-4. In the unlocked range (1e5) the issue's
  // target holds: error at 16 elements <= 2e-4, rate (8 -> 16) >= 3.5. NOT
  // reached (measured, see the docs): that target at 1e7 and above, where
  // both integrations converge at rate ~2 towards the elastica.
  const double k = 3.0;
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (double ratio : {1e5, 1e7, 1e9, 1e11}) {
    const Elastica ref = lockingReference(k, ratio);
    const StaticOutcome coarse = runCantilever(8, k, ratio, Axial::Reduced), fine = runCantilever(16, k, ratio, Axial::Reduced);
    ASSERT_TRUE(coarse.converged && fine.converged) << "EA L^2/EI = " << ratio;
    if (rank) continue;
    const double e8 = tipError(coarse, ref), e16 = tipError(fine, ref), rate = std::log2(e8 / e16);
    PetscPrintf(PETSC_COMM_WORLD, "  EA L^2/EI = %.0e, reduced: error %.2e (8), %.2e (16), rate %.2f\n", ratio, e8, e16,
                rate);
    EXPECT_LT(e8, 3e-3) << "EA L^2/EI = " << ratio;
    EXPECT_LT(e16, 8e-4) << "EA L^2/EI = " << ratio;
    if (ratio == 1e5) {
      EXPECT_LT(e16, 2e-4);
      EXPECT_GT(rate, 3.5);
    }
  }
  // The locking that reduced integration removes: full integration at 1e11, 8 elements.
  const StaticOutcome locked = runCantilever(8, k, 1e11, Axial::Full);
  ASSERT_TRUE(locked.converged);
  if (!rank) EXPECT_GT(tipError(locked, lockingReference(k, 1e11)), 1e-2);
}

TEST(CantileverStatics, AssumedAxialStrainIsFreeOfMembraneLocking)
{
  // Issue 13 item 4, docs/verification.md "Membrane locking", PL^2/EI = 3,
  // -boom_axial_integration assumed. Against the extensible elastica below
  // EA L^2/EI = 1e9, the inextensible one from 1e9 on: error at 16 elements
  // <= 2e-4 and rate >= 3.5 between 8 and 16 and between 16 and 32 elements
  // at every ratio. Measured: 16 elements 6.5e-6 / 2.9e-5 / 3.1e-5 / 3.0e-5,
  // rates 3.9 to 5.5 (reduced: 8.8e-6 / 3.7e-4 / 6.9e-4 / 7.0e-4, rate 2 from 1e9).
  const double k = 3.0;
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (double ratio : {1e5, 1e7, 1e9, 1e11}) {
    const Elastica ref = lockingReference(k, ratio);
    double err[3];
    const int meshes[3] = {8, 16, 32};
    for (int i = 0; i < 3; ++i) {
      const StaticOutcome out = runCantilever(meshes[i], k, ratio, Axial::Assumed);
      ASSERT_TRUE(out.converged) << "EA L^2/EI = " << ratio << ", " << meshes[i] << " elements";
      err[i] = tipError(out, ref);
    }
    if (rank) continue;
    const double rate1 = std::log2(err[0] / err[1]), rate2 = std::log2(err[1] / err[2]);
    PetscPrintf(PETSC_COMM_WORLD, "  EA L^2/EI = %.0e, assumed: error %.2e (8), %.2e (16), %.2e (32), rates %.2f %.2f\n",
                ratio, err[0], err[1], err[2], rate1, rate2);
    EXPECT_LT(err[1], 2e-4) << "EA L^2/EI = " << ratio;
    EXPECT_GT(rate1, 3.5) << "EA L^2/EI = " << ratio;
    EXPECT_GT(rate2, 3.5) << "EA L^2/EI = " << ratio;
  }
}

TEST(CantileverStatics, MembraneLockingStudy)
{
  // The full table of docs/verification.md (about a minute): run with
  // BOOMDYN_LOCKING_STUDY=1 build/tests/verification_tests --gtest_filter='*LockingStudy'.
  if (!std::getenv("BOOMDYN_LOCKING_STUDY")) GTEST_SKIP() << "set BOOMDYN_LOCKING_STUDY=1 to run the study";
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (double k : {1.0, 3.0, 10.0})
    for (double ratio : {1e5, 1e7, 1e9, 1e11}) {
      const Elastica ref = lockingReference(k, ratio);
      for (Axial axial : {Axial::Full, Axial::Reduced, Axial::Assumed}) {
        std::string line;
        double previous = 0;
        for (int n : {2, 4, 8, 16, 32}) {
          const StaticOutcome out = runCantilever(n, k, ratio, axial);
          char cell[64];
          if (!out.converged) {
            std::snprintf(cell, sizeof cell, " | no conv.");
            previous = 0;
          } else {
            const double err = tipError(out, ref);
            if (previous > 0)
              std::snprintf(cell, sizeof cell, " | %.1e (%.1f)", err, std::log2(previous / err));
            else
              std::snprintf(cell, sizeof cell, " | %.1e", err);
            previous = err;
          }
          line += cell;
        }
        if (!rank)
          PetscPrintf(PETSC_COMM_WORLD, "| %g | %.0e | %s%s |\n", k, ratio, axial == Axial::Full ? "full" : axial == Axial::Reduced ? "reduced" : "assumed", line.c_str());
      }
    }
}
