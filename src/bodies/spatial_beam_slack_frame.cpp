#include "boomdyn/spatial_beam_slack_frame.hpp"

#include "spatial_beam_strains.hpp"
#include "boomdyn/ancf_element.hpp"

namespace boomdyn::spatial_beam {

namespace {

using Jet = jet::Jet2<kSlackVariables>;
using detail::V3;

// The axis derivative r^(order) = sum_k S_k^(order)(x) q_k as jets: linear
// in the element vector, its x-derivatives from the next two shape orders.
V3<Jet> axisDerivative(const Vec14 &e, double xi, double l, int order)
{
  const Eigen::Vector4d s0 = ancf::shapeValues(xi, l, order), s1 = ancf::shapeValues(xi, l, order + 1),
                        s2 = ancf::shapeValues(xi, l, order + 2);
  V3<Jet> out;
  Jet *c[3] = {&out.x, &out.y, &out.z};
  for (int d = 0; d < 3; ++d) {
    Jet &j = *c[d];
    j = Jet(0.0);
    for (int k = 0; k < 4; ++k) {
      const int o = detail::kShapeOffset[k] + d;
      j.v += s0[k] * e[o];
      j.g[o] = s0[k];
      j.g[kSlackIndex] += s1[k] * e[o];
      j.h(kSlackIndex, kSlackIndex) += s2[k] * e[o];
      j.h(kSlackIndex, o) = j.h(o, kSlackIndex) = s1[k];
    }
  }
  return out;
}

void store(const Jet &j, SlackScalar &out)
{
  out.value = j.v;
  out.grad = j.g;
  out.hess = j.h;
}

void store(const V3<Jet> &v, SlackScalar (&out)[3]) { store(v.x, out[0]), store(v.y, out[1]), store(v.z, out[2]); }

} // namespace

SlackFrame slackFrame(const Geometry &geo, const Vec14 &e, double xi)
{
  Jet x[kCoordinates];
  for (int i = 0; i < kCoordinates; ++i) x[i] = Jet::variable(e[i], i);
  const detail::NodeData<Jet> nodes = detail::nodeData(geo, x);
  const V3<Jet> r = axisDerivative(e, xi, geo.l, 0);
  Jet xiJet(xi);
  xiJet.g[kSlackIndex] = 1.0 / geo.l;
  const detail::SectionState<Jet> s =
      detail::sectionStateOf(nodes, axisDerivative(e, xi, geo.l, 1), axisDerivative(e, xi, geo.l, 2), xiJet, geo.l);
  SlackFrame f;
  store(r, f.r);
  const V3<Jet> *d[3] = {&s.t, &s.d2, &s.d3};
  for (int k = 0; k < 3; ++k) {
    store(*d[k], f.d[k]);
    store(detail::dot(*d[k], r), f.rd[k]);
  }
  return f;
}

} // namespace boomdyn::spatial_beam
