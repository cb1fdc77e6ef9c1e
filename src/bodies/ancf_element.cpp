#include "boomdyn/ancf_element.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace boomdyn::ancf {

namespace {

// One quadrature point on [0, 1]: position, weight, and the factors (0 or
// 1) of the axial and bending terms evaluated there. With full integration
// both factors are 1 at every point; multiplying by 1.0 is exact, so the
// full rule gives bit-identical results to a single combined loop.
struct QuadPoint {
  double xi, w, axial, bending;
};

struct QuadRule {
  std::array<QuadPoint, kGaussPoints + kReducedAxialPoints> points;
  int size;
};

// n-point Gauss-Legendre (n = 3 or 5) on [0, 1].
void gaussLegendre01(int n, double *xi, double *w)
{
  if (n == 3) {
    const double a = std::sqrt(0.6);
    const double x[3] = {-a, 0.0, a}, wt[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    for (int i = 0; i < 3; ++i) xi[i] = 0.5 * (x[i] + 1.0), w[i] = 0.5 * wt[i];
    return;
  }
  const double a = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  const double b = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  const double wa = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
  const double wb = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
  const double x[5] = {-b, -a, 0.0, a, b}, wt[5] = {wb, wa, 128.0 / 225.0, wa, wb};
  for (int i = 0; i < 5; ++i) xi[i] = 0.5 * (x[i] + 1.0), w[i] = 0.5 * wt[i];
}

QuadRule makeRule(AxialIntegration axial)
{
  QuadRule r{};
  double xi[kGaussPoints], w[kGaussPoints];
  gaussLegendre01(kGaussPoints, xi, w);
  const double fullAxial = axial == AxialIntegration::Reduced ? 0.0 : 1.0;
  for (int i = 0; i < kGaussPoints; ++i) r.points[i] = {xi[i], w[i], fullAxial, 1.0};
  r.size = kGaussPoints;
  if (axial == AxialIntegration::Reduced) {
    gaussLegendre01(kReducedAxialPoints, xi, w);
    for (int i = 0; i < kReducedAxialPoints; ++i) r.points[r.size++] = {xi[i], w[i], 1.0, 0.0};
  }
  return r;
}

const QuadRule &quadRule(AxialIntegration axial)
{
  static const QuadRule full = makeRule(AxialIntegration::Full), reduced = makeRule(AxialIntegration::Reduced);
  return axial == AxialIntegration::Reduced ? reduced : full;
}

// Orthonormal Legendre polynomials on [0, 1] (degree 0 and 1): the basis of the assumed axial strain.
// The 5-point rule, computed once.
struct GaussRule5 {
  double xi[kGaussPoints], w[kGaussPoints];
  GaussRule5() { gaussLegendre01(kGaussPoints, xi, w); }
};

inline double legendre01(int j, double xi) { return j == 0 ? 1.0 : std::sqrt(3.0) * (2.0 * xi - 1.0); }

// w_p phi_j(xi_p) on the 5-point rule: the weights of the assumed strain's projection.
double projectionWeight(int j, int p)
{
  static const GaussRule5 rule;
  return rule.w[p] * legendre01(j, rule.xi[p]);
}

// s' and s'' of the shape functions at a rule's points for an element
// length: the same values shapeValues() gives there, computed once per beam
// instead of at every evaluation. A few lengths are kept (the beams of a
// model are assembled one after the other; another length replaces the
// oldest entry).
struct ShapeTable {
  const QuadRule *rule = nullptr;
  double l = 0;
  Eigen::Vector4d s1[kGaussPoints + kReducedAxialPoints], s2[kGaussPoints + kReducedAxialPoints];
  // phi_1(xi) at the rule's points, and w_p phi_j(xi_p) on the 5-point rule
  // of the assumed strain's projection (legendre01 below; the same products).
  double legendre1[kGaussPoints + kReducedAxialPoints];
  double projectionWeight[kAssumedTerms][kGaussPoints];
  // s1, s2 in every lane (the batched kernel's operands: a product with a
  // lane vector of one value is the product with the value, bit for bit).
  lanes::Lanes4 s1Lanes[kGaussPoints + kReducedAxialPoints][4], s2Lanes[kGaussPoints + kReducedAxialPoints][4];
};

// The shape values at point p as the kernel's operand type: doubles, or lanes.
inline const double *shapeOperands(const Eigen::Vector4d (&s)[kGaussPoints + kReducedAxialPoints],
                                   const lanes::Lanes4 (&)[kGaussPoints + kReducedAxialPoints][4], int p, double *)
{
  return s[p].data();
}
inline const lanes::Lanes4 *shapeOperands(const Eigen::Vector4d (&)[kGaussPoints + kReducedAxialPoints],
                                           const lanes::Lanes4 (&v)[kGaussPoints + kReducedAxialPoints][4], int p,
                                           lanes::Lanes4 *)
{
  return v[p];
}


const ShapeTable &shapeTable(const QuadRule &g, double l)
{
  constexpr int kKept = 4;
  thread_local ShapeTable kept[kKept];
  thread_local int next = 0;
  for (const ShapeTable &t : kept)
    if (t.rule == &g && t.l == l) return t;
  ShapeTable &t = kept[next];
  next = (next + 1) % kKept;
  t.rule = &g;
  t.l = l;
  for (int p = 0; p < g.size; ++p) {
    t.s1[p] = shapeValues(g.points[p].xi, l, 1);
    t.s2[p] = shapeValues(g.points[p].xi, l, 2);
    t.legendre1[p] = legendre01(1, g.points[p].xi);
    for (int k = 0; k < 4; ++k) {
      const double a = t.s1[p][k], b = t.s2[p][k];
      t.s1Lanes[p][k] = lanes::Lanes4{a, a, a, a};
      t.s2Lanes[p][k] = lanes::Lanes4{b, b, b, b};
    }
  }
  for (int j = 0; j < kAssumedTerms; ++j)
    for (int p = 0; p < kGaussPoints; ++p) t.projectionWeight[j][p] = projectionWeight(j, p);
  return t;
}

// Scalar cross product a x b = a_x b_y - a_y b_x.
inline double cross(const Vec2 &a, const Vec2 &b) { return a.x() * b.y() - a.y() * b.x(); }

// Expand 4 scalar shape values into the 8-vector (s ⊗ v) with v 2-D: entry 2k+d = s_k v_d.
inline Vec8 expand(const Eigen::Vector4d &s, const Vec2 &v)
{
  Vec8 out;
  for (int k = 0; k < 4; ++k) {
    out[2 * k] = s[k] * v.x();
    out[2 * k + 1] = s[k] * v.y();
  }
  return out;
}

// Rotated vector W v with a x b = a^T W b, i.e. W v = (v_y, -v_x).
inline Vec2 rotCW(const Vec2 &v) { return Vec2(v.y(), -v.x()); }

// r', r'' at a point with shape derivatives s1, s2, and their rates (the
// same sums from edot): what the damping force needs per Gauss point.
inline void slopesAndRates(const Eigen::Vector4d &s1, const Eigen::Vector4d &s2, const Vec8 &e, const Vec8 &edot,
                           Vec2 &r1, Vec2 &r2, Vec2 &r1d, Vec2 &r2d)
{
  r1 = r2 = r1d = r2d = Vec2::Zero();
  for (int k = 0; k < 4; ++k) {
    r1 += s1[k] * e.segment<2>(2 * k);
    r2 += s2[k] * e.segment<2>(2 * k);
    r1d += s1[k] * edot.segment<2>(2 * k);
    r2d += s2[k] * edot.segment<2>(2 * k);
  }
}

// Add (P ⊗ I) + (Q ⊗ W), W = [[0, 1], [-1, 0]], to an 8x8 matrix: the
// Hessians of the axial strain and of r' x r'' are of these forms.
void addKronecker(const Eigen::Matrix4d &P, const Eigen::Matrix4d &Q, Mat8 &M)
{
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      M(2 * a, 2 * b) += P(a, b);
      M(2 * a + 1, 2 * b + 1) += P(a, b);
      M(2 * a, 2 * b + 1) += Q(a, b);
      M(2 * a + 1, 2 * b) -= Q(a, b);
    }
}


inline Vec2 slopeAt(const Eigen::Vector4d &s1, const Vec8 &e)
{
  Vec2 r1 = Vec2::Zero();
  for (int k = 0; k < 4; ++k) r1 += s1[k] * e.segment<2>(2 * k);
  return r1;
}

// Assumed axial strain (AxialIntegration::Assumed, docs/model.md §1.1): the
// Green strain projected in L2 onto the polynomials of degree < n on the
// element, epsbar = sum_j alpha_j phi_j with alpha_j = ∫ phi_j eps dxi (exact
// on the 5 Gauss points: degree <= 6). The axial energy is
//   1/2 EA l [(1 - gamma) sum_j alpha_j^2 + gamma ∫ eps^2 dxi],
// the pointwise part (weight gamma, on the quadrature points of the rule)
// stabilizing the axial zero-energy mode that the projection alone leaves.
struct AxialProjection {
  int n = 0;                  // basis functions; 0: no projection (Full, Reduced)
  double gamma = 1.0;         // weight of the pointwise axial energy
  double alpha[kAssumedTerms] = {}, alphaDot[kAssumedTerms] = {};
  Vec8 grad[kAssumedTerms], gradDot[kAssumedTerms];   // d alpha_j / de and d alphadot_j / de (= H_j edot)
  // Projected strain and strain rate at xi.
  double strain(double xi) const
  {
    double v = 0;
    for (int j = 0; j < n; ++j) v += alpha[j] * legendre01(j, xi);
    return v;
  }
  double rate(double xi) const
  {
    double v = 0;
    for (int j = 0; j < n; ++j) v += alphaDot[j] * legendre01(j, xi);
    return v;
  }
};

// The projection of eps (and, with edot, of its rate) for the section's
// axial treatment. The gradients d alpha_j / de (and d alphadot_j / de) are
// formed only when asked for: a residual without damping needs alpha alone.
// s1 comes from the element's shape table (the 5-point rule of the Assumed
// treatment, the points and values of GaussRule5 and shapeValues(xi, l, 1)
// exactly), so the result is bit-identical to computing it here. slopes:
// r' at the rule's points if the caller has them already (the same sums).
AxialProjection projectAxialStrain(const Section &sec, double l, const ShapeTable &shapes, const Vec8 &e,
                                   const Vec8 *edot, bool gradients, const Vec2 *slopes = nullptr)
{
  AxialProjection a;
  if (sec.axialIntegration != AxialIntegration::Assumed) return a;
  a.gamma = assumedPointwiseWeight(sec, l);
  // Stocky beams (EA L^2/EI <= kAssumedStabilization): the full element, bit for bit.
  if (a.gamma >= 1.0) return a;
  a.n = kAssumedTerms;
  static const GaussRule5 rule;
  const double *xi = rule.xi, *w = rule.w;
  if (gradients)
    for (int j = 0; j < a.n; ++j) a.grad[j].setZero(), a.gradDot[j].setZero();
  for (int p = 0; p < kGaussPoints; ++p) {
    const Eigen::Vector4d &s1 = shapes.s1[p];
    const Vec2 r1 = slopes ? slopes[p] : slopeAt(s1, e);
    const double eps = 0.5 * (r1.squaredNorm() - 1.0);
    Vec2 r1d = Vec2::Zero();
    if (edot) r1d = slopeAt(s1, *edot);
    for (int j = 0; j < a.n; ++j) {
      const double wp = w[p] * legendre01(j, xi[p]);
      a.alpha[j] += wp * eps;
      if (edot) a.alphaDot[j] += wp * r1.dot(r1d);
      if (!gradients) continue;
      a.grad[j] += wp * expand(s1, r1);
      if (edot) a.gradDot[j] += wp * expand(s1, r1d);
    }
  }
  return a;
}

} // namespace

