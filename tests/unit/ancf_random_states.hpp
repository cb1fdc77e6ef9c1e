// Random element states and the central-difference checks of the ANCF
// element (elastic, damping, reduced and assumed axial strain): shared so
// that every test draws its states and measures its errors the same way.
#pragma once

#include "boomdyn/ancf_element.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace boomdyn::ancf::element_states {

// Size of coordinate k: positions scale with the element length, slopes are ~1.
inline double coordinateScale(int k, double l) { return (k % 4) < 2 ? l : 1.0; }

// A straight element at a random place and direction, perturbed by amp (relative).
inline Vec8 deformedState(std::mt19937 &rng, double l, double amp)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double angle = 3.0 * u(rng);
  Vec8 e = straightElement(Vec2(u(rng), u(rng)), Vec2(std::cos(angle), std::sin(angle)), l);
  for (int k = 0; k < 8; ++k) e[k] += amp * u(rng) * coordinateScale(k, l);
  return e;
}

// Random nodal velocities up to speed * the coordinate's size.
inline Vec8 randomVelocity(std::mt19937 &rng, double l, double speed)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec8 v;
  for (int k = 0; k < 8; ++k) v[k] = speed * u(rng) * coordinateScale(k, l);
  return v;
}

inline double relErr(const Eigen::MatrixXd &a, const Eigen::MatrixXd &b) { return (a - b).norm() / b.norm(); }

// Relative error of internalForce() against central differences of strainEnergy().
inline double energyGradientError(const Section &sec, double l, const Vec8 &e)
{
  Vec8 f, fd;
  internalForce(sec, l, e, f, nullptr);
  for (int k = 0; k < 8; ++k) {
    const double h = 1e-6 * coordinateScale(k, l);
    Vec8 ep = e, em = e;
    ep[k] += h, em[k] -= h;
    fd[k] = (strainEnergy(sec, l, ep) - strainEnergy(sec, l, em)) / (2 * h);
  }
  return relErr(f, fd);
}

// Relative error of the tangent against central differences of
// internalForce(); *asymmetry receives |K - K^T| / |K|.
inline double tangentError(const Section &sec, double l, const Vec8 &e, double *asymmetry)
{
  Vec8 f;
  Mat8 K, fd;
  internalForce(sec, l, e, f, &K);
  for (int k = 0; k < 8; ++k) {
    const double h = 1e-7 * coordinateScale(k, l);
    Vec8 ep = e, em = e, fp, fm;
    ep[k] += h, em[k] -= h;
    internalForce(sec, l, ep, fp, nullptr);
    internalForce(sec, l, em, fm, nullptr);
    fd.col(k) = (fp - fm) / (2 * h);
  }
  *asymmetry = (K - K.transpose()).norm() / K.norm();
  return relErr(K, fd);
}

// Relative errors of the Kelvin-Voigt force's Jacobians, d fd/de (the cQ
// block) and d fd/dedot (the cV block), against central differences;
// *asymmetry receives |D - D^T| / |D| of the cV block.
inline void dampingJacobianErrors(const Section &sec, double l, const Vec8 &e, const Vec8 &v, double *errorQ,
                                  double *errorV, double *asymmetry)
{
  const auto force = [&](const Vec8 &ee, const Vec8 &vv) {
    Vec8 f;
    dampingForce(sec, l, ee, vv, f, nullptr, nullptr);
    return f;
  };
  Vec8 f;
  Mat8 Kq, Dv, fdQ, fdV;
  dampingForce(sec, l, e, v, f, &Kq, &Dv);
  for (int k = 0; k < 8; ++k) {
    const double hq = 1e-7 * coordinateScale(k, l), hv = 1e-3 * coordinateScale(k, l);
    Vec8 ep = e, em = e, vp = v, vm = v;
    ep[k] += hq, em[k] -= hq, vp[k] += hv, vm[k] -= hv;
    fdQ.col(k) = (force(ep, v) - force(em, v)) / (2 * hq);
    fdV.col(k) = (force(e, vp) - force(e, vm)) / (2 * hv);
  }
  *errorQ = relErr(Kq, fdQ);
  *errorV = relErr(Dv, fdV);
  *asymmetry = (Dv - Dv.transpose()).norm() / Dv.norm();
}

} // namespace boomdyn::ancf::element_states
