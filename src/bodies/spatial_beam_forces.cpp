// Internal and Kelvin-Voigt forces of the spatial beam element and their
// Jacobians (docs/model.md §1.7), structured by what each strain depends on.
//
// At a Gauss point the torsion and curvatures depend on the element only
// through the centreline's r' and r'' there (linear in e), node 0's slope
// r'_0 (through its zero-twist axes) and the section angle phi, which is
// linear in theta_0 and psi_1 = theta_1 + beta(r'_0, r'_1). So:
//   - beta and its derivatives are formed once per element (jets over the
//     6 slopes);
//   - per Gauss point, the spin of the carried axes and the curvature's
//     components X, Y on the carried axes b2, b3 are functions of the 9
//     variables z = (r', r'_0, r'')_d, d = x, y, z, through seven scalar
//     products (carriedStrains: first-order jets over z for the residual;
//     carriedStrainsByProducts: chain rule through the products with small
//     jets, for the Hessians); the angle enters in closed
//     form (K2 = cos(phi) X + sin(phi) Y, K3 = cos(phi) Y - sin(phi) X;
//     torsion = spin + (psi_1 - theta_0)/l);
//   - the axial strain (|r'|^2 - 1)/2 is in closed form;
//   - z is linear in v = (r_1 - r_0, r'_0, r'_1)_d, theta_0, psi_1 with the
//     same 3 x 3 block M of shape values in each direction d, so Hessians are
//     mapped to v block by block (M^T H_de M), summed over the Gauss points
//     and mapped to e once: psi_1 -> theta_1 by the rank updates of
//     B = dv/dw and the term f_psi1 d^2beta, then scattered with signs.
// The jet kernels of spatial_beam_element.cpp (namespace reference) carry
// 12-variable jets through every operation instead; they are the oracle
// these are tested against (test_spatial_beam_element.cpp).
#include "boomdyn/spatial_beam_element.hpp"

#include "spatial_beam_quadrature.hpp"
#include "spatial_beam_strains.hpp"

#include <type_traits>

