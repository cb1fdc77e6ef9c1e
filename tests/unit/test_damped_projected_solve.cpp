// solveShifted (damped_mode_refinement.hpp), the dense complex solve of the
// damped refinement's projected quadratic problem, against Eigen's complex
// LU of T(l) = K + l D + l^2 M built explicitly, and its report of a singular
// T(l) (l an eigenvalue).
#include <gtest/gtest.h>

#include "boomdyn/damped_mode_refinement.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <complex>

namespace {

using Complex = std::complex<double>;

// Symmetric p x p matrices of the sizes and scales of the paper scene's
// projections (K ~ omega^2 M, D a percent-level damping).
void pencil(int p, Eigen::MatrixXd *K, Eigen::MatrixXd *D, Eigen::MatrixXd *M)
{
  Eigen::MatrixXd A(p, p), B(p, p);
  for (int i = 0; i < p; ++i)
    for (int j = 0; j < p; ++j) A(i, j) = std::sin(1.3 * i + 0.7 * j + 0.1 * i * j), B(i, j) = std::cos(0.9 * i - 0.4 * j);
  *M = B * B.transpose() + p * Eigen::MatrixXd::Identity(p, p);
  *K = 1e4 * (A * A.transpose() + Eigen::MatrixXd::Identity(p, p));
  *D = 1e-2 * *K + 0.5 * *M;
}

Eigen::VectorXcd rightHandSide(int p)
{
  Eigen::VectorXcd b(p);
  for (int i = 0; i < p; ++i) b[i] = Complex(std::cos(0.3 * i), std::sin(0.8 * i + 0.2));
  return b;
}

} // namespace

TEST(DampedProjectedSolve, MatchesComplexLuOfTheAssembledMatrix)
{
  for (int p : {1, 5, 19, 30}) {
    Eigen::MatrixXd K, D, M;
    pencil(p, &K, &D, &M);
    const Eigen::VectorXcd b = rightHandSide(p);
    for (Complex l : {Complex(-0.8, 170.0), Complex(-3.0, 45.0), Complex(0.0, 1.0), Complex(2.0, -7.0)}) {
      const Eigen::MatrixXcd T = K.cast<Complex>() + l * D.cast<Complex>() + (l * l) * M.cast<Complex>();
      const Eigen::VectorXcd expected = Eigen::PartialPivLU<Eigen::MatrixXcd>(T).solve(b);
      Eigen::VectorXcd z;
      ASSERT_TRUE(boomdyn::solveShifted(K, D, M, l, b, &z)) << "p = " << p;
      ASSERT_EQ(z.size(), p);
      // Both are backward stable: agree to round-off times the condition.
      EXPECT_LE((z - expected).norm(), 1e-10 * expected.norm()) << "p = " << p << ", l = " << l;
      EXPECT_LE((T * z - b).norm(), 1e-12 * (T.norm() * z.norm() + b.norm())) << "p = " << p << ", l = " << l;
    }
  }
}

TEST(DampedProjectedSolve, ReportsASingularShift)
{
  // l = 0 with a singular K: T(0) = K has a zero pivot (exactly, a zero row).
  const int p = 6;
  Eigen::MatrixXd K, D, M;
  pencil(p, &K, &D, &M);
  K.row(2).setZero();
  K.col(2).setZero();
  Eigen::VectorXcd z;
  EXPECT_FALSE(boomdyn::solveShifted(K, D, M, Complex(0.0, 0.0), rightHandSide(p), &z));
}
