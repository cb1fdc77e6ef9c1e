// Euler parameters p = (e0, e) of a rotation (unit quaternion): the rotation
// matrix, its derivatives, and the matrices of the rigid body's rotational
// inertia (Nikravesh, Computer-Aided Analysis of Mechanical Systems, 1988,
// ch. 6 and 11). R(p) = (e0^2 - e.e) I + 2 e e^T + 2 e0 [e]x is a
// homogeneous quadratic in p (orthogonal on |p| = 1, which the body's
// normalization row keeps), so R u' has a derivative linear in p and a
// constant second derivative: the Hessians below are exact.
#pragma once

#include <Eigen/Dense>

namespace boomdyn::euler {

using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat3 = Eigen::Matrix3d;
using Mat34 = Eigen::Matrix<double, 3, 4>;
using Mat4 = Eigen::Matrix4d;

Mat3 skew(const Vec3 &a);
// R(p) as above.
Mat3 rotation(const Vec4 &p);
// d(R(p) u)/dp (3 x 4), linear in p.
Mat34 rotationDerivative(const Vec4 &p, const Vec3 &u);
// d2(w . R(p) u)/dp2 (4 x 4), independent of p.
Mat4 rotationHessian(const Vec3 &w, const Vec3 &u);
// G(p) = [-e, e0 I - [e]x]: body-frame angular velocity omega' = 2 G(p) pdot.
Mat34 bodyRateMatrix(const Vec4 &p);
// E(p) = [-e, e0 I + [e]x]: global angular velocity omega = 2 E(p) pdot.
Mat34 globalRateMatrix(const Vec4 &p);
// G(a)^T y as a linear function of a: G(a)^T y = transposedRateMatrix(y) a.
Mat4 transposedRateMatrix(const Vec3 &y);
// The Euler parameters of a rotation matrix (Shepperd's method, e0 >= 0).
Vec4 fromRotation(const Mat3 &R);

// The rotational inertia force of a rigid body with inertia J' (body axes,
// about the centre of mass) on its Euler parameters, and its Jacobian:
//   f = 4 G^T J' G a + 8 G(v)^T J' G v   (G = G(p), v = pdot, a = pddot),
// with df/da, df/dv and df/dp (4 x 4 each).
struct RotaryInertia {
  Vec4 force;
  Mat4 dA, dV, dP;
};
void rotaryInertia(const Mat3 &J, const Vec4 &p, const Vec4 &v, const Vec4 &a, RotaryInertia &out, bool jacobian);
// Kinetic energy 1/2 omega'^T J' omega' with omega' = 2 G(p) v.
double rotaryKineticEnergy(const Mat3 &J, const Vec4 &p, const Vec4 &v);

} // namespace boomdyn::euler
