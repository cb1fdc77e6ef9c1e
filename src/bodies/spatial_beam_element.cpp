#include "boomdyn/spatial_beam_element.hpp"

#include "spatial_beam_quadrature.hpp"
#include "spatial_beam_strains.hpp"

#include <array>
#include <cmath>
#include <type_traits>

namespace boomdyn::spatial_beam {

using detail::V3;
using detail::legendre01;
using detail::rule3;
using detail::rule5;
using detail::GaussRule;

namespace {

// The element's energy as a sum of quadratic terms U = 1/2 sum_k c_k s_k^2:
// each strain at each quadrature point (or, for the Assumed axial strain,
// each coefficient of its projection) with its weight c_k = (weight) l C
// and retardation time eta_k. T: double (energy) or a jet over the reduced
// variables w (force; with Hessians, the tangent).
template <typename T>
struct QuadraticTerms {
  static constexpr int kMax = 4 * kGaussPoints + kReducedAxialPoints + ancf::kAssumedTerms;
  std::array<T, kMax> s;
  std::array<double, kMax> c, eta;
  int n = 0;
  void add(const T &strain, double weight, double etaK)
  {
    s[n] = strain, c[n] = weight, eta[n] = etaK;
    ++n;
  }
};

template <typename T>
T axialStrainAt(const T *e, const Eigen::Vector4d &s1)
{
  const V3<T> r1 = detail::interpolate(e, s1);
  return 0.5 * (detail::dot(r1, r1) - 1.0);
}

template <typename T>
void elementTerms(const Section &sec, const Geometry &geo, const T *e, QuadraticTerms<T> &q)
{
  const double l = geo.l;
  const StrainLaw law = strainLaw(sec);
  const GaussRule &g = rule5();
  const detail::NodeData<T> nodes = detail::nodeData(geo, e);
  const double gamma = assumedPointwiseWeight(sec, l);
  const bool projected = sec.axialIntegration == AxialIntegration::Assumed && gamma < 1.0;
  const bool axialOnRule5 = sec.axialIntegration != AxialIntegration::Reduced;
  T alpha[ancf::kAssumedTerms] = {T(0.0), T(0.0)};
  for (int p = 0; p < g.n; ++p) {
    const double xi = g.xi[p], wl = g.w[p] * l;
    const detail::SectionState<T> s =
        detail::sectionState(nodes, e, xi, l, ancf::shapeValues(xi, l, 1), ancf::shapeValues(xi, l, 2));
    q.add(s.torsion, wl * law.stiffness[1], law.eta[1]);
    q.add(s.curvature2, wl * law.stiffness[2], law.eta[2]);
    q.add(s.curvature3, wl * law.stiffness[3], law.eta[3]);
    if (axialOnRule5) q.add(s.axial, gamma * wl * law.stiffness[0], law.eta[0]);
    if (projected)
      for (int j = 0; j < ancf::kAssumedTerms; ++j) alpha[j] += (g.w[p] * legendre01(j, xi)) * s.axial;
  }
  if (projected)
    for (int j = 0; j < ancf::kAssumedTerms; ++j) q.add(alpha[j], (1.0 - gamma) * l * law.stiffness[0], law.eta[0]);
  if (!axialOnRule5) {
    const GaussRule &r = rule3();
    for (int p = 0; p < r.n; ++p)
      q.add(axialStrainAt(e, ancf::shapeValues(r.xi[p], l, 1)), r.w[p] * l * law.stiffness[0], law.eta[0]);
  }
}

// The terms on jets over the reduced variables w (spatial_beam_strains.hpp).
template <typename J>
void jetTerms(const Section &sec, const Geometry &geo, const Vec14 &e, QuadraticTerms<J> &q)
{
  J x[kCoordinates];
  detail::seedReduced(e, x);
  elementTerms(sec, geo, x, q);
}

using detail::kReduced;
using detail::ReducedJet;
using detail::ReducedJet1;
using VecW = Eigen::Matrix<double, kReduced, 1>;
using MatW = Eigen::Matrix<double, kReduced, kReduced>;

} // namespace

Mat14 massMatrix(const Section &sec, double l)
{
  // ∫_0^1 s_a s_b dxi of the cubic Hermite functions (/420), per direction.
  Eigen::Matrix4d m;
  m << 156, 22 * l, 54, -13 * l,
       22 * l, 4 * l * l, 13 * l, -3 * l * l,
       54, 13 * l, 156, -22 * l,
       -13 * l, -3 * l * l, -22 * l, 4 * l * l;
  m *= sec.rhoA * l / 420.0;
  Mat14 M = Mat14::Zero();
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int d = 0; d < 3; ++d) M(detail::kShapeOffset[a] + d, detail::kShapeOffset[b] + d) = m(a, b);
  // Linear interpolation of the twist: rhoIp l [1/3 1/6; 1/6 1/3].
  const double c = sec.rhoIp * l / 6.0;
  M(twistIndex(0), twistIndex(0)) = M(twistIndex(1), twistIndex(1)) = 2.0 * c;
  M(twistIndex(0), twistIndex(1)) = M(twistIndex(1), twistIndex(0)) = c;
  return M;
}