namespace boomdyn::spatial_beam {

namespace {

using detail::V3;
constexpr int kV = 12; // v: (r_1 - r_0, r'_0, r'_1)_d at 3d, 3d + 1, 3d + 2; theta_0 at 9; psi_1 at 10; 11 unused
constexpr int kTheta0 = 9, kPsi1 = 10;
using VecV = Eigen::Matrix<double, kV, 1>;
using MatV = Eigen::Matrix<double, kV, kV>;
// z (the Gauss point's variables, 9) shares v's layout: r'_d at 3d, r'_0d at
// 3d + 1, r''_d at 3d + 2; in y = (z, theta_0, psi_1) the angles keep 9, 10.
constexpr int kZ = 9;
constexpr int kZJet = 10; // the jets' width: 9 used; an even width keeps Eigen's vector loops (9: 2x slower, 12: no faster)

// Entry of v that coordinate i of e feeds, and the sign (r_0 enters r_1 - r_0
// negatively); after the change psi_1 -> theta_1, entry 10 is theta_1.
constexpr int kSlot[kCoordinates] = {0, 3, 6, 1, 4, 7, kTheta0, 0, 3, 6, 2, 5, 8, kPsi1};
constexpr double kSign[kCoordinates] = {-1, -1, -1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};

// e-vector -> v-vector (the rates of v from edot: r_1 - r_0 gets rdot_1 - rdot_0).
VecV toV(const Vec14 &e)
{
  VecV v = VecV::Zero();
  for (int i = 0; i < kCoordinates; ++i) v[kSlot[i]] += kSign[i] * e[i];
  return v;
}
void scatter(const VecV &v, Vec14 &e)
{
  for (int i = 0; i < kCoordinates; ++i) e[i] = kSign[i] * v[kSlot[i]];
}
void scatter(const MatV &m, Mat14 &a)
{
  for (int j = 0; j < kCoordinates; ++j)
    for (int i = 0; i < kCoordinates; ++i) a(i, j) = kSign[i] * kSign[j] * m(kSlot[i], kSlot[j]);
}

// X^T with v's entry 10 turned from psi_1 into theta_1: X -> B^T X B,
// B = I + e_10 gBeta^T (gBeta[10] = 0).
void changeToTheta(MatV &X, const VecV &gBeta)
{
  const VecV row = X.row(kPsi1).transpose(), col = X.col(kPsi1);
  const double corner = X(kPsi1, kPsi1);
  X.noalias() += gBeta * row.transpose();
  X.noalias() += col * gBeta.transpose();
  X.noalias() += (corner * gBeta) * gBeta.transpose();
}
void changeToTheta(VecV &x, const VecV &gBeta) { x += x[kPsi1] * gBeta; }

// M (rows: r', r'_0, r'' of one direction; columns: r_1 - r_0, r'_0, r'_1).
Eigen::Matrix3d shapeBlock(const Eigen::Vector4d &s1, const Eigen::Vector4d &s2)
{
  Eigen::Matrix3d M;
  M << s1[2], s1[1], s1[3], 0, 1, 0, s2[2], s2[1], s2[3];
  return M;
}

// y -> v: J0^T X J0 and J0^T x with J0 = diag(M, M, M, 1, 1, 0).
void pushAdd(const MatV &Xy, const Eigen::Matrix3d &M, MatV &Xv)
{
  for (int d = 0; d < 3; ++d) {
    for (int c = 0; c < 3; ++c) Xv.block<3, 3>(3 * d, 3 * c).noalias() += M.transpose() * Xy.block<3, 3>(3 * d, 3 * c) * M;
    Xv.block<3, 2>(3 * d, kTheta0).noalias() += M.transpose() * Xy.block<3, 2>(3 * d, kTheta0);
    Xv.block<2, 3>(kTheta0, 3 * d).noalias() += Xy.block<2, 3>(kTheta0, 3 * d) * M;
  }
  Xv.block<2, 2>(kTheta0, kTheta0) += Xy.block<2, 2>(kTheta0, kTheta0);
}
void pushAdd(const VecV &xy, const Eigen::Matrix3d &M, VecV &xv)
{
  for (int d = 0; d < 3; ++d) xv.segment<3>(3 * d).noalias() += M.transpose() * xy.segment<3>(3 * d);
  xv.segment<2>(kTheta0) += xy.segment<2>(kTheta0);
}
// v -> y rates: J0 vdot.
VecV pullRates(const VecV &vdot, const Eigen::Matrix3d &M)
{
  VecV y = vdot;
  for (int d = 0; d < 3; ++d) y.segment<3>(3 * d) = M * vdot.segment<3>(3 * d);
  return y;
}

// The curvature's components on the carried axes and their spin at one
// Gauss point, as jets over z. With t = r'/|r'|, kappa = t x t_x and node 0's
// zero-twist axes t0, n, m = t0 x n, the carried axes are
// b2 = n - c (t0 + t), b3 = t x b2 with c = t.n / D, D = 1 + t0.t; and since
// kappa x t = t_x, t_x x t = -kappa and b3.t0 = -t.m, the quantities of
// detail::sectionState reduce to seven scalar products:
//   X = kappa.b2 = kappa.n - c kappa.t0,  Y = kappa.b3 = t_x.n - c t_x.t0,
//   spin = b2_x.b3 = (t.m) Y / D + c X.
template <typename J>
struct CarriedStrains {
  J spin, X, Y;
};
template <typename J>
CarriedStrains<J> carriedStrains(const V3<J> &t0, const V3<J> &n, const V3<J> &m, const V3<double> &a,
                                 const V3<double> &b)
{
  using detail::cross;
  using detail::dot;
  using std::sqrt;
  using jet::sqrt;
  const V3<J> r1{J::variable(a.x, 0), J::variable(a.y, 3), J::variable(a.z, 6)};
  const V3<J> r2{J::variable(b.x, 2), J::variable(b.y, 5), J::variable(b.z, 8)};
  const J invJ = 1.0 / sqrt(dot(r1, r1));
  const V3<J> t = invJ * r1;
  const V3<J> kappa = (invJ * invJ) * cross(r1, r2);
  const V3<J> tx = invJ * (r2 - dot(t, r2) * t);
  const J invD = 1.0 / (1.0 + dot(t0, t));
  const J c = dot(t, n) * invD;
  const J X = dot(kappa, n) - c * dot(kappa, t0);
  const J Y = dot(tx, n) - c * dot(tx, t0);
  return {dot(t, m) * invD * Y + c * X, X, Y};
}

// The same three with their Hessians by the chain rule through the seven
// scalar products q_i = w_i . p_i, w in {t, kappa, t_x} (functions of r', r''
// alone: 6-variable jets), p in {n, t0, m} (of r'_0 alone: formed once per
// element): dF/dz = G dF/dq, d^2F/dz^2 = G F_qq G^T + sum_i F_i d^2q_i/dz^2,
// with d^2q/dz^2 = sum_k p_k d^2w_k (r', r'' block), dw^T dp (mixed),
// sum_k w_k d^2p_k (r'_0 block).
struct NodeAxes {
  Vec3 value[3];        // n, t0, m
  Mat3 jac[3];          // d p / d r'_0 (rows: components)
  Mat3 hess[3][3];      // d^2 p_k / d r'_0^2
};
using Z = jet::Jet2<kZJet>;
NodeAxes nodeAxes(const V3<Z> &n, const V3<Z> &t0, const V3<Z> &m)
{
  NodeAxes a;
  const V3<Z> *p[3] = {&n, &t0, &m};
  for (int i = 0; i < 3; ++i) {
    const Z *c[3] = {&p[i]->x, &p[i]->y, &p[i]->z};
    for (int k = 0; k < 3; ++k) {
      a.value[i][k] = c[k]->v;
      for (int d = 0; d < 3; ++d) {
        a.jac[i](k, d) = c[k]->g[3 * d + 1];
        for (int f = 0; f < 3; ++f) a.hess[i][k](d, f) = c[k]->h(3 * d + 1, 3 * f + 1);
      }
    }
  }
  return a;
}

CarriedStrains<Z> carriedStrainsByProducts(const NodeAxes &na, const V3<double> &a, const V3<double> &b)
{
  using J6 = jet::Jet2<6>;
  using J8 = jet::Jet2<8>;
  using detail::cross;
  using detail::dot;
  using jet::sqrt;
  constexpr int kAB[6] = {0, 3, 6, 2, 5, 8}; // z slot of r'_d (0..2) and r''_d (3..5)
  constexpr int kR0[3] = {1, 4, 7};
  const V3<J6> r1{J6::variable(a.x, 0), J6::variable(a.y, 1), J6::variable(a.z, 2)};
  const V3<J6> r2{J6::variable(b.x, 3), J6::variable(b.y, 4), J6::variable(b.z, 5)};
  const J6 invJ = 1.0 / sqrt(dot(r1, r1));
  const V3<J6> t = invJ * r1;
  const V3<J6> kappa = (invJ * invJ) * cross(r1, r2);
  const V3<J6> tx = invJ * (r2 - dot(t, r2) * t);
  const V3<J6> *w[3] = {&t, &kappa, &tx};
  Vec3 wv[3];
  Eigen::Matrix<double, 3, 6> dw[3];
  for (int i = 0; i < 3; ++i) {
    wv[i] << w[i]->x.v, w[i]->y.v, w[i]->z.v;
    dw[i].row(0) = w[i]->x.g.transpose(), dw[i].row(1) = w[i]->y.g.transpose(), dw[i].row(2) = w[i]->z.g.transpose();
  }
  // (w, p) of each product: t.n, t.t0, t.m, kappa.n, kappa.t0, t_x.n, t_x.t0.
  constexpr int kW[7] = {0, 0, 0, 1, 1, 2, 2}, kP[7] = {0, 1, 2, 0, 1, 0, 1};
  Eigen::Matrix<double, kZJet, 8> G = Eigen::Matrix<double, kZJet, 8>::Zero();
  J8 q[7];
  for (int i = 0; i < 7; ++i) {
    const Vec3 &p = na.value[kP[i]];
    const Eigen::Matrix<double, 6, 1> gab = dw[kW[i]].transpose() * p;
    const Vec3 gr0 = na.jac[kP[i]].transpose() * wv[kW[i]];
    for (int j = 0; j < 6; ++j) G(kAB[j], i) = gab[j];
    for (int d = 0; d < 3; ++d) G(kR0[d], i) = gr0[d];
    q[i] = J8::variable(wv[kW[i]].dot(p), i);
  }
  const J8 invD = 1.0 / (1.0 + q[1]);
  const J8 c = q[0] * invD;
  const J8 X = q[3] - c * q[4];
  const J8 Y = q[5] - c * q[6];
  const J8 spin = q[2] * invD * Y + c * X;
  const J8 *F[3] = {&spin, &X, &Y};
  Z out[3];
  for (int s = 0; s < 3; ++s) {
    const J8 &f = *F[s];
    out[s].v = f.v;
    out[s].g.noalias() = G * f.g;
    // Lazy (coefficient-wise) products: at these sizes Eigen's blocked GEMM costs more than it saves.
    const Eigen::Matrix<double, kZJet, 8> Gh = G.lazyProduct(f.h);
    out[s].h.noalias() = Gh.lazyProduct(G.transpose());
    // sum_i f_i d^2 q_i, block by block.
    Eigen::Matrix<double, 6, 6> hab = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 3> hmix = Eigen::Matrix<double, 6, 3>::Zero();
    Mat3 hr0 = Mat3::Zero();
    Vec3 mu[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}, nu[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    Mat3 jw[3] = {Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};
    for (int i = 0; i < 7; ++i) {
      mu[kW[i]] += f.g[i] * na.value[kP[i]];
      nu[kP[i]] += f.g[i] * wv[kW[i]];
      jw[kW[i]] += f.g[i] * na.jac[kP[i]];
    }
    for (int i = 0; i < 3; ++i) {
      const J6 *wc[3] = {&w[i]->x, &w[i]->y, &w[i]->z};
      for (int k = 0; k < 3; ++k) {
        hab += mu[i][k] * wc[k]->h;
        hr0 += nu[i][k] * na.hess[i][k];
      }
      hmix.noalias() += dw[i].transpose() * jw[i];
    }
    for (int j = 0; j < 6; ++j) {
      for (int k = 0; k < 6; ++k) out[s].h(kAB[j], kAB[k]) += hab(j, k);
      for (int d = 0; d < 3; ++d) {
        out[s].h(kAB[j], kR0[d]) += hmix(j, d);
        out[s].h(kR0[d], kAB[j]) += hmix(j, d);
      }
    }
    for (int d = 0; d < 3; ++d)
      for (int e = 0; e < 3; ++e) out[s].h(kR0[d], kR0[e]) += hr0(d, e);
  }
  return {out[0], out[1], out[2]};
}

// One strain at a Gauss point over y: value, gradient, Hessian (if Hess).
struct YStrain {
  double v;
  VecV g;
  MatV h;
};

struct Wanted {
  bool K, damping, Kq, Dv;
};

// The sums of one element over v (and the Gauss point's sums over y); only
// the wanted ones are cleared (and used).
struct Sums {
  VecV f, fd, u;
  MatV K, Kq, Dv;
  double power = 0;
  explicit Sums(const Wanted &want)
  {
    f.setZero();
    if (want.K) K.setZero();
    if (want.damping) fd.setZero();
    if (want.Dv) Dv.setZero();
    if (want.Kq) Kq.setZero(), u.setZero();
  }
};

// Adds c/2 s^2 (and its Kelvin-Voigt force with c eta) of one strain over y.
template <bool Hess>
void addTerm(const YStrain &s, double c, double eta, const VecV &ydot, const Wanted &want, Sums &y)
{
  y.f += (c * s.v) * s.g;
  if constexpr (Hess)
    if (want.K) {
      y.K.noalias() += c * s.g * s.g.transpose();
      y.K.noalias() += (c * s.v) * s.h;
    }
  const double ce = c * eta;
  if (!want.damping || ce == 0) return;
  const double rate = s.g.dot(ydot);
  y.fd += (ce * rate) * s.g;
  y.power += ce * rate * rate;
  if (want.Dv) y.Dv.noalias() += ce * s.g * s.g.transpose();
  if constexpr (Hess)
    if (want.Kq) {
      y.Kq.noalias() += ce * s.g * (s.h * ydot).transpose();
      y.Kq.noalias() += (ce * rate) * s.h;
      y.u += (ce * s.g[kPsi1]) * s.g;
    }
}

void pushSums(const Sums &y, const Eigen::Matrix3d &M, const Wanted &want, Sums &v)
{
  pushAdd(y.f, M, v.f);
  if (want.K) pushAdd(y.K, M, v.K);
  if (!want.damping) return;
  pushAdd(y.fd, M, v.fd);
  v.power += y.power;
  if (want.Dv) pushAdd(y.Dv, M, v.Dv);
  if (want.Kq) {
    pushAdd(y.Kq, M, v.Kq);
    pushAdd(y.u, M, v.u);
  }
}

// The axial strain (|r'|^2 - 1)/2 at r' = a over y: gradient r' on the r'
// slots, Hessian the identity there.
template <bool Hess>
YStrain axialStrain(const V3<double> &a)
{
  YStrain s;
  s.v = 0.5 * (detail::dot(a, a) - 1.0);
  s.g.setZero();
  s.g[0] = a.x, s.g[3] = a.y, s.g[6] = a.z;
  if constexpr (Hess) {
    s.h.setZero();
    s.h(0, 0) = s.h(3, 3) = s.h(6, 6) = 1.0;
  }
  return s;
}

template <bool Hess>
double elementForces(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 *edot, Vec14 &f, Mat14 *K,
                     Vec14 *fd, Mat14 *Kq, Mat14 *Dv)
{
  using J6 = std::conditional_t<Hess, jet::Jet2<6>, jet::Jet1<6>>;
  using J9 = std::conditional_t<Hess, jet::Jet2<kZJet>, jet::Jet1<kZJet>>;
  const Wanted want{K != nullptr, edot != nullptr, Kq != nullptr, Dv != nullptr};
  const double l = geo.l;
  const StrainLaw law = strainLaw(sec);

  // beta(r'_0, r'_1) over the 6 slopes, mapped to v.
  J6 x6[kCoordinates];
  for (int i = 0; i < kCoordinates; ++i) x6[i] = J6(e[i]);
  for (int d = 0; d < 3; ++d)
    x6[slopeIndex(0) + d] = J6::variable(e[slopeIndex(0) + d], d),
    x6[slopeIndex(1) + d] = J6::variable(e[slopeIndex(1) + d], 3 + d);
  const detail::NodeData<J6> nodes = detail::nodeData(geo, x6);
  constexpr int kSlope6[6] = {1, 4, 7, 2, 5, 8};
  VecV gBeta = VecV::Zero();
  MatV hBeta = MatV::Zero();
  for (int i = 0; i < 6; ++i) {
    gBeta[kSlope6[i]] = nodes.beta.g[i];
    if constexpr (Hess)
      for (int k = 0; k < 6; ++k) hBeta(kSlope6[i], kSlope6[k]) = nodes.beta.h(i, k);
  }
  // Node 0's zero-twist axes over z (the same at every Gauss point).
  V3<J9> t0, nb2, nb3;
  {
    J9 s0[kCoordinates];
    for (int i = 0; i < kCoordinates; ++i) s0[i] = J9(e[i]);
    for (int d = 0; d < 3; ++d) s0[slopeIndex(0) + d] = J9::variable(e[slopeIndex(0) + d], 3 * d + 1);
    t0 = detail::unit(detail::slopeOf(s0, 0));
    detail::zeroTwistAxes(geo.node[0], t0, nb2, nb3);
  }
  NodeAxes axes;
  if constexpr (Hess) axes = nodeAxes(nb2, t0, nb3);

  VecV vdot = VecV::Zero();
  if (want.damping) {
    vdot = toV(*edot);
    vdot[kPsi1] += gBeta.dot(vdot);
  }
  const double theta0 = e[twistIndex(0)], phiEnd = e[twistIndex(1)] + nodes.beta.v;
  const double gamma = assumedPointwiseWeight(sec, l);
  const bool projected = sec.axialIntegration == AxialIntegration::Assumed && gamma < 1.0;
  const bool axialOnRule5 = sec.axialIntegration != AxialIntegration::Reduced;

  Sums v(want);
  // The projected axial strain's coefficients alpha_j = sum_p w_p L_j(xi_p) eps_p: values, gradients over v and
  // the 3 x 3 block Q_j = sum_p w_p L_j m_p m_p^T (m_p: M's first row) of their Hessians in every direction.
  double alpha[ancf::kAssumedTerms] = {0, 0};
  VecV gAlpha[ancf::kAssumedTerms] = {VecV::Zero(), VecV::Zero()};
  Eigen::Matrix3d qAlpha[ancf::kAssumedTerms] = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};

  const detail::GaussRule &g = detail::rule5();
  for (int p = 0; p < g.n; ++p) {
    const double xi = g.xi[p], wl = g.w[p] * l;
    const Eigen::Vector4d s1 = ancf::shapeValues(xi, l, 1), s2 = ancf::shapeValues(xi, l, 2);
    const Eigen::Matrix3d M = shapeBlock(s1, s2);
    const V3<double> a = detail::interpolate(e.data(), s1), b = detail::interpolate(e.data(), s2);
    CarriedStrains<J9> cs;
    if constexpr (Hess)
      cs = carriedStrainsByProducts(axes, a, b);
    else
      cs = carriedStrains(t0, nb2, nb3, a, b);
    const VecV ydot = want.damping ? pullRates(vdot, M) : VecV::Zero();
    Sums y(want);

    const double phi = (1.0 - xi) * theta0 + xi * phiEnd;
    const double cp = std::cos(phi), sp = std::sin(phi);
    YStrain torsion, k2, k3;
    torsion.v = (phiEnd - theta0) * (1.0 / l) + cs.spin.v;
    torsion.g.setZero();
    torsion.g.head<kZ>() = cs.spin.g.template head<kZ>();
    torsion.g[kTheta0] = -1.0 / l, torsion.g[kPsi1] = 1.0 / l;
    k2.v = cp * cs.X.v + sp * cs.Y.v;
    k3.v = cp * cs.Y.v - sp * cs.X.v;
    const Eigen::Matrix<double, kZ, 1> gz2 = (cp * cs.X.g + sp * cs.Y.g).template head<kZ>(),
                                      gz3 = (cp * cs.Y.g - sp * cs.X.g).template head<kZ>();
    const Eigen::Vector2d dphi(1.0 - xi, xi); // dphi/d(theta_0, psi_1)
    k2.g.setZero(), k3.g.setZero();
    k2.g.head<kZ>() = gz2, k2.g.segment<2>(kTheta0) = k3.v * dphi;
    k3.g.head<kZ>() = gz3, k3.g.segment<2>(kTheta0) = -k2.v * dphi;
    if constexpr (Hess) {
      torsion.h.setZero();
      torsion.h.topLeftCorner<kZ, kZ>() = cs.spin.h.template topLeftCorner<kZ, kZ>();
      k2.h.setZero(), k3.h.setZero();
      k2.h.topLeftCorner<kZ, kZ>() = (cp * cs.X.h + sp * cs.Y.h).template topLeftCorner<kZ, kZ>();
      k3.h.topLeftCorner<kZ, kZ>() = (cp * cs.Y.h - sp * cs.X.h).template topLeftCorner<kZ, kZ>();
      k2.h.block<kZ, 2>(0, kTheta0) = gz3 * dphi.transpose();
      k3.h.block<kZ, 2>(0, kTheta0) = -gz2 * dphi.transpose();
      k2.h.block<2, kZ>(kTheta0, 0) = k2.h.block<kZ, 2>(0, kTheta0).transpose();
      k3.h.block<2, kZ>(kTheta0, 0) = k3.h.block<kZ, 2>(0, kTheta0).transpose();
      k2.h.block<2, 2>(kTheta0, kTheta0) = -k2.v * dphi * dphi.transpose();
      k3.h.block<2, 2>(kTheta0, kTheta0) = -k3.v * dphi * dphi.transpose();
    }
    addTerm<Hess>(torsion, wl * law.stiffness[1], law.eta[1], ydot, want, y);
    addTerm<Hess>(k2, wl * law.stiffness[2], law.eta[2], ydot, want, y);
    addTerm<Hess>(k3, wl * law.stiffness[3], law.eta[3], ydot, want, y);
    const YStrain axial = axialStrain<Hess>(a);
    if (axialOnRule5) addTerm<Hess>(axial, gamma * wl * law.stiffness[0], law.eta[0], ydot, want, y);
    pushSums(y, M, want, v);
    if (projected)
      for (int j = 0; j < ancf::kAssumedTerms; ++j) {
        const double wj = g.w[p] * detail::legendre01(j, xi);
        alpha[j] += wj * axial.v;
        pushAdd(VecV(wj * axial.g), M, gAlpha[j]);
        const Eigen::Vector3d m = M.row(0).transpose();
        qAlpha[j].noalias() += wj * m * m.transpose();
      }
  }
  if (projected)
    for (int j = 0; j < ancf::kAssumedTerms; ++j) {
      // alpha_j is a sum over the points: its gradient and Hessian live on v.
      const double c = (1.0 - gamma) * l * law.stiffness[0], ce = c * law.eta[0];
      const VecV &ga = gAlpha[j];
      v.f += (c * alpha[j]) * ga;
      MatV h = MatV::Zero();
      for (int d = 0; d < 3; ++d) h.block<3, 3>(3 * d, 3 * d) = qAlpha[j];
      if (want.K) {
        v.K.noalias() += c * ga * ga.transpose();
        v.K.noalias() += (c * alpha[j]) * h;
      }
      if (want.damping && ce != 0) {
        const double rate = ga.dot(vdot);
        v.fd += (ce * rate) * ga;
        v.power += ce * rate * rate;
        if (want.Dv) v.Dv.noalias() += ce * ga * ga.transpose();
        if (want.Kq) {
          v.Kq.noalias() += ce * ga * (h * vdot).transpose();
          v.Kq.noalias() += (ce * rate) * h;
        }
      }
    }
  if (!axialOnRule5) {
    const detail::GaussRule &r = detail::rule3();
    for (int p = 0; p < r.n; ++p) {
      const Eigen::Vector4d s1 = ancf::shapeValues(r.xi[p], l, 1);
      const Eigen::Matrix3d M = shapeBlock(s1, Eigen::Vector4d::Zero());
      const VecV ydot = want.damping ? pullRates(vdot, M) : VecV::Zero();
      Sums y(want);
      addTerm<Hess>(axialStrain<Hess>(detail::interpolate(e.data(), s1)), r.w[p] * l * law.stiffness[0], law.eta[0],
                    ydot, want, y);
      pushSums(y, M, want, v);
    }
  }

  // psi_1 -> theta_1: first the terms of beta's curvature (their weights are
  // the psi_1 components before the change), then B^T (.) B.
  if constexpr (Hess) {
    if (want.K) {
      v.K.noalias() += v.f[kPsi1] * hBeta;
      changeToTheta(v.K, gBeta);
    }
    if (want.Kq) {
      // dfd/dw = B^T Kq_v B + (B^T u) (d^2beta wdot)^T + fd_psi1 d^2beta.
      VecV wdot = toV(*edot);
      changeToTheta(v.u, gBeta);
      const VecV hBetaRate = hBeta * wdot;
      changeToTheta(v.Kq, gBeta);
      v.Kq.noalias() += v.u * hBetaRate.transpose();
      v.Kq.noalias() += v.fd[kPsi1] * hBeta;
    }
  }
  changeToTheta(v.f, gBeta);
  scatter(v.f, f);
  if (K) scatter(v.K, *K);
  if (!want.damping) return 0;
  changeToTheta(v.fd, gBeta);
  scatter(v.fd, *fd);
  if (Dv) {
    changeToTheta(v.Dv, gBeta);
    scatter(v.Dv, *Dv);
  }
  if (Kq) scatter(v.Kq, *Kq);
  return v.power;
}

} // namespace

void internalForce(const Section &sec, const Geometry &geo, const Vec14 &e, Vec14 &f, Mat14 *K)
{
  if (K)
    elementForces<true>(sec, geo, e, nullptr, f, K, nullptr, nullptr, nullptr);
  else
    elementForces<false>(sec, geo, e, nullptr, f, nullptr, nullptr, nullptr, nullptr);
}

double internalAndDampingForce(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 &edot, Vec14 &f,
                               Mat14 *K, Vec14 &fd, Mat14 *Kq, Mat14 *Dv)
{
  if (K || Kq) return elementForces<true>(sec, geo, e, &edot, f, K, &fd, Kq, Dv);
  return elementForces<false>(sec, geo, e, &edot, f, nullptr, &fd, nullptr, Dv);
}

double dampingForce(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 &edot, Vec14 &fd, Mat14 *Kq,
                    Mat14 *Dv)
{
  Vec14 f;
  if (Kq) return elementForces<true>(sec, geo, e, &edot, f, nullptr, &fd, Kq, Dv);
  return elementForces<false>(sec, geo, e, &edot, f, nullptr, &fd, nullptr, Dv);
}

} // namespace boomdyn::spatial_beam