double assumedPointwiseWeight(const Section &sec, double l)
{
  if (sec.axialIntegration != AxialIntegration::Assumed) return 1.0;
  const double L = sec.length > 0 ? sec.length : l;
  return std::min(1.0, kAssumedStabilization * sec.EI / (sec.EA * L * L));
}

Eigen::Vector4d shapeValues(double xi, double l, int derivative)
{
  const double x2 = xi * xi, x3 = x2 * xi;
  switch (derivative) {
  case 0:
    return {1 - 3 * x2 + 2 * x3, l * (xi - 2 * x2 + x3), 3 * x2 - 2 * x3, l * (-x2 + x3)};
  case 1:
    return Eigen::Vector4d(-6 * xi + 6 * x2, l * (1 - 4 * xi + 3 * x2), 6 * xi - 6 * x2, l * (-2 * xi + 3 * x2)) / l;
  case 2:
    return Eigen::Vector4d(-6 + 12 * xi, l * (-4 + 6 * xi), 6 - 12 * xi, l * (-2 + 6 * xi)) / (l * l);
  case 3:
    return Eigen::Vector4d(12, 6 * l, -12, 6 * l) / (l * l * l);
  default:
    return Eigen::Vector4d::Zero();
  }
}

Mat28 shapeMatrix(double xi, double l, int derivative)
{
  const Eigen::Vector4d s = shapeValues(xi, l, derivative);
  Mat28 S = Mat28::Zero();
  for (int k = 0; k < 4; ++k) {
    S(0, 2 * k) = s[k];
    S(1, 2 * k + 1) = s[k];
  }
  return S;
}