Vec14 gravityForce(const Section &sec, double l, const Vec3 &g)
{
  // ∫_0^1 s_k dxi = (1/2, l/12, 1/2, -l/12).
  const double integral[4] = {0.5, l / 12.0, 0.5, -l / 12.0};
  Vec14 f = Vec14::Zero();
  for (int k = 0; k < 4; ++k) f.segment<3>(detail::kShapeOffset[k]) = sec.rhoA * l * integral[k] * g;
  return f;
}

double strainEnergy(const Section &sec, const Geometry &geo, const Vec14 &e)
{
  QuadraticTerms<double> q;
  elementTerms(sec, geo, e.data(), q);
  double U = 0;
  for (int k = 0; k < q.n; ++k) U += q.c[k] * q.s[k] * q.s[k];
  return 0.5 * U;
}

namespace {

// fd, the power and (if asked) Kq and Dv from the terms, summed over w and
// mapped to e once; Kq needs the Hessians (ReducedJet).
template <typename J>
double dampingFromTerms(const QuadraticTerms<J> &q, const Vec14 &edot, Vec14 &fd, Mat14 *Kq, Mat14 *Dv)
{
  const detail::ReducedMap &P = detail::reducedMap();
  const VecW wdot = P.transpose() * edot; // rates of w (P^T: r_1 - r_0 gets rdot_1 - rdot_0)
  VecW out = VecW::Zero();
  MatW Kqw = MatW::Zero(), Dvw = MatW::Zero();
  double power = 0;
  for (int k = 0; k < q.n; ++k) {
    const double ce = q.c[k] * q.eta[k];
    if (ce == 0) continue;
    const J &s = q.s[k];
    const double rate = s.g.dot(wdot);
    out += (ce * rate) * s.g;
    power += ce * rate * rate;
    if constexpr (std::is_same_v<J, ReducedJet>)
      if (Kq) {
        Kqw.noalias() += ce * s.g * (s.h * wdot).transpose();
        Kqw.noalias() += (ce * rate) * s.h;
      }
    if (Dv) Dvw.noalias() += ce * s.g * s.g.transpose();
  }
  fd.noalias() = P * out;
  if (Kq) Kq->noalias() = P * Kqw * P.transpose();
  if (Dv) Dv->noalias() = P * Dvw * P.transpose();
  return power;
}

} // namespace

namespace {

// f = sum_k c_k s_k ds_k/de and, for jets with Hessians and K != nullptr,
// K = sum_k c_k (ds_k/de ds_k/de^T + s_k d^2 s_k/de^2).
// Sums over w, mapped to e once: f = P f_w, K = P K_w P^T.
template <typename J>
void elasticFromTerms(const QuadraticTerms<J> &q, Vec14 &f, Mat14 *K)
{
  const detail::ReducedMap &P = detail::reducedMap();
  VecW fw = VecW::Zero();
  MatW Kw = MatW::Zero();
  for (int k = 0; k < q.n; ++k) {
    const J &s = q.s[k];
    fw += (q.c[k] * s.v) * s.g;
    if constexpr (std::is_same_v<J, ReducedJet>)
      if (K) {
        Kw.noalias() += q.c[k] * s.g * s.g.transpose();
        Kw.noalias() += (q.c[k] * s.v) * s.h;
      }
  }
  f.noalias() = P * fw;
  if (K) K->noalias() = P * Kw * P.transpose();
}

} // namespace

namespace reference {

void internalForce(const Section &sec, const Geometry &geo, const Vec14 &e, Vec14 &f, Mat14 *K)
{
  if (!K) { // the residual: gradients only
    QuadraticTerms<ReducedJet1> q;
    jetTerms(sec, geo, e, q);
    elasticFromTerms(q, f, nullptr);
    return;
  }
  QuadraticTerms<ReducedJet> q;
  jetTerms(sec, geo, e, q);
  elasticFromTerms(q, f, K);
}

double internalAndDampingForce(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 &edot, Vec14 &f,
                               Mat14 *K, Vec14 &fd, Mat14 *Kq, Mat14 *Dv)
{
  if (!K && !Kq) {
    QuadraticTerms<ReducedJet1> q;
    jetTerms(sec, geo, e, q);
    elasticFromTerms(q, f, nullptr);
    return dampingFromTerms(q, edot, fd, nullptr, Dv);
  }
  QuadraticTerms<ReducedJet> q;
  jetTerms(sec, geo, e, q);
  elasticFromTerms(q, f, K);
  return dampingFromTerms(q, edot, fd, Kq, Dv);
}

double dampingForce(const Section &sec, const Geometry &geo, const Vec14 &e, const Vec14 &edot, Vec14 &fd, Mat14 *Kq,
                    Mat14 *Dv)
{
  if (!Kq) { // fd and Dv need the strains' gradients only
    QuadraticTerms<ReducedJet1> q;
    jetTerms(sec, geo, e, q);
    return dampingFromTerms(q, edot, fd, nullptr, Dv);
  }
  QuadraticTerms<ReducedJet> q;
  jetTerms(sec, geo, e, q);
  return dampingFromTerms(q, edot, fd, Kq, Dv);
}

} // namespace reference

} // namespace boomdyn::spatial_beam
