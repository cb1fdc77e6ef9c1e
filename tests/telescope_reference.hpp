// Independent reference for the paper's three-boom telescope, written for the
// tests only: each boom a linear Euler-Bernoulli beam of exact Hermite
// elements (consistent mass), the booms coupled at the four pads by equal
// transverse displacement (the linearized normal condition of a frictionless
// sliding joint), boom 1 clamped at x = 0. Dense Eigen algebra throughout.
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace boomdyn::testing {

struct TelescopeReference {
  double length = 2.0, E = 2.1e11, rho = 7850, g = 9.81, tipLoad = 0;
  double A[3] = {6.944e-3, 5.264e-3, 3.816e-3};
  double I[3] = {6.395214e-5, 3.720306e-5, 1.986431e-5};
  double x0[3] = {0.0, 0.25, 0.5}; // boom starts
  double h = 0.05;                 // reference element length (every pad lies on a node)

  int elements() const { return static_cast<int>(std::lround(length / h)); }
  int dof(int boom, int node, int k) const { return boom * 2 * (elements() + 1) + 2 * node + k; }
  int size() const { return 3 * 2 * (elements() + 1); }

  // Stiffness, mass, load, and the constraint rows (clamp + 4 pads).
  void assemble(Eigen::MatrixXd &K, Eigen::MatrixXd &M, Eigen::VectorXd &f, Eigen::MatrixXd &C) const
  {
    const int n = elements(), nd = size();
    K.setZero(nd, nd), M.setZero(nd, nd), f.setZero(nd);
    for (int b = 0; b < 3; ++b) {
      const double EI = E * I[b], rhoA = rho * A[b], q = -rhoA * g;
      Eigen::Matrix4d ke, me;
      ke << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h, 6 * h, 2 * h * h,
        -6 * h, 4 * h * h;
      ke *= EI / (h * h * h);
      me << 156, 22 * h, 54, -13 * h, 22 * h, 4 * h * h, 13 * h, -3 * h * h, 54, 13 * h, 156, -22 * h, -13 * h,
        -3 * h * h, -22 * h, 4 * h * h;
      me *= rhoA * h / 420.0;
      const Eigen::Vector4d fe(q * h / 2, q * h * h / 12, q * h / 2, -q * h * h / 12);
      for (int e = 0; e < n; ++e) {
        const int d[4] = {dof(b, e, 0), dof(b, e, 1), dof(b, e + 1, 0), dof(b, e + 1, 1)};
        for (int i = 0; i < 4; ++i) {
          f[d[i]] += fe[i];
          for (int j = 0; j < 4; ++j) K(d[i], d[j]) += ke(i, j), M(d[i], d[j]) += me(i, j);
        }
      }
    }
    f[dof(2, n, 0)] -= tipLoad;
    // Pads (slider boom, track boom, x): j1 boom1 end on boom2, j2 boom2 start on boom1,
    // j3 boom2 end on boom3, j4 boom3 start on boom2.
    struct Pad { int a, b; double x; };
    const Pad pads[4] = {{0, 1, x0[0] + length}, {1, 0, x0[1]}, {1, 2, x0[1] + length}, {2, 1, x0[2]}};
    C.setZero(6, nd);
    C(0, dof(0, 0, 0)) = C(1, dof(0, 0, 1)) = 1.0;
    for (int p = 0; p < 4; ++p) {
      C(2 + p, dof(pads[p].a, static_cast<int>(std::lround((pads[p].x - x0[pads[p].a]) / h)), 0)) = 1.0;
      C(2 + p, dof(pads[p].b, static_cast<int>(std::lround((pads[p].x - x0[pads[p].b]) / h)), 0)) = -1.0;
    }
  }

  // Static tip deflection (y of boom 3's end).
  double tipDeflection() const
  {
    Eigen::MatrixXd K, M, C;
    Eigen::VectorXd f;
    assemble(K, M, f, C);
    const int nd = size(), nc = static_cast<int>(C.rows());
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(nd + nc, nd + nc);
    S.topLeftCorner(nd, nd) = K;
    S.topRightCorner(nd, nc) = C.transpose();
    S.bottomLeftCorner(nc, nd) = C;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nd + nc);
    rhs.head(nd) = f;
    const Eigen::VectorXd u = S.fullPivLu().solve(rhs);
    return u[dof(2, elements(), 0)];
  }

  // Lowest `count` frequencies (Hz) of the constrained system, by a null-space basis.
  std::vector<double> frequencies(int count) const
  {
    Eigen::MatrixXd K, M, C;
    Eigen::VectorXd f;
    assemble(K, M, f, C);
    const Eigen::MatrixXd Z = C.fullPivLu().kernel();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Z.transpose() * K * Z, Z.transpose() * M * Z);
    std::vector<double> out;
    for (int k = 0; k < count; ++k) out.push_back(std::sqrt(es.eigenvalues()[k]) / (2 * M_PI));
    return out;
  }
};

} // namespace boomdyn::testing