Vec2 position(const Vec8 &e, double xi, double l, int derivative)
{
  const Eigen::Vector4d s = shapeValues(xi, l, derivative);
  Vec2 r = Vec2::Zero();
  for (int k = 0; k < 4; ++k) r += s[k] * e.segment<2>(2 * k);
  return r;
}

Mat8 massMatrix(double rhoA, double l)
{
  // ∫_0^1 s_a s_b dxi for the cubic Hermite functions (the classic beam
  // consistent-mass matrix /(420)), expanded to both directions.
  Eigen::Matrix4d m;
  m << 156, 22 * l, 54, -13 * l,
       22 * l, 4 * l * l, 13 * l, -3 * l * l,
       54, 13 * l, 156, -22 * l,
       -13 * l, -3 * l * l, -22 * l, 4 * l * l;
  m *= rhoA * l / 420.0;
  Mat8 M = Mat8::Zero();
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      M(2 * a, 2 * b) = m(a, b);
      M(2 * a + 1, 2 * b + 1) = m(a, b);
    }
  return M;
}

Vec8 gravityForce(double rhoA, double l, const Vec2 &g)
{
  // ∫_0^1 s_k dxi = (1/2, l/12, 1/2, -l/12).
  const Eigen::Vector4d integral(0.5, l / 12.0, 0.5, -l / 12.0);
  return expand(rhoA * l * integral, g);
}

double axialStrain(const Vec8 &e, double xi, double l)
{
  const Vec2 r1 = position(e, xi, l, 1);
  return 0.5 * (r1.squaredNorm() - 1.0);
}

double curvature(const Vec8 &e, double xi, double l)
{
  const Vec2 r1 = position(e, xi, l, 1), r2 = position(e, xi, l, 2);
  return cross(r1, r2) / r1.squaredNorm();
}

double strainEnergy(const Section &sec, double l, const Vec8 &e)
{
  // axialStrain(e, q.xi, l) and curvature(e, q.xi, l) with the tabulated
  // shape derivatives (the same values, the same sums: bit-identical); the
  // energy diagnostics evaluate this for every element after every step.
  // r' at the rule's points once, for the pointwise energy and for the
  // projection of the assumed strain (projectAxialStrain's sums, in its
  // order, on the same slopes: it formed r' at the 5 points again). The
  // slopes stay 2-vectors: x and y in one SSE2 register, half the
  // instructions of scalar code here.
  const QuadRule &g = quadRule(sec.axialIntegration);
  const ShapeTable &shapes = shapeTable(g, l);
  constexpr int kMax = kGaussPoints + kReducedAxialPoints;
  double J2[kMax], C[kMax];
  for (int p = 0; p < g.size; ++p) {
    const Eigen::Vector4d &s1 = shapes.s1[p], &s2 = shapes.s2[p];
    Vec2 r1 = Vec2::Zero(), r2 = Vec2::Zero();
    for (int k = 0; k < 4; ++k) r1 += s1[k] * e.segment<2>(2 * k);
    for (int k = 0; k < 4; ++k) r2 += s2[k] * e.segment<2>(2 * k);
    J2[p] = r1.squaredNorm();
    C[p] = cross(r1, r2);
  }
  const double gamma = assumedPointwiseWeight(sec, l);
  const bool projected = sec.axialIntegration == AxialIntegration::Assumed && gamma < 1.0;
  double alpha[kAssumedTerms] = {};
  if (projected)
    for (int p = 0; p < kGaussPoints; ++p) {
      const double eps = 0.5 * (J2[p] - 1.0);
      for (int j = 0; j < kAssumedTerms; ++j) alpha[j] += shapes.projectionWeight[j][p] * eps;
    }
  double U = 0;
  for (int p = 0; p < g.size; ++p) {
    const QuadPoint &q = g.points[p];
    const double eps = 0.5 * (J2[p] - 1.0), K = C[p] / J2[p];
    U += q.w * (q.axial * gamma * sec.EA * eps * eps + q.bending * sec.EI * K * K);
  }
  if (projected)
    for (int j = 0; j < kAssumedTerms; ++j) U += (1.0 - gamma) * sec.EA * alpha[j] * alpha[j];
  return 0.5 * l * U;
}

