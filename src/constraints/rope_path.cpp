#include "boomdyn/rope_path.hpp"

#include <stdexcept>

namespace boomdyn {

RopePath::RopePath(std::vector<Point> points) : points_(std::move(points))
{
  if (points_.size() < 2) throw std::logic_error("a rope path needs at least two points");
  for (const Point &p : points_) {
    loc_.push_back(p.body->locate(p.s));
    offset_.push_back(n_);
    n_ += loc_.back().count;
  }
}

void RopePath::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.clear();
  for (const auto &loc : loc_) dofs.insert(dofs.end(), loc.dofs.begin(), loc.dofs.begin() + loc.count);
}

double RopePath::length(const double *q) const
{
  double l = 0;
  Vec2 previous = Vec2::Zero();
  for (std::size_t k = 0; k < points_.size(); ++k) {
    CenterlineSample s;
    points_[k].body->sample(loc_[k], points_[k].s, q + offset_[k], s);
    if (k > 0) l += (previous - s.r[0]).norm();
    previous = s.r[0];
  }
  return l;
}

std::vector<double> RopePath::segmentLengths(const double *q) const
{
  std::vector<double> lengths;
  Vec2 previous = Vec2::Zero();
  for (std::size_t k = 0; k < points_.size(); ++k) {
    CenterlineSample s;
    points_[k].body->sample(loc_[k], points_[k].s, q + offset_[k], s);
    if (k > 0) lengths.push_back((previous - s.r[0]).norm());
    previous = s.r[0];
  }
  return lengths;
}

int RopePath::shortSegment(const double *q) const
{
  const std::vector<double> l = segmentLengths(q);
  double total = 0;
  for (double lj : l) total += lj;
  // 1e-9 of the span: the segment's stiffness T (I - u u^T) / l_j would be
  // 1e9 times that of the rope's other segments, and its direction round-off.
  for (std::size_t j = 0; j < l.size(); ++j)
    if (!(l[j] > 1e-9 * total)) return static_cast<int>(j);
  return -1;
}

void RopePath::geometry(const double *q, Geometry &g) const
{
  // Every array is reused from the previous call (same sizes, no heap
  // traffic per residual); the arithmetic is that of a fresh Geometry.
  const std::size_t N = points_.size();
  std::vector<CenterlineSample> &s = scratch_.samples;
  std::vector<Eigen::MatrixXd> &rq = scratch_.rq; // d r_k / dq
  s.resize(N), rq.resize(N);
  for (std::size_t k = 0; k < N; ++k) {
    points_[k].body->sample(loc_[k], points_[k].s, q + offset_[k], s[k]);
    rq[k].setZero(2, n_);
    rq[k].block(0, offset_[k], 2, loc_[k].count) = s[k].r_q[0].leftCols(loc_[k].count);
  }
  g.segment.resize(N - 1), g.dq.resize(N - 1), g.projector.resize(N - 1);
  g.length = 0;
  g.lq.setZero(n_);
  g.dldr.assign(N, Vec2::Zero());
  g.linear.clear();
  for (const CenterlineSample &p : s) g.linear.push_back(p.linear);
  Eigen::RowVectorXd &segmentGradient = scratch_.segmentGradient;
  for (std::size_t j = 0; j + 1 < N; ++j) {
    // Segment d = r_j - r_{j+1}: l_j = |d|, dl_j/dq = u^T d_q, d2 l_j/dq2 = d_q^T (I - u u^T)/l_j d_q.
    const Vec2 d = s[j].r[0] - s[j + 1].r[0];
    const double lj = d.norm();
    const Vec2 u = d / lj;
    g.dq[j] = rq[j] - rq[j + 1];
    g.segment[j] = lj;
    g.projector[j] = (Eigen::Matrix2d::Identity() - u * u.transpose()) / lj;
    g.length += lj;
    segmentGradient.noalias() = u.transpose() * g.dq[j]; // then added, as C_q always was
    g.lq += segmentGradient;
    g.dldr[j] += u, g.dldr[j + 1] -= u;
  }
}

const RopePath::Geometry &RopePath::geometry(const double *q) const
{
  geometry(q, scratch_.geometry);
  return scratch_.geometry;
}

Eigen::MatrixXd RopePath::segmentHessian(const Geometry &g)
{
  Eigen::MatrixXd H = g.dq[0].transpose() * g.projector[0] * g.dq[0];
  for (std::size_t j = 1; j < g.dq.size(); ++j) H += g.dq[j].transpose() * g.projector[j] * g.dq[j];
  return H;
}

double RopePath::segmentRate2(const Geometry &g, const Eigen::VectorXd &v, bool negate)
{
  double sum = 0;
  for (std::size_t j = 0; j < g.dq.size(); ++j) {
    const Vec2 rate = g.dq[j] * v;
    const double term = rate.dot(g.projector[j] * rate);
    sum = negate ? sum - term : sum + term;
  }
  return sum;
}

void RopePath::addCurvature(const double *q, const Geometry &g, double w, Eigen::MatrixXd &H) const
{
  for (std::size_t k = 0; k < points_.size(); ++k) {
    if (g.linear[k]) continue;
    Eigen::Matrix<double, 8, 8> H8;
    points_[k].body->curvatureTerm(loc_[k], points_[k].s, q + offset_[k], 0, w * g.dldr[k], H8);
    const int c = loc_[k].count;
    H.block(offset_[k], offset_[k], c, c) += H8.topLeftCorner(c, c);
  }
}

double RopePath::evaluate(const double *q, Eigen::RowVectorXd &lq, double w, Eigen::MatrixXd *H) const
{
  const Geometry &g = geometry(q);
  lq = g.lq;
  if (H) {
    *H += w * segmentHessian(g);
    addCurvature(q, g, w, *H);
  }
  return g.length;
}

} // namespace boomdyn
