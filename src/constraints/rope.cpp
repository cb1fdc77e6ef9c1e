#include "boomdyn/rope.hpp"

namespace boomdyn {

Rope::Rope(std::string name, Point p, Point q, Point r, double length)
  : name_(std::move(name)), pts_{p, q, r}, length_(length)
{
  for (int k = 0; k < 3; ++k) loc_[k] = pts_[k].body->locate(pts_[k].s);
}

void Rope::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.clear();
  for (const auto &loc : loc_) dofs.insert(dofs.end(), loc.dofs.begin(), loc.dofs.begin() + loc.count);
}

double Rope::spannedLength(const double *q) const
{
  CenterlineSample s[3];
  int offset = 0;
  for (int k = 0; k < 3; ++k) {
    pts_[k].body->sample(loc_[k], pts_[k].s, q + offset, s[k]);
    offset += loc_[k].count;
  }
  return (s[0].r[0] - s[1].r[0]).norm() + (s[1].r[0] - s[2].r[0]).norm();
}

void Rope::evaluate(double, const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  CenterlineSample s[3];
  int offset[3], n = 0;
  for (int k = 0; k < 3; ++k) {
    offset[k] = n;
    pts_[k].body->sample(loc_[k], pts_[k].s, q + n, s[k]);
    n += loc_[k].count;
  }
  // Segment vectors a = r_P - r_Q, b = r_Q - r_R and their Jacobians.
  Eigen::MatrixXd Pq = Eigen::MatrixXd::Zero(2, n), Qq = Pq, Rq = Pq;
  Pq.block(0, offset[0], 2, loc_[0].count) = s[0].r_q[0].leftCols(loc_[0].count);
  Qq.block(0, offset[1], 2, loc_[1].count) = s[1].r_q[0].leftCols(loc_[1].count);
  Rq.block(0, offset[2], 2, loc_[2].count) = s[2].r_q[0].leftCols(loc_[2].count);
  const Vec2 a = s[0].r[0] - s[1].r[0], b = s[1].r[0] - s[2].r[0];
  const double la = a.norm(), lb = b.norm();
  const Vec2 ua = a / la, ub = b / lb;
  const Eigen::MatrixXd aq = Pq - Qq, bq = Qq - Rq;
  out.C.setConstant(1, length_ - la - lb);
  out.Cq = -(ua.transpose() * aq + ub.transpose() * bq);
  // Second derivatives: -(I - u u^T)/l for each segment, plus the curvature
  // of nonlinear centerlines (rigid bodies) weighted by -(d|a|/dr) etc.
  const Eigen::Matrix2d Pa = (Eigen::Matrix2d::Identity() - ua * ua.transpose()) / la;
  const Eigen::Matrix2d Pb = (Eigen::Matrix2d::Identity() - ub * ub.transpose()) / lb;
  // Weight of each point's position in C: dC/dr_P = -ua, dC/dr_Q = ua - ub, dC/dr_R = ub.
  const Vec2 weight[3] = {-ua, ua - ub, ub};
  auto curvature = [&](double scale, Eigen::MatrixXd &H) {
    Eigen::Matrix<double, 8, 8> H8;
    for (int k = 0; k < 3; ++k) {
      if (s[k].linear) continue;
      pts_[k].body->curvatureTerm(loc_[k], pts_[k].s, q + offset[k], 0, scale * weight[k], H8);
      H.block(offset[k], offset[k], loc_[k].count, loc_[k].count) += H8.topLeftCorner(loc_[k].count, loc_[k].count);
    }
  };
  if (v) {
    const Eigen::Map<const Eigen::VectorXd> vv(v, n);
    const Vec2 adot = aq * vv, bdot = bq * vv;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
    curvature(1.0, H);
    out.gamma.setConstant(1, -adot.dot(Pa * adot) - bdot.dot(Pb * bdot) + vv.dot(H * vv));
  }
  if (w) {
    out.H = -w[0] * (aq.transpose() * Pa * aq + bq.transpose() * Pb * bq);
    curvature(w[0], out.H);
  }
}

} // namespace boomdyn