namespace {

// The elastic force of one quadrature point (weight wx = w l), added to fl:
// N = EA eps + EAproj (alpha_0 + alpha_1 phi_1) (the projection's term +0
// without it), f += s1 (wx (N r' + b n(r''))) - s2 (wx b n(r')), with
// b = EI K / |r'|^2 and n the rotation by -90 degrees. Shared by the
// force-only and the force-and-damping kernels, so that both do the same
// operations in the same order (their forces are bit for bit equal: tests
// AncfElement.ForceOnlyPathIsBitIdentical, InternalAndDampingForceIsBitIdentical).
// K and 1/|r'|^2 go out for the damping force. S: double or the lanes.
template <typename T, typename S>
inline void addElasticForceAt(double wx, double EA, double EI, double EAproj, bool projected, const T &alpha0,
                              const T &alpha1, double legendre1, const T &r1x, const T &r1y, const T &r2x,
                              const T &r2y, const S *s1, const S *s2, T fl[8], T *curvature, T *inverseJ2)
{
  const T J2 = r1x * r1x + r1y * r1y, iJ2 = 1.0 / J2;
  const T eps = 0.5 * (J2 - 1.0);
  const T K = (r1x * r2y - r1y * r2x) * iJ2;
  // proj.strain(q.xi): alpha_0 phi_0 + alpha_1 phi_1, summed from zero.
  T strain{};
  strain += alpha0 * 1.0;
  strain += alpha1 * legendre1;
  T axial{}; // EAproj * strain, or +0 without the projection
  if (projected) axial = EAproj * strain;
  const T N = EA * eps + axial;
  const T a = N - 2.0 * EI * K * K * iJ2, b = EI * K * iJ2;
  const T v1x = wx * (a * r1x + b * r2y), v1y = wx * (a * r1y + b * -r2x);
  const T wb = wx * b, v2x = wb * r1y, v2y = wb * -r1x;
  for (int k = 0; k < 4; ++k) {
    fl[2 * k] += s1[k] * v1x - s2[k] * v2x;
    fl[2 * k + 1] += s1[k] * v1y - s2[k] * v2y;
  }
  *curvature = K, *inverseJ2 = iJ2;
}

// internalForce without the tangent (every residual evaluation): the
// operations of the general path below, in the same order, on scalars, so
// the force is bit-identical to it (test AncfElement.ForceOnlyPathIsBitIdentical).
// What it saves is data movement, not arithmetic: no AxialProjection
// record (alpha, gradients) is built and returned, the Legendre weights
// come from the shape table, and r', r'' stay in registers as x and y parts
// instead of 2-vectors (the Eigen path spent more instructions on moves and
// shuffles than on its ~400 flops; callgrind, docs/performance-history.md).
// T is double (one element) or ForceLanes (kForceBatch elements of one
// beam, one per lane): every operation is lane-wise IEEE arithmetic in the
// same order as the scalar one (no FMA in this build, no reassociation), so
// each lane is bit for bit the scalar element (test
// AncfElement.BatchedForceIsBitIdentical). e and f hold 8 values of T.
// NP: the rule's size (g.size) as a constant, so that the loops over the
// points unroll (the two rules: 5 points, 8 with reduced axial points).
template <typename T, int NP>
void internalForceOnlyN(const Section &sec, double l, const QuadRule &g, const ShapeTable &shapes, const T *e, T *f)
{
  T r1x[NP], r1y[NP], r2x[NP], r2y[NP];
  for (int p = 0; p < NP; ++p) {
    const auto *s1 = shapeOperands(shapes.s1, shapes.s1Lanes, p, static_cast<T *>(nullptr));
    const auto *s2 = shapeOperands(shapes.s2, shapes.s2Lanes, p, static_cast<T *>(nullptr));
    T ax{}, ay{}, bx{}, by{};
    for (int k = 0; k < 4; ++k) {
      ax += s1[k] * e[2 * k];
      ay += s1[k] * e[2 * k + 1];
      bx += s2[k] * e[2 * k];
      by += s2[k] * e[2 * k + 1];
    }
    r1x[p] = ax, r1y[p] = ay, r2x[p] = bx, r2y[p] = by;
  }
  // projectAxialStrain(.., gradients = false) with the slopes above.
  const double gamma = assumedPointwiseWeight(sec, l);
  const bool projected = sec.axialIntegration == AxialIntegration::Assumed && gamma < 1.0;
  T alpha0{}, alpha1{};
  if (projected)
    for (int p = 0; p < kGaussPoints; ++p) {
      const T eps = 0.5 * ((r1x[p] * r1x[p] + r1y[p] * r1y[p]) - 1.0);
      alpha0 += shapes.projectionWeight[0][p] * eps;
      alpha1 += shapes.projectionWeight[1][p] * eps;
    }
  const double EAproj = (1.0 - gamma) * sec.EA;
  T fl[8] = {};
  for (int p = 0; p < NP; ++p) {
    const QuadPoint &q = g.points[p];
    const double EA = q.axial * gamma * sec.EA, EI = q.bending * sec.EI;
    const auto *s1 = shapeOperands(shapes.s1, shapes.s1Lanes, p, static_cast<T *>(nullptr));
    const auto *s2 = shapeOperands(shapes.s2, shapes.s2Lanes, p, static_cast<T *>(nullptr));
    T K, iJ2;
    addElasticForceAt(q.w * l, EA, EI, EAproj, projected, alpha0, alpha1, shapes.legendre1[p], r1x[p], r1y[p],
                      r2x[p], r2y[p], s1, s2, fl, &K, &iJ2);
  }
  for (int i = 0; i < 8; ++i) f[i] = fl[i];
}

template <typename T>
void internalForceOnly(const Section &sec, double l, const QuadRule &g, const ShapeTable &shapes, const T *e, T *f)
{
  static_assert(kGaussPoints == 5 && kGaussPoints + kReducedAxialPoints == 8, "the two rules' sizes");
  if (g.size == kGaussPoints) internalForceOnlyN<T, kGaussPoints>(sec, l, g, shapes, e, f);
  else internalForceOnlyN<T, kGaussPoints + kReducedAxialPoints>(sec, l, g, shapes, e, f);
}

// r' and r'' at every point of the rule g, for the kernels with a tangent
// and the assumed strain's projection (on the same points when it applies).
void slopesAtPoints(const QuadRule &g, const ShapeTable &shapes, const Vec8 &e, Vec2 *slopes, Vec2 *curvatures)
{
  for (int p = 0; p < g.size; ++p) {
    Vec2 r1 = Vec2::Zero(), r2 = Vec2::Zero();
    for (int k = 0; k < 4; ++k) {
      r1 += shapes.s1[p][k] * e.segment<2>(2 * k);
      r2 += shapes.s2[p][k] * e.segment<2>(2 * k);
    }
    slopes[p] = r1, curvatures[p] = r2;
  }
}

} // namespace

