#include "boomdyn/euler_parameters.hpp"

#include <cmath>

namespace boomdyn::euler {

Mat3 skew(const Vec3 &a)
{
  Mat3 S;
  S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return S;
}

Mat3 rotation(const Vec4 &p)
{
  const double e0 = p[0];
  const Vec3 e = p.tail<3>();
  return (e0 * e0 - e.dot(e)) * Mat3::Identity() + 2.0 * e * e.transpose() + 2.0 * e0 * skew(e);
}

Mat34 rotationDerivative(const Vec4 &p, const Vec3 &u)
{
  // R u = (e0^2 - e.e) u + 2 (e.u) e + 2 e0 e x u.
  const double e0 = p[0];
  const Vec3 e = p.tail<3>();
  Mat34 D;
  D.col(0) = 2.0 * e0 * u + 2.0 * e.cross(u);
  D.rightCols<3>() = -2.0 * u * e.transpose() + 2.0 * e.dot(u) * Mat3::Identity() + 2.0 * e * u.transpose() -
                     2.0 * e0 * skew(u);
  return D;
}

Mat4 rotationHessian(const Vec3 &w, const Vec3 &u)
{
  Mat4 H;
  const Vec3 uw = u.cross(w);
  H(0, 0) = 2.0 * w.dot(u);
  H.block<1, 3>(0, 1) = 2.0 * uw.transpose();
  H.block<3, 1>(1, 0) = 2.0 * uw;
  H.block<3, 3>(1, 1) = -2.0 * w.dot(u) * Mat3::Identity() + 2.0 * w * u.transpose() + 2.0 * u * w.transpose();
  return H;
}

Mat34 bodyRateMatrix(const Vec4 &p)
{
  Mat34 G;
  G.col(0) = -p.tail<3>();
  G.rightCols<3>() = p[0] * Mat3::Identity() - skew(p.tail<3>());
  return G;
}

Mat34 globalRateMatrix(const Vec4 &p)
{
  Mat34 E;
  E.col(0) = -p.tail<3>();
  E.rightCols<3>() = p[0] * Mat3::Identity() + skew(p.tail<3>());
  return E;
}

Mat4 transposedRateMatrix(const Vec3 &y)
{
  // G(a)^T y = [-a_v . y; a0 y + a_v x y] = [0, -y^T; y, -[y]x] a.
  Mat4 B;
  B(0, 0) = 0;
  B.block<1, 3>(0, 1) = -y.transpose();
  B.block<3, 1>(1, 0) = y;
  B.block<3, 3>(1, 1) = -skew(y);
  return B;
}

Vec4 fromRotation(const Mat3 &R)
{
  const double tr = R.trace();
  Vec4 p;
  // The largest of e0^2, e1^2, e2^2, e3^2 is found first (no cancellation).
  const double c[4] = {tr, R(0, 0), R(1, 1), R(2, 2)};
  int k = 0;
  for (int i = 1; i < 4; ++i)
    if (c[i] > c[k]) k = i;
  if (k == 0) {
    p[0] = 0.5 * std::sqrt(1.0 + tr);
    const double f = 0.25 / p[0];
    p[1] = f * (R(2, 1) - R(1, 2)), p[2] = f * (R(0, 2) - R(2, 0)), p[3] = f * (R(1, 0) - R(0, 1));
  } else {
    const int i = k - 1, j = (i + 1) % 3, l = (i + 2) % 3;
    const double ei = 0.5 * std::sqrt(1.0 + 2.0 * R(i, i) - tr), f = 0.25 / ei;
    p[1 + i] = ei;
    p[0] = f * (R(l, j) - R(j, l));
    p[1 + j] = f * (R(j, i) + R(i, j));
    p[1 + l] = f * (R(l, i) + R(i, l));
    if (p[0] < 0) p = -p;
  }
  return p / p.norm();
}

void rotaryInertia(const Mat3 &J, const Vec4 &p, const Vec4 &v, const Vec4 &a, RotaryInertia &out, bool jacobian)
{
  const Mat34 G = bodyRateMatrix(p), Gv = bodyRateMatrix(v);
  const Vec3 wv = G * v;      // omega' / 2
  const Vec3 Jga = J * (G * a), Jgv = J * wv;
  out.force = 4.0 * G.transpose() * Jga + 8.0 * Gv.transpose() * Jgv;
  if (!jacobian) return;
  // G(p) x = -G(x) p and G(x)^T y = B(y) x (transposedRateMatrix).
  out.dA = 4.0 * G.transpose() * J * G;
  out.dV = 8.0 * transposedRateMatrix(Jgv) + 8.0 * Gv.transpose() * J * G;
  out.dP = 4.0 * transposedRateMatrix(Jga) - 4.0 * G.transpose() * J * bodyRateMatrix(a) -
           8.0 * Gv.transpose() * J * Gv;
}

double rotaryKineticEnergy(const Mat3 &J, const Vec4 &p, const Vec4 &v)
{
  const Vec3 w = 2.0 * bodyRateMatrix(p) * v;
  return 0.5 * w.dot(J * w);
}

} // namespace boomdyn::euler
