// Forward-mode automatic differentiation to second order (Jet2: a value with
// its gradient and Hessian with respect to N independent variables) and to
// first order (Jet1: value and gradient). The spatial
// beam element (docs/model.md §1.7) forms its strains from the 14 element
// coordinates through normalizations, smallest rotations and an angle; its
// internal force and tangent need each strain's gradient and Hessian, which
// this type carries through the same expressions exactly (no truncation
// error, unlike finite differences; no hand-derived chain rules to get wrong).
// Cost: a product updates N(N+1) Hessian entries, so it is meant for small N
// (one element's coordinates), not for a whole model.
#pragma once

#include <Eigen/Dense>

#include <cmath>

namespace boomdyn::jet {

template <int N>
struct Jet2 {
  using Grad = Eigen::Matrix<double, N, 1>;
  using Hess = Eigen::Matrix<double, N, N>;
  double v = 0;
  Grad g = Grad::Zero();
  Hess h = Hess::Zero();

  Jet2() = default;
  explicit Jet2(double value) : v(value) {}
  // Independent variable number i.
  static Jet2 variable(double value, int i)
  {
    Jet2 a(value);
    a.g[i] = 1.0;
    return a;
  }
  // A quantity linear in the variables: value and constant gradient.
  static Jet2 linear(double value, const Grad &gradient)
  {
    Jet2 a(value);
    a.g = gradient;
    return a;
  }