void internalForce(const Section &sec, double l, const Vec8 &e, Vec8 &f, Mat8 *Kt)
{
  const QuadRule &g = quadRule(sec.axialIntegration);
  if (!Kt) {
    internalForceOnly<double>(sec, l, g, shapeTable(g, l), e.data(), f.data());
    return;
  }
  const ShapeTable &shapes = shapeTable(g, l);
  // r' and r'' at every point, once: the assumed strain's projection (on the
  // same 5 points when it applies) and the loop below both need them.
  Vec2 slopes[kGaussPoints + kReducedAxialPoints], curvatures[kGaussPoints + kReducedAxialPoints];
  slopesAtPoints(g, shapes, e, slopes, curvatures);
  const AxialProjection proj = projectAxialStrain(sec, l, shapes, e, nullptr, Kt != nullptr,
                                                  sec.axialIntegration == AxialIntegration::Assumed ? slopes : nullptr);
  const double EAproj = (1.0 - proj.gamma) * sec.EA; // EA of the projected strain (0 unless Assumed)
  Vec8 fl = Vec8::Zero(); // local accumulator: f may alias e
  // With a = EA eps - 2 EI K^2 / J2 and b = EI K / J2 (dK = (dc - 2 K dEps) / J2),
  //   f  = sum wx (a dEps + b dc),
  //   Kt = sum wx (EA dEps dEps^T + EI dK dK^T - 2b (dK dEps^T + dEps dK^T) + a d2eps + b d2c),
  // where d2eps = S'^T S' = (s1 s1^T) ⊗ I and d2c = S'^T W S'' + S''^T W^T S' = (s1 s2^T - s2 s1^T) ⊗ W
  // only depend on the shape functions: their scalar 4x4 parts are summed
  // over the Gauss points (P, Q) and expanded once at the end.
  Eigen::Matrix4d P, Q;
  if (Kt) {
    P.setZero(), Q.setZero();
    Kt->setZero();
  }
  for (int p = 0; p < g.size; ++p) {
    const QuadPoint &q = g.points[p];
    const double EA = q.axial * proj.gamma * sec.EA, EI = q.bending * sec.EI; // this point's terms
    const Eigen::Vector4d &s1 = shapes.s1[p], &s2 = shapes.s2[p];
    const Vec2 &r1 = slopes[p], &r2 = curvatures[p];
    const double wx = q.w * l; // dx weight
    const double J2 = r1.squaredNorm(), iJ2 = 1.0 / J2;
    const double eps = 0.5 * (J2 - 1.0);
    const double K = cross(r1, r2) * iJ2;
    // Axial force: pointwise strain, plus the projected strain (Assumed; on the 5 points of its projection).
    const double N = EA * eps + (proj.n ? EAproj * proj.strain(q.xi) : 0.0);
    const double a = N - 2.0 * EI * K * K * iJ2, b = EI * K * iJ2;
    // dEps = s1 ⊗ r1, dc = s1 ⊗ W r2 - s2 ⊗ W r1.
    const Vec2 v1 = wx * (a * r1 + b * rotCW(r2)), v2 = (wx * b) * rotCW(r1);
    for (int k = 0; k < 4; ++k) fl.segment<2>(2 * k) += s1[k] * v1 - s2[k] * v2;
    if (!Kt) continue;
    const Vec8 dEps = expand(s1, r1);
    const Vec8 dK = (expand(s1, rotCW(r2)) - expand(s2, rotCW(r1)) - 2.0 * K * dEps) * iJ2;
    Eigen::Matrix<double, 8, 2> G;
    G << dEps, dK;
    Eigen::Matrix2d Mw;
    Mw << wx * EA, -2.0 * wx * b, -2.0 * wx * b, wx * EI;
    Kt->noalias() += G * Mw * G.transpose();
    P.noalias() += (wx * a) * s1 * s1.transpose();
    Q.noalias() += (wx * b) * (s1 * s2.transpose() - s2 * s1.transpose());
  }
  f = fl;
  if (!Kt) return;
  addKronecker(P, Q, *Kt);
  for (int j = 0; j < proj.n; ++j) Kt->noalias() += (EAproj * l) * proj.grad[j] * proj.grad[j].transpose();
}

void internalForceLanes(const Section &sec, double l, const ForceLanes e[8], ForceLanes f[8])
{
  const QuadRule &g = quadRule(sec.axialIntegration);
  internalForceOnly<ForceLanes>(sec, l, g, shapeTable(g, l), e, f);
}

void internalForceBatch(const Section &sec, double l, const double *const e[kForceBatch], double *const f[kForceBatch])
{
  // Lanes in, one element per lane (the transpose of kForceBatch element
  // vectors), the scalar kernel's operations on the lanes, lanes out.
  ForceLanes el[8], fl[8];
  lanes::gatherLanes(e, 0, el), lanes::gatherLanes(e, 4, el + 4);
  internalForceLanes(sec, l, el, fl);
  lanes::scatterLanes(fl, f, 0), lanes::scatterLanes(fl + 4, f, 4);
}

