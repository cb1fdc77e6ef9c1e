#include "boomdyn/spatial_beam_kinematics.hpp"

#include "spatial_beam_strains.hpp"
#include "boomdyn/ancf_element.hpp"

namespace boomdyn::spatial_beam {

using detail::Jet;
using detail::V3;

namespace {

Vec3 toVec(const V3<double> &v) { return Vec3(v.x, v.y, v.z); }
V3<double> fromVec(const Vec3 &v) { return {v.x(), v.y(), v.z()}; }

// The section state at xi on jets: what sectionFrame and its Hessian read.
struct JetSection {
  V3<Jet> r;
  detail::SectionState<Jet> s;
};

JetSection jetSection(const Geometry &geo, const Vec14 &e, double xi)
{
  Jet x[kCoordinates];
  detail::seed(e, x);
  const detail::NodeData<Jet> n = detail::nodeData(geo, x);
  JetSection js;
  js.r = detail::interpolate(x, ancf::shapeValues(xi, geo.l, 0));
  js.s = detail::sectionState(n, x, xi, geo.l, ancf::shapeValues(xi, geo.l, 1), ancf::shapeValues(xi, geo.l, 2));
  return js;
}

const V3<Jet> &director(const JetSection &js, int i) { return i == 0 ? js.s.t : i == 1 ? js.s.d2 : js.s.d3; }

} // namespace

Strains strainsAt(const Geometry &geo, const Vec14 &e, double xi)
{
  const detail::NodeData<double> n = detail::nodeData(geo, e.data());
  const detail::SectionState<double> s = detail::sectionState(
      n, e.data(), xi, geo.l, ancf::shapeValues(xi, geo.l, 1), ancf::shapeValues(xi, geo.l, 2));
  return {s.axial, s.torsion, s.curvature2, s.curvature3};
}

SectionFrame sectionFrame(const Geometry &geo, const Vec14 &e, double xi)
{
  const JetSection js = jetSection(geo, e, xi);
  SectionFrame f;
  const Jet *r[3] = {&js.r.x, &js.r.y, &js.r.z};
  for (int c = 0; c < 3; ++c) {
    f.r[c] = r[c]->v;
    f.rGrad.row(c) = r[c]->g.transpose();
  }
  for (int i = 0; i < 3; ++i) {
    const V3<Jet> &d = director(js, i);
    const Jet *dc[3] = {&d.x, &d.y, &d.z};
    for (int c = 0; c < 3; ++c) {
      f.d(c, i) = dc[c]->v;
      f.dGrad[i].row(c) = dc[c]->g.transpose();
    }
  }
  return f;
}

Mat14 sectionFrameHessian(const Geometry &geo, const Vec14 &e, double xi, int i, const Vec3 &w)
{
  const JetSection js = jetSection(geo, e, xi);
  const V3<Jet> &d = director(js, i);
  return w.x() * d.x.h + w.y() * d.y.h + w.z() * d.z.h;
}

void sectionMomentForce(const Geometry &geo, const Vec14 &e, double xi, const Vec3 &M, Vec14 &Q, Mat14 *dQ)
{
  const JetSection js = jetSection(geo, e, xi);
  Mat3 Mx; // [M]x v = M x v
  Mx << 0, -M.z(), M.y(), M.z(), 0, -M.x(), -M.y(), M.x(), 0;
  Q.setZero();
  if (dQ) dQ->setZero();
  for (int i = 0; i < 3; ++i) {
    const V3<Jet> &d = director(js, i);
    Mat3x14 grad;
    grad.row(0) = d.x.g.transpose(), grad.row(1) = d.y.g.transpose(), grad.row(2) = d.z.g.transpose();
    const Vec3 w = M.cross(Vec3(d.x.v, d.y.v, d.z.v));
    Q += 0.5 * grad.transpose() * w;
    if (dQ) {
      // d/de of (dd_i/de)^T (M x d_i): the director's second derivative
      // contracted with M x d_i, and the rate of M x d_i itself.
      dQ->noalias() += 0.5 * (w.x() * d.x.h + w.y() * d.y.h + w.z() * d.z.h);
      dQ->noalias() += 0.5 * grad.transpose() * Mx * grad;
    }
  }
}

Mat3 nodeTriad(const NodeFrame &ref, const Vec3 &slope, double theta)
{
  const V3<double> t = detail::unit(fromVec(slope));
  V3<double> b2, b3;
  detail::zeroTwistAxes(ref, t, b2, b3);
  const double c = std::cos(theta), s = std::sin(theta);
  Mat3 d;
  d.col(0) = toVec(t);
  d.col(1) = c * toVec(b2) + s * toVec(b3);
  d.col(2) = c * toVec(b3) - s * toVec(b2);
  return d;
}

double twistFor(const NodeFrame &ref, const Vec3 &slope, const Vec3 &d2)
{
  const V3<double> t = detail::unit(fromVec(slope));
  V3<double> b2, b3;
  detail::zeroTwistAxes(ref, t, b2, b3);
  return std::atan2(d2.dot(toVec(b3)), d2.dot(toVec(b2)));
}

NodeFrame rebasedNodeFrame(const NodeFrame &ref, const Vec3 &slope)
{
  const V3<double> t = detail::unit(fromVec(slope));
  V3<double> b2, b3;
  detail::zeroTwistAxes(ref, t, b2, b3);
  return {toVec(t), toVec(b2)};
}

Vec14 straightElement(const Vec3 &p0, const Mat3 &triad, double l)
{
  Vec14 e = Vec14::Zero();
  const Vec3 t = triad.col(0);
  e.segment<3>(positionIndex(0)) = p0;
  e.segment<3>(slopeIndex(0)) = t;
  e.segment<3>(positionIndex(1)) = p0 + l * t;
  e.segment<3>(slopeIndex(1)) = t;
  return e;
}

Geometry straightGeometry(const Mat3 &triad, double l)
{
  Geometry g;
  g.l = l;
  g.node[0] = g.node[1] = NodeFrame{triad.col(0), triad.col(1)};
  return g;
}

} // namespace boomdyn::spatial_beam