  Jet2 &operator+=(const Jet2 &b)
  {
    v += b.v, g += b.g, h += b.h;
    return *this;
  }
  Jet2 &operator-=(const Jet2 &b)
  {
    v -= b.v, g -= b.g, h -= b.h;
    return *this;
  }
  Jet2 &operator*=(double s)
  {
    v *= s, g *= s, h *= s;
    return *this;
  }
};

template <int N> inline Jet2<N> operator+(Jet2<N> a, const Jet2<N> &b) { return a += b; }
template <int N> inline Jet2<N> operator-(Jet2<N> a, const Jet2<N> &b) { return a -= b; }
template <int N> inline Jet2<N> operator-(Jet2<N> a) { return a *= -1.0; }
template <int N> inline Jet2<N> operator*(Jet2<N> a, double s) { return a *= s; }
template <int N> inline Jet2<N> operator*(double s, Jet2<N> a) { return a *= s; }
template <int N> inline Jet2<N> operator+(Jet2<N> a, double s)
{
  a.v += s;
  return a;
}
template <int N> inline Jet2<N> operator+(double s, Jet2<N> a) { return a + s; }
template <int N> inline Jet2<N> operator-(Jet2<N> a, double s)
{
  a.v -= s;
  return a;
}
template <int N> inline Jet2<N> operator-(double s, Jet2<N> a)
{
  a *= -1.0;
  a.v += s;
  return a;
}

template <int N> inline Jet2<N> operator*(const Jet2<N> &a, const Jet2<N> &b)
{
  Jet2<N> c;
  c.v = a.v * b.v;
  c.g = a.v * b.g + b.v * a.g;
  // One pass over the Hessian (lazy outer products: no temporaries).
  c.h.noalias() = a.v * b.h + b.v * a.h + a.g.lazyProduct(b.g.transpose()) + b.g.lazyProduct(a.g.transpose());
  return c;
}

// a0 b0 + s a1 b1 and a0 b0 + a1 b1 + a2 b2 in one pass over the Hessian
// (the cross and dot products of 3-vectors of jets: most of the operations).
template <int N>
inline Jet2<N> sumOfProducts(const Jet2<N> &a0, const Jet2<N> &b0, const Jet2<N> &a1, const Jet2<N> &b1, double s)
{
  Jet2<N> c;
  c.v = a0.v * b0.v + s * (a1.v * b1.v);
  c.g = a0.v * b0.g + b0.v * a0.g + s * (a1.v * b1.g + b1.v * a1.g);
  const typename Jet2<N>::Grad sa1 = s * a1.g, sb1 = s * b1.g;
  c.h.noalias() = a0.v * b0.h + b0.v * a0.h + (s * a1.v) * b1.h + (s * b1.v) * a1.h +
                  a0.g.lazyProduct(b0.g.transpose()) + b0.g.lazyProduct(a0.g.transpose()) +
                  sa1.lazyProduct(b1.g.transpose()) + sb1.lazyProduct(a1.g.transpose());
  return c;
}
template <int N>
inline Jet2<N> sumOfProducts(const Jet2<N> &a0, const Jet2<N> &b0, const Jet2<N> &a1, const Jet2<N> &b1,
                             const Jet2<N> &a2, const Jet2<N> &b2)
{
  Jet2<N> c;
  c.v = a0.v * b0.v + a1.v * b1.v + a2.v * b2.v;
  c.g = a0.v * b0.g + b0.v * a0.g + a1.v * b1.g + b1.v * a1.g + a2.v * b2.g + b2.v * a2.g;
  c.h.noalias() = a0.v * b0.h + b0.v * a0.h + a1.v * b1.h + b1.v * a1.h + a2.v * b2.h + b2.v * a2.h +
                  a0.g.lazyProduct(b0.g.transpose()) + b0.g.lazyProduct(a0.g.transpose()) +
                  a1.g.lazyProduct(b1.g.transpose()) + b1.g.lazyProduct(a1.g.transpose()) +
                  a2.g.lazyProduct(b2.g.transpose()) + b2.g.lazyProduct(a2.g.transpose());
  return c;
}

// f(a) with f' = d1, f'' = d2 at a.v.
template <int N> inline Jet2<N> chain(const Jet2<N> &a, double f, double d1, double d2)
{
  Jet2<N> c;
  c.v = f;
  c.g = d1 * a.g;
  const typename Jet2<N>::Grad d2g = d2 * a.g;
  c.h.noalias() = d1 * a.h + d2g.lazyProduct(a.g.transpose());
  return c;
}

template <int N> inline Jet2<N> inverse(const Jet2<N> &a)
{
  const double i = 1.0 / a.v;
  return chain(a, i, -i * i, 2.0 * i * i * i);
}
template <int N> inline Jet2<N> operator/(const Jet2<N> &a, const Jet2<N> &b) { return a * inverse(b); }
template <int N> inline Jet2<N> operator/(Jet2<N> a, double s) { return a *= 1.0 / s; }
template <int N> inline Jet2<N> operator/(double s, const Jet2<N> &a) { return s * inverse(a); }

template <int N> inline Jet2<N> sqrt(const Jet2<N> &a)
{
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s, -0.25 / (s * a.v));
}
template <int N> inline Jet2<N> sin(const Jet2<N> &a)
{
  const double s = std::sin(a.v);
  return chain(a, s, std::cos(a.v), -s);
}
template <int N> inline Jet2<N> cos(const Jet2<N> &a)
{
  const double c = std::cos(a.v);
  return chain(a, c, -std::sin(a.v), -c);
}

// atan2(y, x) with its first and second partial derivatives.
template <int N> inline Jet2<N> atan2(const Jet2<N> &y, const Jet2<N> &x)
{
  const double r2 = x.v * x.v + y.v * y.v, r4 = r2 * r2;
  const double fy = x.v / r2, fx = -y.v / r2;
  const double fyy = -2.0 * x.v * y.v / r4, fxx = -fyy, fxy = (y.v * y.v - x.v * x.v) / r4;
  Jet2<N> c;
  c.v = std::atan2(y.v, x.v);
  c.g = fy * y.g + fx * x.g;
  c.h.noalias() = fy * y.h + fx * x.h;
  c.h.noalias() += fyy * y.g * y.g.transpose() + fxx * x.g * x.g.transpose();
  c.h.noalias() += fxy * (y.g * x.g.transpose() + x.g * y.g.transpose());
  return c;
}

// Plain doubles take the same templated expressions (energy, strains for output).
inline double value(double a) { return a; }
template <int N> inline double value(const Jet2<N> &a) { return a.v; }

} // namespace boomdyn::jet