namespace {

// Below this, no product of two factors overflows (the rest-rate test below).
inline bool moderate(double x) { return std::abs(x) < 1e100; }
template <typename V> bool moderate(const V &v) { return (v.array().abs() < 1e100).all(); }
// Every entry zero (either sign); a plain loop that stops at the first
// nonzero (a Newton tangent's rates): Eigen's all() over the comparison was
// an out-of-line call on every tangent of a damped element.
inline bool allZero(const Vec8 &x)
{
  for (int i = 0; i < 8; ++i)
    if (x[i] != 0.0) return false;
  return true;
}

// dampingForce; restShortcut: at zero rate, Kq is set to zero instead of
// summed (see there).
double dampingForceImpl(const Section &sec, double l, const Vec8 &e, const Vec8 &edot, Vec8 &fd, Mat8 *Kq, Mat8 *Dv,
                        bool restShortcut)
{
  // The axial strain rate on the points of the axial strain, so that D stays etaA K_axial.
  const QuadRule &g = quadRule(sec.axialIntegration);
  const ShapeTable &shapes = shapeTable(g, l);
  const AxialProjection proj = projectAxialStrain(sec, l, shapes, e, &edot, true);
  const double cproj = (1.0 - proj.gamma) * sec.EA * sec.etaA * l; // projected strain rate (Assumed)
  Vec8 fl = Vec8::Zero(); // local accumulator: fd may alias e or edot
  double power = 0;
  // With g_e = deps/de, g_K = dK/de and their Hessians H_e = (s1 s1^T) ⊗ I,
  // H_K = (H_c - 2 K H_e - 2 (g_e g_K^T + g_K g_e^T)) / J2, the rates are
  // epsdot = g_e . edot, Kdot = g_K . edot, and per Gauss point
  //   fd    = ca epsdot g_e + cb Kdot g_K                   (ca = wx EA etaA, cb = wx EI etaB)
  //   dfd/dedot = ca g_e g_e^T + cb g_K g_K^T
  //   dfd/de    = ca (g_e h_e^T + epsdot H_e) + cb (g_K h_K^T + Kdot H_K),  h = H edot.
  Eigen::Matrix4d P, Q;
  if (Kq) P.setZero(), Q.setZero(), Kq->setZero();
  if (Dv) Dv->setZero();
  // At rest (edot all zeros, either sign: the eigen-analysis' damping pencil
  // is taken at v = 0) r1d = r2d = +0 exactly (sums from zero), and so
  // epsdot, Kdot, hE, hK, bd, alphadot, gradDot and the rate of the projected
  // strain are signed zeros: every term summed into Kq, P and Q is a product
  // with a zero factor and is itself a signed zero as long as the other
  // factors are finite and no product of two of them overflows (all below
  // 1e100, checked point by point), and sums from +0 of signed zeros stay
  // +0. Kq is then +0 everywhere, bit for bit what the sums give, and is left
  // as set above; the sums are what dfd/de cost (about 2/3 of a tangent
  // evaluation). A factor out of range: the full sums (restShortcut false).
  const bool atRest = Kq && restShortcut && allZero(edot);
  bool restExact = atRest;
  for (int p = 0; p < g.size; ++p) {
    const QuadPoint &q = g.points[p];
    const Eigen::Vector4d &s1 = shapes.s1[p], &s2 = shapes.s2[p];
    Vec2 r1, r2, r1d, r2d;
    slopesAndRates(s1, s2, e, edot, r1, r2, r1d, r2d);
    const double wx = q.w * l;
    const double ca = wx * proj.gamma * sec.EA * sec.etaA * q.axial, cb = wx * sec.EI * sec.etaB * q.bending;
    const double iJ2 = 1.0 / r1.squaredNorm();
    const double K = cross(r1, r2) * iJ2;
    const double epsdot = r1.dot(r1d);
    const double Kdot = (cross(r1d, r2) + cross(r1, r2d) - 2.0 * K * epsdot) * iJ2;
    power += ca * epsdot * epsdot + cb * Kdot * Kdot;
    if (!Kq && !Dv) {
      // Force only (residuals, energy diagnostics): the same sum per node
      // block, s1_k u1 - s2_k u2, without forming g_e and g_K as 8-vectors.
      const double bK = cb * Kdot * iJ2;
      const Vec2 u1 = (ca * epsdot) * r1 + bK * (rotCW(r2) - (2.0 * K) * r1), u2 = bK * rotCW(r1);
      for (int k = 0; k < 4; ++k) fl.segment<2>(2 * k) += s1[k] * u1 - s2[k] * u2;
      continue;
    }
    const Vec8 gE = expand(s1, r1);
    const Vec8 gK = (expand(s1, rotCW(r2)) - expand(s2, rotCW(r1)) - 2.0 * K * gE) * iJ2;
    fl += (ca * epsdot) * gE + (cb * Kdot) * gK;
    if (Dv) Dv->noalias() += ca * gE * gE.transpose() + cb * gK * gK.transpose();
    if (!Kq) continue;
    if (atRest) {
      restExact = restExact && moderate(ca) && moderate(cb) && moderate(iJ2) && moderate(K) && moderate(r1) &&
                  moderate(r2) && moderate(s1) && moderate(s2) && moderate(gE) && moderate(gK) &&
                  (!proj.n || moderate(wx * (1.0 - proj.gamma) * sec.EA * sec.etaA));
      continue;
    }
    const Vec8 hE = expand(s1, r1d);
    const Vec8 hK = (expand(s1, rotCW(r2d)) - expand(s2, rotCW(r1d)) - 2.0 * K * hE - 2.0 * Kdot * gE -
                     2.0 * epsdot * gK) *
                    iJ2;
    const double bd = cb * Kdot * iJ2;
    Kq->noalias() += ca * gE * hE.transpose() + cb * gK * hK.transpose() -
                     (2.0 * bd) * (gE * gK.transpose() + gK * gE.transpose());
    const double projRate = proj.n ? wx * (1.0 - proj.gamma) * sec.EA * sec.etaA * proj.rate(q.xi) : 0.0;
    P.noalias() += (ca * epsdot + projRate - 2.0 * bd * K) * s1 * s1.transpose();
    Q.noalias() += bd * (s1 * s2.transpose() - s2 * s1.transpose());
  }
  // The projected axial strain rate: fd = c sum_j alphadot_j g_j, dfd/dedot = c sum_j g_j g_j^T,
  // dfd/de = c sum_j (g_j h_j^T + alphadot_j H_j) (the H_j part is in P above).
  for (int j = 0; j < proj.n; ++j) {
    fl += (cproj * proj.alphaDot[j]) * proj.grad[j];
    power += cproj * proj.alphaDot[j] * proj.alphaDot[j];
    if (Dv) Dv->noalias() += cproj * proj.grad[j] * proj.grad[j].transpose();
    if (atRest) restExact = restExact && moderate(cproj) && moderate(proj.grad[j]);
    else if (Kq) Kq->noalias() += cproj * proj.grad[j] * proj.gradDot[j].transpose();
  }
  // Before fd is written (it may alias e or edot).
  if (atRest && !restExact) return dampingForceImpl(sec, l, e, edot, fd, Kq, Dv, false);
  fd = fl;
  if (Kq && !atRest) addKronecker(P, Q, *Kq);
  return power;
}

} // namespace

double dampingForce(const Section &sec, double l, const Vec8 &e, const Vec8 &edot, Vec8 &fd, Mat8 *Kq, Mat8 *Dv)
{
  return dampingForceImpl(sec, l, e, edot, fd, Kq, Dv, true);
}

