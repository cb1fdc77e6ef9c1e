// The spatial beam's kinematics as templates on the scalar type (docs/model.md
// §1.7): double for energies and output, jet::Jet2<14> for the strains'
// first and second derivatives with respect to the element vector. Shared by
// spatial_beam_kinematics.cpp and spatial_beam_element.cpp; not a public header.
#pragma once

#include "boomdyn/spatial_beam_kinematics.hpp"
#include "second_order_jet.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace boomdyn::spatial_beam::detail {

using Jet = jet::Jet2<kCoordinates>;
using Jet1 = jet::Jet1<kCoordinates>;

// The strains do not change when the element is translated: they depend on
// e only through w = [r_1 - r_0, r'_0, theta_0, r'_1, theta_1] (11 entries),
// and jets over w carry 11 x 11 instead of 14 x 14 Hessians. kReducedSlot[i]
// is the entry of w that coordinate i of e feeds (-1: r_0, held constant;
// its derivatives are minus those of r_1 - r_0).
constexpr int kReduced = 12; // 11 used; an even size keeps Eigen's 2-wide vector loops
constexpr int kReducedSlot[kCoordinates] = {-1, -1, -1, 3, 4, 5, 6, 0, 1, 2, 7, 8, 9, 10};
using ReducedJet = jet::Jet2<kReduced>;
using ReducedJet1 = jet::Jet1<kReduced>;
using ReducedMap = Eigen::Matrix<double, kCoordinates, kReduced>;

// P with de-derivatives = P (dw-derivatives): +1 from r_1, r'_a, theta_a to
// their entries of w, -1 from r_0 to r_1 - r_0.
inline const ReducedMap &reducedMap()
{
  static const ReducedMap P = [] {
    ReducedMap m = ReducedMap::Zero();
    for (int i = 0; i < kCoordinates; ++i)
      if (kReducedSlot[i] >= 0) m(i, kReducedSlot[i]) = 1.0;
    for (int d = 0; d < 3; ++d) m(positionIndex(0) + d, d) = -1.0;
    return m;
  }();
  return P;
}
using std::atan2;
using std::cos;
using std::sin;
using std::sqrt;
using jet::atan2;
using jet::cos;
using jet::sin;
using jet::sqrt;

