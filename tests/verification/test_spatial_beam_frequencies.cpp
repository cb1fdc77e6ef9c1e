// Natural frequencies of a spatial cantilever with EIy != EIz and GJ
// (docs/model.md §1.7, docs/verification.md) against the closed forms derived
// here: bending in each principal plane omega_n = (beta_n L)^2 / L^2
// sqrt(EI/rhoA) with cos(beta L) cosh(beta L) = -1, torsion
// omega_n = (2n - 1) pi/(2L) sqrt(GJ/rhoIp), axial omega_1 = pi/(2L)
// sqrt(EA/rhoA). The linearization is taken about the straight state (the
// tangent stiffness and the consistent mass of the dense assembly, node 0
// clamped); each mode is labelled by the share of its kinetic energy in the
// axial, lateral y, lateral z and twist coordinates. Measured (L = 40 m, box
// 0.3 x 0.4 x 0.01 m): at 128 elements the errors are 1.4e-10 (axial),
// <= 8e-8 (bending, the round-off floor), 6.3e-6 and 5.6e-5 (torsion 1, 2);
// rates 4 (axial, bending) and 2.00 (torsion).
#include "verification/spatial_beam_assembly.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

using namespace boomdyn::spatial_beam;
using namespace boomdyn::spatial_beam::verification;

namespace {

// Root of cos x cosh x + 1 near x0 (Newton).
double cantileverRoot(double x0)
{
  double x = x0;
  for (int i = 0; i < 50; ++i) {
    const double f = std::cos(x) * std::cosh(x) + 1.0;
    const double df = -std::sin(x) * std::cosh(x) + std::cos(x) * std::sinh(x);
    x -= f / df;
  }
  return x;
}

enum Kind { Axial = 0, BendingY = 1, BendingZ = 2, Torsion = 3 };

// Frequencies (rad/s) of each kind, ascending.
std::map<int, std::vector<double>> labelledFrequencies(const Section &sec, double L, int elements)
{
  Cantilever b(sec, L, elements);
  Eigen::VectorXd f;
  Eigen::MatrixXd K;
  b.internal(f, K);
  const Eigen::MatrixXd M = b.mass();
  const std::vector<int> free = b.freeIndices();
  const int n = static_cast<int>(free.size());
  const Eigen::MatrixXd Kf = K(free, free), Mf = M(free, free);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Kf, Mf);
  std::map<int, std::vector<double>> out;
  for (int m = 0; m < n; ++m) {
    const Eigen::VectorXd phi = eig.eigenvectors().col(m);
    double share[4] = {0, 0, 0, 0};
    for (int kind = 0; kind < 4; ++kind) {
      Eigen::VectorXd part = Eigen::VectorXd::Zero(n);
      for (int i = 0; i < n; ++i) {
        const int local = free[i] % kNodeCoordinates;
        const int k = local == 6 ? Torsion : local % 3;
        if (k == kind) part[i] = phi[i];
      }
      share[kind] = part.dot(Mf * part);
    }
    const int kind = static_cast<int>(std::max_element(share, share + 4) - share);
    const double total = share[0] + share[1] + share[2] + share[3];
    EXPECT_GT(share[kind], (1 - 1e-8) * total) << "mode " << m << " mixes kinds";
    out[kind].push_back(std::sqrt(eig.eigenvalues()[m]));
  }
  return out;
}

} // namespace

TEST(SpatialBeamFrequencies, CantileverBendingTorsionAndAxialFrequenciesConverge)
{
  const double L = 40.0; // L/h = 100: the Assumed axial strain is active (pointwise weight 0.1)
  const Section sec = boxSection(2.1e11, 8.1e10, 7850, 0.3, 0.4, 0.01);
  ASSERT_GT(std::abs(sec.EIy / sec.EIz - 1), 0.2);
  const double b1 = cantileverRoot(1.875), b2 = cantileverRoot(4.694);
  std::map<int, std::vector<double>> exact;
  // Lateral y is bending about d3 (EIz), lateral z about d2 (EIy).
  for (double beta : {b1, b2}) {
    exact[BendingY].push_back(beta * beta / (L * L) * std::sqrt(sec.EIz / sec.rhoA));
    exact[BendingZ].push_back(beta * beta / (L * L) * std::sqrt(sec.EIy / sec.rhoA));
  }
  for (int k = 1; k <= 2; ++k) exact[Torsion].push_back((2 * k - 1) * M_PI / (2 * L) * std::sqrt(sec.GJ / sec.rhoIp));
  exact[Axial].push_back(M_PI / (2 * L) * std::sqrt(sec.EA / sec.rhoA));
  const char *names[4] = {"axial", "bending y", "bending z", "torsion"};

  std::map<int, std::vector<double>> previous;
  for (int n : {8, 16, 32, 64, 128}) {
    const auto freq = labelledFrequencies(sec, L, n);
    for (const auto &[kind, ref] : exact) {
      for (size_t j = 0; j < ref.size(); ++j) {
        ASSERT_GT(freq.at(kind).size(), j);
        const double err = std::abs(freq.at(kind)[j] / ref[j] - 1);
        std::printf("%3d elements %-9s mode %zu: %.8e rad/s, exact %.8e, rel. error %.3e", n, names[kind], j + 1,
                    freq.at(kind)[j], ref[j], err);
        if (n > 8) {
          const double rate = std::log2(previous[kind][j] / err);
          std::printf(", rate %.2f", rate);
          // Linear twist interpolation with consistent inertia: rate 2. Cubic
          // Hermite centreline: rate 4, measured while the error is above the
          // dense eigensolver's round-off floor (~1e-8 here).
          if (kind == Torsion)
            EXPECT_NEAR(rate, 2.0, 0.05) << names[kind] << " mode " << j + 1 << ", " << n << " elements";
          else if (previous[kind][j] > 1e-6)
            EXPECT_GT(rate, 3.9) << names[kind] << " mode " << j + 1 << ", " << n << " elements";
        }
        std::printf("\n");
        if (n == 128) EXPECT_LT(err, 1e-4) << names[kind] << " mode " << j + 1;
        previous[kind].resize(ref.size());
        previous[kind][j] = err;
      }
    }
  }
}