bool stiffnessAndDampingAtRest(const Section &sec, double l, const Vec8 &e, const Vec8 &edot, Mat8 &Kt, Mat8 &Kq,
                               Mat8 &Dv)
{
  if (!allZero(edot)) return false;
  // internalForce's tangent and dampingForce's matrices in one loop over the
  // points: r', r'', the projection, 1/|r'|^2, K and the gradients g_e =
  // dEps, g_K = dK are the same expressions on the same values in both, so
  // they are formed once; every accumulator (Kt, P, Q of the stiffness; Dv)
  // receives the terms of its own kernel in its order. Not formed: the
  // forces and the power (not asked for), and Kq, zero at rest under
  // dampingForce's checks, which are made here on the same factors.
  const QuadRule &g = quadRule(sec.axialIntegration);
  const ShapeTable &shapes = shapeTable(g, l);
  Vec2 slopes[kGaussPoints + kReducedAxialPoints], curvatures[kGaussPoints + kReducedAxialPoints];
  slopesAtPoints(g, shapes, e, slopes, curvatures);
  // With edot: alpha and the gradients as without it (internalForce's call),
  // and the rates that dampingForce's call adds.
  const AxialProjection proj = projectAxialStrain(sec, l, shapes, e, &edot, true,
                                                  sec.axialIntegration == AxialIntegration::Assumed ? slopes : nullptr);
  const double EAproj = (1.0 - proj.gamma) * sec.EA;
  const double cproj = (1.0 - proj.gamma) * sec.EA * sec.etaA * l;
  Eigen::Matrix4d P, Q;
  P.setZero(), Q.setZero();
  Kt.setZero();
  Kq.setZero();
  Dv.setZero();
  bool restExact = true;
  for (int p = 0; p < g.size; ++p) {
    const QuadPoint &q = g.points[p];
    const Eigen::Vector4d &s1 = shapes.s1[p], &s2 = shapes.s2[p];
    const Vec2 &r1 = slopes[p], &r2 = curvatures[p];
    const double wx = q.w * l;
    const double J2 = r1.squaredNorm(), iJ2 = 1.0 / J2;
    const double K = cross(r1, r2) * iJ2;
    // Stiffness (internalForce).
    const double EA = q.axial * proj.gamma * sec.EA, EI = q.bending * sec.EI;
    const double eps = 0.5 * (J2 - 1.0);
    const double N = EA * eps + (proj.n ? EAproj * proj.strain(q.xi) : 0.0);
    const double a = N - 2.0 * EI * K * K * iJ2, b = EI * K * iJ2;
    const Vec8 dEps = expand(s1, r1);
    const Vec8 dK = (expand(s1, rotCW(r2)) - expand(s2, rotCW(r1)) - 2.0 * K * dEps) * iJ2;
    Eigen::Matrix<double, 8, 2> G;
    G << dEps, dK;
    Eigen::Matrix2d Mw;
    Mw << wx * EA, -2.0 * wx * b, -2.0 * wx * b, wx * EI;
    Kt.noalias() += G * Mw * G.transpose();
    P.noalias() += (wx * a) * s1 * s1.transpose();
    Q.noalias() += (wx * b) * (s1 * s2.transpose() - s2 * s1.transpose());
    // Damping (dampingForce): g_e = dEps, g_K = dK.
    const double ca = wx * proj.gamma * sec.EA * sec.etaA * q.axial, cb = wx * sec.EI * sec.etaB * q.bending;
    Dv.noalias() += ca * dEps * dEps.transpose() + cb * dK * dK.transpose();
    restExact = restExact && moderate(ca) && moderate(cb) && moderate(iJ2) && moderate(K) && moderate(r1) &&
                moderate(r2) && moderate(s1) && moderate(s2) && moderate(dEps) && moderate(dK) &&
                (!proj.n || moderate(wx * (1.0 - proj.gamma) * sec.EA * sec.etaA));
  }
  addKronecker(P, Q, Kt);
  for (int j = 0; j < proj.n; ++j) Kt.noalias() += (EAproj * l) * proj.grad[j] * proj.grad[j].transpose();
  for (int j = 0; j < proj.n; ++j) {
    Dv.noalias() += cproj * proj.grad[j] * proj.grad[j].transpose();
    restExact = restExact && moderate(cproj) && moderate(proj.grad[j]);
  }
  return restExact;
}

double dampingForceSummed(const Section &sec, double l, const Vec8 &e, const Vec8 &edot, Vec8 &fd, Mat8 *Kq, Mat8 *Dv)
{
  return dampingForceImpl(sec, l, e, edot, fd, Kq, Dv, false);
}

