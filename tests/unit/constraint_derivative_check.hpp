// Central finite-difference checks of a constraint kernel at random states
// near q0, shared by the planar and spatial kernel tests: the Jacobian C_q,
// the multiplier-weighted Hessian H = d(C_q^T w)/dq, the acceleration-level
// term gamma (d2C/dt2 along q + tau v + tau^2/2 a equals C_q a + gamma) and,
// for time-dependent rows, dC/dt at fixed q.
#pragma once

#include "boomdyn/constraint.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace boomdyn::testing {

// q0 at the constraint's coordinates plus uniform noise in [-spread, spread].
inline std::vector<double> randomNear(const std::vector<PetscInt> &dofs, const std::vector<double> &q0,
                                      std::mt19937 &rng, double spread)
{
  std::uniform_real_distribution<double> u(-spread, spread);
  std::vector<double> q(dofs.size());
  for (std::size_t i = 0; i < dofs.size(); ++i) q[i] = q0[dofs[i]] + u(rng);
  return q;
}

inline void checkConstraintDerivatives(const Constraint &c, const std::vector<double> &q0, unsigned seed,
                                       double spread)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<PetscInt> dofs;
  c.coordinates(dofs);
  const int n = static_cast<int>(dofs.size()), m = c.numRows();
  for (int trial = 0; trial < 4; ++trial) {
    const double t = 0.37 + trial;
    std::vector<double> q = randomNear(dofs, q0, rng, spread), v(n), a(n), w(m);
    for (auto *vec : {&v, &a, &w})
      for (double &x : *vec) x = u(rng);
    ConstraintEval ev;
    c.evaluate(t, q.data(), v.data(), w.data(), ev);
    ASSERT_EQ(ev.C.size(), m);
    ASSERT_EQ(ev.Cq.rows(), m);
    ASSERT_EQ(ev.Cq.cols(), n);
    const double h = 1e-6;
    Eigen::MatrixXd fd(m, n), fdH(n, n);
    const Eigen::Map<const Eigen::VectorXd> wv(w.data(), m);
    for (int j = 0; j < n; ++j) {
      auto qp = q, qm = q;
      qp[j] += h, qm[j] -= h;
      ConstraintEval ep, em;
      c.evaluate(t, qp.data(), nullptr, nullptr, ep);
      c.evaluate(t, qm.data(), nullptr, nullptr, em);
      fd.col(j) = (ep.C - em.C) / (2 * h);
      fdH.col(j) = (ep.Cq.transpose() * wv - em.Cq.transpose() * wv) / (2 * h);
    }
    EXPECT_LT((ev.Cq - fd).norm(), 1e-7 * (1.0 + fd.norm())) << c.name() << " C_q";
    EXPECT_LT((ev.H - fdH).norm(), 1e-6 * (1.0 + fdH.norm())) << c.name() << " H";
    const double ht = 1e-4;
    auto path = [&](double tau) {
      std::vector<double> qt(n);
      for (int j = 0; j < n; ++j) qt[j] = q[j] + tau * v[j] + 0.5 * tau * tau * a[j];
      ConstraintEval e;
      c.evaluate(t + tau, qt.data(), nullptr, nullptr, e);
      return Eigen::VectorXd(e.C);
    };
    const Eigen::VectorXd d2 = (path(ht) - 2.0 * path(0.0) + path(-ht)) / (ht * ht);
    const Eigen::VectorXd predicted = ev.Cq * Eigen::Map<const Eigen::VectorXd>(a.data(), n) + ev.gamma;
    EXPECT_LT((predicted - d2).norm(), 1e-5 * (1.0 + d2.norm())) << c.name() << " gamma";
    if (c.dependsOnTime()) {
      ConstraintEval ep, em;
      c.evaluate(t + h, q.data(), nullptr, nullptr, ep);
      c.evaluate(t - h, q.data(), nullptr, nullptr, em);
      EXPECT_LT((ev.Ct - (ep.C - em.C) / (2 * h)).norm(), 1e-7) << c.name() << " C_t";
    }
  }
}

} // namespace boomdyn::testing
