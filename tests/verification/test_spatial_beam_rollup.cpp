// Roll-up of a spatial cantilever under an end moment (docs/model.md §1.7,
// docs/verification.md): the exact solution is a circular arc of radius EI/M,
// tip at L sin(phi)/phi along the beam and L (1 - cos phi)/phi across it,
// phi = M L / EI. At M = pi EI/L (a half circle) and 2 pi EI/L (a full
// circle, the tip back at the clamp), about a principal axis and about an
// axis at 45 degrees between the principal axes of a section with EIy = EIz;
// tip error within 1e-4 L at 16 elements, convergence rate 4 (measured
// 3.9-4.0 from 4 to 32 elements), no torsion.
#include "verification/spatial_beam_assembly.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace boomdyn::spatial_beam;
using namespace boomdyn::spatial_beam::verification;

namespace {

// A slender box (L/h = 25): EA L^2/EI ~ 4e3.
Section rollSection(bool equalBending)
{
  Section s = boxSection(2.1e11, 8.1e10, 7850, 0.3, equalBending ? 0.3 : 0.4, 0.01);
  s.axialIntegration = AxialIntegration::Assumed;
  return s;
}

// Tip error / L of the roll-up with moment axis m (unit, ⊥ x) and angle phi.
double rollUpError(const Section &sec, double L, int elements, const Vec3 &m, double EI, double phi, int steps)
{
  Cantilever b(sec, L, elements);
  const Vec3 M = (phi * EI / L) * m;
  EXPECT_TRUE(solveTipMoment(b, M, steps)) << elements << " elements, phi " << phi;
  // The moment stays normal to the tangent: no torsion anywhere.
  for (int i = 0; i < elements; ++i)
    EXPECT_LT(std::abs(strainsAt(b.geometry(i), b.element(i), 0.5).torsion), 1e-9 / L) << "element " << i;
  const Vec3 across = m.cross(Vec3::UnitX());
  const Vec3 exact = L * std::sin(phi) / phi * Vec3::UnitX() + L * (1 - std::cos(phi)) / phi * across;
  return (b.tip() - exact).norm() / L;
}

void checkRollUp(const Section &sec, const Vec3 &m, double EI, const char *what)
{
  const double L = 10.0;
  for (double phi : {M_PI, 2 * M_PI}) {
    double previous = 0;
    for (int n : {4, 8, 16, 32}) {
      const double err = rollUpError(sec, L, n, m, EI, phi, 16);
      std::printf("roll-up %s phi = %.4f: %2d elements, tip error %.3e L", what, phi, n, err);
      if (previous > 0) std::printf(", rate %.2f", std::log2(previous / err));
      std::printf("\n");
      if (n == 16) EXPECT_LT(err, 1e-4) << what << " phi " << phi;
      if (previous > 0 && n <= 16) EXPECT_GT(std::log2(previous / err), 3.5) << what << " " << n << " elements";
      previous = err;
    }
  }
}

} // namespace

TEST(SpatialBeamRollUp, MomentAboutAPrincipalAxisRollsTheBeamIntoACircle)
{
  const Section sec = rollSection(false);
  checkRollUp(sec, Vec3::UnitZ(), sec.EIz, "about d3");
  checkRollUp(sec, Vec3::UnitY(), sec.EIy, "about d2");
}

TEST(SpatialBeamRollUp, MomentAboutAnAxisAt45DegreesWithEqualBendingStiffnesses)
{
  const Section sec = rollSection(true);
  ASSERT_NEAR(sec.EIy, sec.EIz, 1e-12 * sec.EIy);
  checkRollUp(sec, Vec3(0, 1, 1).normalized(), sec.EIy, "about 45 deg");
}

// Objectivity of the static solution: the same cantilever, clamp, references
// and moment rotated as a whole by a large rotation about an arbitrary axis
// end in the rotated equilibrium (every node's position and slope rotated,
// the same twists, since the references turn with it) to 1e-10.
TEST(SpatialBeamRollUp, RotatedProblemHasTheRotatedSolution)
{
  const Section sec = rollSection(false);
  const double L = 10.0;
  const int n = 8;
  const Mat3 R = Eigen::AngleAxisd(2.3, Vec3(0.3, -0.8, 0.5).normalized()).toRotationMatrix();
  // A moment with components about both principal axes and along the beam: bending and torsion.
  const Vec3 M = Vec3(0.4 * sec.GJ, 1.1 * sec.EIy, 2.0 * sec.EIz) / L;
  Cantilever a(sec, L, n, Mat3::Identity(), true), b(sec, L, n, R, true);
  ASSERT_TRUE(solveTipMoment(a, M, 16));
  ASSERT_TRUE(solveTipMoment(b, R * M, 16));
  double maxTwist = 0, maxDeviation = 0;
  for (int k = 0; k <= n; ++k) {
    const int o = kNodeCoordinates * k;
    EXPECT_LT((b.q.segment<3>(o) - R * a.q.segment<3>(o)).norm(), 1e-10 * L) << "node " << k;
    EXPECT_LT((b.q.segment<3>(o + 3) - R * a.q.segment<3>(o + 3)).norm(), 1e-10) << "node " << k;
    EXPECT_NEAR(b.q[o + 6], a.q[o + 6], 1e-10) << "node " << k;
    maxTwist = std::max(maxTwist, std::abs(a.q[o + 6]));
    maxDeviation = std::max(maxDeviation, (b.q.segment<3>(o) - R * a.q.segment<3>(o)).norm() / L);
  }
  EXPECT_GT(maxTwist, 0.1); // the moment does twist the beam
  std::printf("rotated roll-up: largest position deviation %.2e L, largest twist %.3f rad\n", maxDeviation, maxTwist);
}