namespace {

// internalAndDampingForce on T = double (one element) or ForceLanes (four
// elements of one beam, one per lane), like internalForceOnlyN: the
// operations of internalForce(.., nullptr) and dampingForce(.., nullptr,
// nullptr) on scalars (r', r'' and their rates as x and y parts, not
// 2-vectors), each force accumulated in the order of its own function, so
// that both forces and the power are bit for bit theirs (tests
// AncfElement.InternalAndDampingForceIsBitIdentical and
// AncfElement.BatchedDampedForceIsBitIdentical). Shared: the shape values,
// r', r'', 1/|r'|^2, K and the axial projection; of the projection only
// alpha, its rate and d alpha/de (the damping force's projected part) are
// formed, not the d alphadot/de that projectAxialStrain also builds.
// e, edot, f, fd hold 8 values of T; f and fd are written after the last
// read of e and edot (they may alias them). Returns the dissipated power.
template <typename T, int NP>
T internalAndDampingForceN(const Section &sec, double l, const QuadRule &g, const ShapeTable &shapes, const T *e,
                           const T *edot, T *f, T *fd)
{
  // slopesAndRates at every point: r', r'' and their rates, sums from zero in k's order.
  T r1x[NP], r1y[NP], r2x[NP], r2y[NP], d1x[NP], d1y[NP], d2x[NP], d2y[NP];
  for (int p = 0; p < NP; ++p) {
    const auto *s1 = shapeOperands(shapes.s1, shapes.s1Lanes, p, static_cast<T *>(nullptr));
    const auto *s2 = shapeOperands(shapes.s2, shapes.s2Lanes, p, static_cast<T *>(nullptr));
    T ax{}, ay{}, bx{}, by{}, cx{}, cy{}, dx{}, dy{};
    for (int k = 0; k < 4; ++k) {
      ax += s1[k] * e[2 * k], ay += s1[k] * e[2 * k + 1];
      bx += s2[k] * e[2 * k], by += s2[k] * e[2 * k + 1];
      cx += s1[k] * edot[2 * k], cy += s1[k] * edot[2 * k + 1];
      dx += s2[k] * edot[2 * k], dy += s2[k] * edot[2 * k + 1];
    }
    r1x[p] = ax, r1y[p] = ay, r2x[p] = bx, r2y[p] = by;
    d1x[p] = cx, d1y[p] = cy, d2x[p] = dx, d2y[p] = dy;
  }
  // projectAxialStrain(.., &edot, gradients = true) with the slopes above
  // (the same 5 points: Assumed uses the full rule): alpha_j, alphadot_j and
  // grad_j = sum_p w_p phi_j (s1 ⊗ r1), each from zero in p's order.
  const double gamma = assumedPointwiseWeight(sec, l);
  const bool projected = sec.axialIntegration == AxialIntegration::Assumed && gamma < 1.0;
  T alpha[kAssumedTerms] = {}, alphaDot[kAssumedTerms] = {}, grad[kAssumedTerms][8] = {};
  if (projected)
    for (int p = 0; p < kGaussPoints; ++p) {
      const auto *s1 = shapeOperands(shapes.s1, shapes.s1Lanes, p, static_cast<T *>(nullptr));
      const T eps = 0.5 * ((r1x[p] * r1x[p] + r1y[p] * r1y[p]) - 1.0);
      const T epsRate = r1x[p] * d1x[p] + r1y[p] * d1y[p];
      for (int j = 0; j < kAssumedTerms; ++j) {
        const double wp = shapes.projectionWeight[j][p];
        alpha[j] += wp * eps;
        alphaDot[j] += wp * epsRate;
        for (int k = 0; k < 4; ++k) {
          grad[j][2 * k] += wp * (s1[k] * r1x[p]);
          grad[j][2 * k + 1] += wp * (s1[k] * r1y[p]);
        }
      }
    }
  const double EAproj = (1.0 - gamma) * sec.EA;
  const double cproj = (1.0 - gamma) * sec.EA * sec.etaA * l;
  T fl[8] = {}, fdl[8] = {}, power{};
  for (int p = 0; p < NP; ++p) {
    const QuadPoint &q = g.points[p];
    const auto *s1 = shapeOperands(shapes.s1, shapes.s1Lanes, p, static_cast<T *>(nullptr));
    const auto *s2 = shapeOperands(shapes.s2, shapes.s2Lanes, p, static_cast<T *>(nullptr));
    const double wx = q.w * l;
    // Internal force (internalForceOnlyN's operations).
    const double EA = q.axial * gamma * sec.EA, EI = q.bending * sec.EI;
    T K, iJ2;
    addElasticForceAt(wx, EA, EI, EAproj, projected, alpha[0], alpha[1], shapes.legendre1[p], r1x[p], r1y[p], r2x[p],
                      r2y[p], s1, s2, fl, &K, &iJ2);
    // Damping force (dampingForceImpl's force-only branch).
    const double ca = wx * gamma * sec.EA * sec.etaA * q.axial, cb = wx * sec.EI * sec.etaB * q.bending;
    const T epsdot = r1x[p] * d1x[p] + r1y[p] * d1y[p];
    const T Kdot = ((d1x[p] * r2y[p] - d1y[p] * r2x[p]) + (r1x[p] * d2y[p] - r1y[p] * d2x[p]) - 2.0 * K * epsdot) * iJ2;
    power += ca * epsdot * epsdot + cb * Kdot * Kdot;
    const T bK = cb * Kdot * iJ2, ce = ca * epsdot, K2 = 2.0 * K;
    const T u1x = ce * r1x[p] + bK * (r2y[p] - K2 * r1x[p]), u1y = ce * r1y[p] + bK * (-r2x[p] - K2 * r1y[p]);
    const T u2x = bK * r1y[p], u2y = bK * -r1x[p];
    for (int k = 0; k < 4; ++k) {
      fdl[2 * k] += s1[k] * u1x - s2[k] * u2x;
      fdl[2 * k + 1] += s1[k] * u1y - s2[k] * u2y;
    }
  }
  // The projected axial strain rate: fd += c alphadot_j grad_j.
  if (projected)
    for (int j = 0; j < kAssumedTerms; ++j) {
      const T c = cproj * alphaDot[j];
      for (int i = 0; i < 8; ++i) fdl[i] += c * grad[j][i];
      power += cproj * alphaDot[j] * alphaDot[j];
    }
  for (int i = 0; i < 8; ++i) f[i] = fl[i], fd[i] = fdl[i];
  return power;
}

template <typename T>
T internalAndDampingForceT(const Section &sec, double l, const T *e, const T *edot, T *f, T *fd)
{
  const QuadRule &g = quadRule(sec.axialIntegration);
  const ShapeTable &shapes = shapeTable(g, l);
  if (g.size == kGaussPoints) return internalAndDampingForceN<T, kGaussPoints>(sec, l, g, shapes, e, edot, f, fd);
  return internalAndDampingForceN<T, kGaussPoints + kReducedAxialPoints>(sec, l, g, shapes, e, edot, f, fd);
}

} // namespace

double internalAndDampingForce(const Section &sec, double l, const Vec8 &e, const Vec8 &edot, Vec8 &f, Vec8 &fd)
{
  return internalAndDampingForceT<double>(sec, l, e.data(), edot.data(), f.data(), fd.data());
}

ForceLanes internalAndDampingForceLanes(const Section &sec, double l, const ForceLanes e[8], const ForceLanes edot[8],
                                        ForceLanes f[8], ForceLanes fd[8])
{
  return internalAndDampingForceT<ForceLanes>(sec, l, e, edot, f, fd);
}

void internalAndDampingForceBatch(const Section &sec, double l, const double *const e[kForceBatch],
                                  const double *const edot[kForceBatch], double *const f[kForceBatch],
                                  double *const fd[kForceBatch], double power[kForceBatch])
{
  ForceLanes el[8], vl[8], fl[8], fdl[8];
  lanes::gatherLanes(e, 0, el), lanes::gatherLanes(e, 4, el + 4);
  lanes::gatherLanes(edot, 0, vl), lanes::gatherLanes(edot, 4, vl + 4);
  const ForceLanes p = internalAndDampingForceLanes(sec, l, el, vl, fl, fdl);
  lanes::scatterLanes(fl, f, 0), lanes::scatterLanes(fl + 4, f, 4);
  lanes::scatterLanes(fdl, fd, 0), lanes::scatterLanes(fdl + 4, fd, 4);
  lanes::store(power, p);
}

Vec8 straightElement(const Vec2 &p0, const Vec2 &dir, double l)
{
  Vec8 e;
  e << p0, dir, p0 + l * dir, dir;
  return e;
}

} // namespace boomdyn::ancf