namespace boomdyn::jet {

// First order only (value and gradient): the residual's path, where the
// Hessians are not needed; about N/2 times cheaper per operation than Jet2.
template <int N>
struct Jet1 {
  using Grad = Eigen::Matrix<double, N, 1>;
  double v = 0;
  Grad g = Grad::Zero();

  Jet1() = default;
  explicit Jet1(double value) : v(value) {}
  static Jet1 variable(double value, int i)
  {
    Jet1 a(value);
    a.g[i] = 1.0;
    return a;
  }
  static Jet1 linear(double value, const Grad &gradient)
  {
    Jet1 a(value);
    a.g = gradient;
    return a;
  }
  Jet1 &operator+=(const Jet1 &b)
  {
    v += b.v, g += b.g;
    return *this;
  }
  Jet1 &operator-=(const Jet1 &b)
  {
    v -= b.v, g -= b.g;
    return *this;
  }
  Jet1 &operator*=(double s)
  {
    v *= s, g *= s;
    return *this;
  }
};

template <int N> inline Jet1<N> operator+(Jet1<N> a, const Jet1<N> &b) { return a += b; }
template <int N> inline Jet1<N> operator-(Jet1<N> a, const Jet1<N> &b) { return a -= b; }
template <int N> inline Jet1<N> operator-(Jet1<N> a) { return a *= -1.0; }
template <int N> inline Jet1<N> operator*(Jet1<N> a, double s) { return a *= s; }
template <int N> inline Jet1<N> operator*(double s, Jet1<N> a) { return a *= s; }
template <int N> inline Jet1<N> operator+(Jet1<N> a, double s)
{
  a.v += s;
  return a;
}
template <int N> inline Jet1<N> operator+(double s, Jet1<N> a) { return a + s; }
template <int N> inline Jet1<N> operator-(Jet1<N> a, double s)
{
  a.v -= s;
  return a;
}
template <int N> inline Jet1<N> operator-(double s, Jet1<N> a)
{
  a *= -1.0;
  a.v += s;
  return a;
}
template <int N> inline Jet1<N> operator*(const Jet1<N> &a, const Jet1<N> &b)
{
  Jet1<N> c;
  c.v = a.v * b.v;
  c.g = a.v * b.g + b.v * a.g;
  return c;
}
template <int N> inline Jet1<N> chain(const Jet1<N> &a, double f, double d1, double)
{
  Jet1<N> c;
  c.v = f;
  c.g = d1 * a.g;
  return c;
}
template <int N> inline Jet1<N> inverse(const Jet1<N> &a)
{
  const double i = 1.0 / a.v;
  return chain(a, i, -i * i, 0.0);
}
template <int N> inline Jet1<N> operator/(const Jet1<N> &a, const Jet1<N> &b) { return a * inverse(b); }
template <int N> inline Jet1<N> operator/(Jet1<N> a, double s) { return a *= 1.0 / s; }
template <int N> inline Jet1<N> operator/(double s, const Jet1<N> &a) { return s * inverse(a); }
template <int N> inline Jet1<N> sqrt(const Jet1<N> &a)
{
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s, 0.0);
}
template <int N> inline Jet1<N> sin(const Jet1<N> &a) { return chain(a, std::sin(a.v), std::cos(a.v), 0.0); }
template <int N> inline Jet1<N> cos(const Jet1<N> &a) { return chain(a, std::cos(a.v), -std::sin(a.v), 0.0); }
template <int N> inline Jet1<N> atan2(const Jet1<N> &y, const Jet1<N> &x)
{
  const double r2 = x.v * x.v + y.v * y.v;
  Jet1<N> c;
  c.v = std::atan2(y.v, x.v);
  c.g = (x.v / r2) * y.g - (y.v / r2) * x.g;
  return c;
}
template <int N> inline double value(const Jet1<N> &a) { return a.v; }

} // namespace boomdyn::jet
