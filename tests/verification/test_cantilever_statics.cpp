// Static cantilever: small-load tip deflection against P L^3 / (3 EI), and
// large deflections against the inextensible elastica (closed form with
// elliptic integrals, Bisshopp & Drucker 1945), with the mesh-convergence
// rate measured and printed.
#include "support.hpp"

#include <cmath>

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