template <typename T>
struct V3 {
  T x, y, z;
};
template <typename T> inline V3<T> operator+(const V3<T> &a, const V3<T> &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <typename T> inline V3<T> operator-(const V3<T> &a, const V3<T> &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <typename T> inline V3<T> operator*(const T &s, const V3<T> &a) { return {s * a.x, s * a.y, s * a.z}; }
template <typename T> inline V3<T> scaled(const V3<T> &a, double s) { return {a.x * s, a.y * s, a.z * s}; }
template <typename T> inline T dot(const V3<T> &a, const V3<T> &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
// Dot with a constant vector (cheaper than promoting it).
template <typename T> inline T dot(const V3<T> &a, const Vec3 &b) { return a.x * b.x() + a.y * b.y() + a.z * b.z(); }
template <typename T> inline V3<T> cross(const V3<T> &a, const V3<T> &b)
{
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// The same products on second-order jets, each in one pass (sumOfProducts).
template <int N> inline jet::Jet2<N> dot(const V3<jet::Jet2<N>> &a, const V3<jet::Jet2<N>> &b)
{
  return jet::sumOfProducts(a.x, b.x, a.y, b.y, a.z, b.z);
}
template <int N> inline V3<jet::Jet2<N>> cross(const V3<jet::Jet2<N>> &a, const V3<jet::Jet2<N>> &b)
{
  return {jet::sumOfProducts(a.y, b.z, a.z, b.y, -1.0), jet::sumOfProducts(a.z, b.x, a.x, b.z, -1.0),
          jet::sumOfProducts(a.x, b.y, a.y, b.x, -1.0)};
}
template <typename T> inline V3<T> constant(const Vec3 &v) { return {T(v.x()), T(v.y()), T(v.z())}; }

// Offsets of the four Hermite coefficient vectors r_0, r'_0, r_1, r'_1 in e.
constexpr int kShapeOffset[4] = {positionIndex(0), slopeIndex(0), positionIndex(1), slopeIndex(1)};

// sum_k s_k q_k (one Hermite interpolation) from the element vector. For a
// jet the result is linear in the variables: its gradient is the same sum of
// the coefficients' gradients, its Hessian zero.
inline V3<double> interpolate(const double *e, const Eigen::Vector4d &s)
{
  V3<double> r{0, 0, 0};
  for (int k = 0; k < 4; ++k) {
    const int o = kShapeOffset[k];
    r.x += s[k] * e[o], r.y += s[k] * e[o + 1], r.z += s[k] * e[o + 2];
  }
  return r;
}
template <typename J>
inline V3<J> interpolate(const J *e, const Eigen::Vector4d &s)
{
  V3<J> r;
  J *c[3] = {&r.x, &r.y, &r.z};
  for (int d = 0; d < 3; ++d) {
    typename J::Grad g = J::Grad::Zero();
    double v = 0;
    for (int k = 0; k < 4; ++k) {
      const int o = kShapeOffset[k] + d;
      v += s[k] * e[o].v;
      g += s[k] * e[o].g;
    }
    *c[d] = J::linear(v, g);
  }
  return r;
}

template <typename T> inline V3<T> slopeOf(const T *e, int a)
{
  const int o = slopeIndex(a);
  return {e[o], e[o + 1], e[o + 2]};
}

// Smallest rotation SR(a -> b) of v, a and b unit, v ⊥ a:
// v - (b.v)/(1 + a.b) (a + b).
template <typename T, typename A>
inline V3<T> smallestRotationNormal(const A &a, const V3<T> &b, const V3<T> &v, const T &aDotB)
{
  const T c = dot(b, v) / (1.0 + aDotB);
  return v - c * (a + b);
}

// What the element needs from its nodes: node 0's tangent and zero-twist
// axes, node 1's tangent, and the angle beta that turns node 0's zero-twist
// triad, carried to node 1 by the smallest rotation, into node 1's zero-twist
// triad (about t_1). theta_0 and theta_1 + beta are then the section angles
// at the two ends against the one transported frame.
template <typename T>
struct NodeData {
  V3<T> t0, b2, b3, t1;
  T beta, theta0, theta1;
};

template <typename T>
inline void zeroTwistAxes(const NodeFrame &ref, const V3<T> &t, V3<T> &b2, V3<T> &b3)
{
  const T c = dot(t, ref.normal) / (1.0 + dot(t, ref.tangent));
  b2 = {ref.normal.x() - c * (ref.tangent.x() + t.x), ref.normal.y() - c * (ref.tangent.y() + t.y),
        ref.normal.z() - c * (ref.tangent.z() + t.z)};
  b3 = cross(t, b2);
}

template <typename T> inline V3<T> unit(const V3<T> &v)
{
  const T inv = 1.0 / sqrt(dot(v, v));
  return inv * v;
}

template <typename T>
NodeData<T> nodeData(const Geometry &geo, const T *e)
{
  NodeData<T> n;
  n.t0 = unit(slopeOf(e, 0));
  n.t1 = unit(slopeOf(e, 1));
  zeroTwistAxes(geo.node[0], n.t0, n.b2, n.b3);
  V3<T> n2, n3;
  zeroTwistAxes(geo.node[1], n.t1, n2, n3);
  const V3<T> c2 = smallestRotationNormal(n.t0, n.t1, n.b2, dot(n.t0, n.t1));
  const V3<T> c3 = cross(n.t1, c2);
  n.beta = atan2(dot(n2, c3), dot(n2, c2));
  n.theta0 = e[twistIndex(0)];
  n.theta1 = e[twistIndex(1)];
  return n;
}

// Everything at one section xi. s1, s2: the shape functions' first and second
// x-derivatives at xi.
template <typename T>
struct SectionState {
  T axial, torsion, curvature2, curvature3;
  V3<T> t, d2, d3;
};

// The section at xi from the axis derivatives r1 = r', r2 = r'' there. xi
// is a double inside an element's quadrature, or a jet when the section
// point itself is a variable (the slack coordinate of a sliding joint,
// spatial_beam_slack_frame.cpp).
template <typename T, typename X>
SectionState<T> sectionStateOf(const NodeData<T> &n, const V3<T> &r1, const V3<T> &r2, const X &xi, double l)
{
  const T J2 = dot(r1, r1);
  const T invJ = 1.0 / sqrt(J2);
  const V3<T> t = invJ * r1;
  // Curvature vector t x t_x = r' x r'' / |r'|^2 and the tangent's rate t_x.
  const T invJ2 = invJ * invJ;
  const V3<T> kappa = invJ2 * cross(r1, r2);
  const V3<T> tx = invJ * (r2 - dot(t, r2) * t);
  // Node 0's zero-twist axes carried to t by the smallest rotation, and the
  // rate of their spin about t (Omega_1 = b2_x . b3).
  const V3<T> u = n.t0 + t;
  const T invD = 1.0 / (1.0 + dot(n.t0, t));
  const T c = dot(t, n.b2) * invD;
  const V3<T> b2 = n.b2 - c * u;
  const V3<T> b3 = cross(t, b2);
  const T cx = (dot(tx, n.b2) - c * dot(n.t0, tx)) * invD;
  const V3<T> b2x = T(-1.0) * (cx * u + c * tx);
  const T spin = dot(b2x, b3);
  // Section angle against the carried axes, linear in xi.
  const T phiEnd = n.theta1 + n.beta;
  const T phi = (1.0 - xi) * n.theta0 + xi * phiEnd;
  const T cp = cos(phi), sp = sin(phi);
  SectionState<T> s;
  s.t = t;
  s.d2 = cp * b2 + sp * b3;
  s.d3 = cp * b3 - sp * b2;
  s.axial = 0.5 * (J2 - 1.0);
  s.torsion = (phiEnd - n.theta0) * (1.0 / l) + spin;
  s.curvature2 = dot(kappa, s.d2);
  s.curvature3 = dot(kappa, s.d3);
  return s;
}

template <typename T>
SectionState<T> sectionState(const NodeData<T> &n, const T *e, double xi, double l, const Eigen::Vector4d &s1,
                             const Eigen::Vector4d &s2)
{
  return sectionStateOf(n, interpolate(e, s1), interpolate(e, s2), xi, l);
}

// The element vector as jets over w: r_0 constant, the others variables.
template <typename J>
inline void seedReduced(const Vec14 &e, J *x)
{
  for (int i = 0; i < kCoordinates; ++i) x[i] = kReducedSlot[i] < 0 ? J(e[i]) : J::variable(e[i], kReducedSlot[i]);
}

// The element vector as independent variables of 14-variable jets.
template <typename J>
inline void seed(const Vec14 &e, J *x)
{
  for (int i = 0; i < kCoordinates; ++i) x[i] = J::variable(e[i], i);
}

} // namespace boomdyn::spatial_beam::detail
