// The geometry of a rope over pulleys (docs/model.md §2.2 and §7): material
// points P_0 (first end), P_1 ... P_{N-2} (pulleys) and P_{N-1} (far end) on
// bodies, joined by straight segments; the spanned length is
//     l(q) = sum_j |r_j - r_{j+1}|.
// Pulleys are points: no radius, no wrap angle, no friction; the rope slides
// over them freely. One helper for the inextensible rope (rope.cpp) and the
// elastic tension-only rope (elastic_rope.cpp): l, its gradient l_q and its
// Hessian l_qq = sum_j d_jq^T (I - u_j u_j^T)/l_j d_jq + sum_k curvature of
// nonlinear centerlines weighted by dl/dr_k.
#pragma once

#include "boomdyn/body.hpp"

#include <Eigen/Dense>

#include <vector>

namespace boomdyn {

class RopePath {
public:
  struct Point {
    const Body *body;
    double s;
  };
  explicit RopePath(std::vector<Point> points); // at least 2 points
  const std::vector<Point> &points() const { return points_; }
  // Coordinates of every point, point after point (values in this order).
  void coordinates(std::vector<PetscInt> &dofs) const;
  int numCoordinates() const { return n_; }
  // Spanned length l(q).
  double length(const double *q) const;
  // The lengths l_j of the segments at q, first to last. A segment of zero
  // length has no direction (u_j = d_j / l_j): the rope types refuse one
  // at t = 0 (shortSegment()).
  std::vector<double> segmentLengths(const double *q) const;
  // The first segment shorter than 1e-9 of the spanned length (or of zero
  // length, or not finite) at q, or -1: its points are j and j + 1.
  int shortSegment(const double *q) const;
  // The path at q: per segment j (P_j to P_{j+1}) its length l_j, d_jq =
  // d(r_j - r_{j+1})/dq and (I - u_j u_j^T)/l_j; the total l and l_q.
  struct Geometry {
    std::vector<double> segment;
    std::vector<Eigen::MatrixXd> dq;
    std::vector<Eigen::Matrix2d> projector;
    double length = 0;
    Eigen::RowVectorXd lq;
    std::vector<Vec2> dldr; // dl / dr_k per point
    std::vector<char> linear; // per point: its centerline is linear in q (no curvature term)
  };
  void geometry(const double *q, Geometry &g) const;
  // The same into this path's own Geometry, valid until the next call (the
  // residual's path: no arrays allocated per evaluation).
  const Geometry &geometry(const double *q) const;
  // The segments' part of l_qq: sum_j d_jq^T (I - u_j u_j^T)/l_j d_jq.
  static Eigen::MatrixXd segmentHessian(const Geometry &g);
  // The segments' part of v^T l_qq v: sum_j |d_j'|^2_(projector), negated when `negate`
  // (accumulated term by term in that sign).
  static double segmentRate2(const Geometry &g, const Eigen::VectorXd &v, bool negate);
  // H += the curvature of nonlinear centerlines (rigid bodies): sum_k (w dl/dr_k) . d2 r_k/dq2.
  void addCurvature(const double *q, const Geometry &g, double w, Eigen::MatrixXd &H) const;
  // l(q), l_q and, when H is not null, H += w * l_qq (n x n).
  double evaluate(const double *q, Eigen::RowVectorXd &lq, double w = 0, Eigen::MatrixXd *H = nullptr) const;

private:
  std::vector<Point> points_;
  std::vector<CenterlineLocation> loc_;
  std::vector<int> offset_;
  int n_ = 0;
  // Work arrays of geometry(), kept between calls so that a residual
  // evaluation allocates nothing (one path per rope; not thread-safe, as
  // the assembly is not threaded).
  struct Scratch {
    std::vector<CenterlineSample> samples;
    std::vector<Eigen::MatrixXd> rq;
    Eigen::RowVectorXd segmentGradient;
    Geometry geometry;
  };
  mutable Scratch scratch_;
};

} // namespace boomdyn
