#include "boomdyn/ancf_beam.hpp"

#include <algorithm>
#include <cmath>

namespace boomdyn {

AncfBeam::AncfBeam(std::string name, double length, int elements, const ancf::Section &section, Vec2 origin,
                   double angle, PetscInt first)
  : Body(std::move(name), length, first), elements_(elements), section_(section), origin_(origin),
    direction_(std::cos(angle), std::sin(angle))
{
}

void AncfBeam::initialCoordinates(double *q) const
{
  for (int k = 0; k <= elements_; ++k) {
    const Vec2 p = origin_ + (k * elementLength()) * direction_;
    q[4 * k + 0] = p.x();
    q[4 * k + 1] = p.y();
    q[4 * k + 2] = direction_.x();
    q[4 * k + 3] = direction_.y();
  }
}

CenterlineLocation AncfBeam::locate(double s) const
{
  const double l = elementLength();
  // A point exactly on a node belongs to the element that starts there (the
  // last node to the last element); both give the same r, r' by C1 continuity.
  int el = static_cast<int>(std::floor(s / l));
  el = std::clamp(el, 0, elements_ - 1);
  CenterlineLocation loc;
  loc.count = 8;
  loc.element = el;
  loc.s = s;
  loc.xi = (s - el * l) / l;
  loc.begin = el * l;
  loc.end = (el + 1) * l;
  for (int k = 0; k < 8; ++k) loc.dofs[k] = elementDof(el, k);
  return loc;
}

void AncfBeam::sample(const CenterlineLocation &loc, double s, const double *values, CenterlineSample &out) const
{
  const double l = elementLength();
  const double xi = (s - loc.element * l) / l;
  // r^(d) = S_d e with S_d = ancf::shapeMatrix(xi, l, d) = [s_0 I, s_1 I,
  // s_2 I, s_3 I]: formed here from the four shape values, and the product
  // summed over its nonzero columns only, in the order of Eigen's 2x8 product
  // (column after column; the skipped terms are exact zeros), so r is
  // bit-identical to S_d * e at a third of the cost. Sliding joints and
  // ropes sample at every residual.
  const double *e = values;
  for (int d = 0; d < 4; ++d) {
    const Eigen::Vector4d sv = ancf::shapeValues(xi, l, d);
    ancf::Mat28 &S = out.r_q[d];
    S.setZero();
    for (int k = 0; k < 4; ++k) S(0, 2 * k) = sv[k], S(1, 2 * k + 1) = sv[k];
    out.r[d] = Vec2(((sv[0] * e[0] + sv[1] * e[2]) + sv[2] * e[4]) + sv[3] * e[6],
                    ((sv[0] * e[1] + sv[1] * e[3]) + sv[2] * e[5]) + sv[3] * e[7]);
  }
  out.linear = true;
}

} // namespace boomdyn
