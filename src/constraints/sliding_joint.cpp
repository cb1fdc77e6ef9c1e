#include "boomdyn/sliding_joint.hpp"

#include "boomdyn/slack_track.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cstring>

namespace boomdyn {

static_assert(SlidingJoint::relocationHysteresis == kSlackRelocationHysteresis, "one relocation band for all sliding joints");

namespace {

using Mat2 = Eigen::Matrix2d;
using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;

// Up to 8 + 8 coordinates of the two bodies and the slack coordinate: the
// work arrays of a row evaluation live on the stack (a residual evaluates
// every joint, and heap temporaries were a visible part of its cost).
constexpr int kMaxCoordinates = 17;
using ZJacobian = Eigen::Matrix<double, 4, Eigen::Dynamic, Eigen::ColMajor, 4, kMaxCoordinates>;

// g(d, t) = (A t) . d / |t| and its gradient, and with gzz its Hessian, in z = (d, t).
void rowFunction(const Mat2 &A, const Vec2 &d, const Vec2 &t, double &g, Vec4 &gz, Mat4 *gzzOut)
{
  const double J = t.norm(), J3 = J * J * J, J5 = J3 * J * J;
  const Vec2 At = A * t, Atd = A.transpose() * d;
  const double c = At.dot(d);
  g = c / J;
  gz.head<2>() = At / J;
  gz.tail<2>() = Atd / J - c * t / J3;
  if (!gzzOut) return; // the residual needs C and C_q only
  Mat4 &gzz = *gzzOut;
  gzz.setZero();
  const Mat2 ddt = A / J - At * t.transpose() / J3; // d/dt of (A t / J)
  gzz.block<2, 2>(0, 2) = ddt;
  gzz.block<2, 2>(2, 0) = ddt.transpose();
  gzz.block<2, 2>(2, 2) = -(Atd * t.transpose() + t * Atd.transpose()) / J3 - c * Mat2::Identity() / J3 +
                          3.0 * c * t * t.transpose() / J5;
}

} // namespace

SlidingJoint::SlidingJoint(std::string name, const Body &track, const Body &slider, double sliderPoint,
                           PetscInt slackIndex, double s0, bool normalRow)
  : name_(std::move(name)), track_(&track), slider_(&slider), xP_(sliderPoint), slack_(slackIndex),
    trackLoc_(track.locate(s0)), sliderLoc_(slider.locate(sliderPoint)), normalRow_(normalRow)
{
}

void SlidingJoint::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.assign(trackLoc_.dofs.begin(), trackLoc_.dofs.begin() + trackLoc_.count);
  dofs.insert(dofs.end(), sliderLoc_.dofs.begin(), sliderLoc_.dofs.begin() + sliderLoc_.count);
  dofs.push_back(slack_);
}

bool SlidingJoint::relocate(double s)
{
  double sc;
  if (!slackLeavesElement(s, trackLoc_.begin, trackLoc_.end, track_->length(), &sc)) return false;
  const CenterlineLocation loc = track_->locate(sc);
  if (loc.element == trackLoc_.element) return false;
  trackLoc_ = loc;
  rowsValid_ = false;
  return true;
}

void SlidingJoint::evaluate(double, const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  if (normalRow_) {
    evaluateRows(q, v, w, out);
    return;
  }
  // Both rows into the joint's own work arrays, then row d (out keeps its
  // one-row sizes between calls: no heap traffic per residual).
  const double w2[2] = {w ? w[0] : 0.0, 0.0};
  const ConstraintEval *both = &scratch_;
  if (!v && !w) both = &rowsAt(q); // a residual: the pad asks for the same rows
  else evaluateRows(q, v, w ? w2 : nullptr, scratch_);
  const ConstraintEval &rows = *both;
  const Eigen::Index n = rows.Cq.cols();
  out.C.resize(1);
  out.C[0] = rows.C[0];
  out.Cq.resize(1, n);
  out.Cq.row(0) = rows.Cq.row(0);
  if (v) {
    out.gamma.resize(1);
    out.gamma[0] = rows.gamma[0];
  }
  if (w) out.H = rows.H;
}

void SlidingJoint::normalGap(const double *q, double &d, Eigen::VectorXd &dq, Eigen::MatrixXd &dqq) const
{
  const double w[2] = {0.0, 1.0};
  ConstraintEval &ev = scratch_;
  evaluateRows(q, nullptr, w, ev);
  d = -ev.C[1];
  dq = -ev.Cq.row(1).transpose();
  dqq = -ev.H;
}

void SlidingJoint::normalGap(const double *q, double &d, Eigen::VectorXd &dq) const
{
  const ConstraintEval &ev = rowsAt(q);
  d = -ev.C[1];
  dq = -ev.Cq.row(1).transpose();
}

const ConstraintEval &SlidingJoint::rowsAt(const double *q) const
{
  const int n = trackLoc_.count + sliderLoc_.count + 1;
  // Bitwise the same q (memcmp: -0 and +0 differ, a NaN never matches).
  if (rowsValid_ && std::memcmp(q, rowsQ_, sizeof(double) * n) == 0) return rows_;
  evaluateRows(q, nullptr, nullptr, rows_);
  std::copy(q, q + n, rowsQ_);
  rowsValid_ = true;
  return rows_;
}

void SlidingJoint::evaluateRows(const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  const int ni = trackLoc_.count, nj = sliderLoc_.count, n = ni + nj + 1, is = n - 1;
  const double s = q[is];
  CenterlineSample ti, sj;
  track_->sample(trackLoc_, s, q, ti);
  slider_->sample(sliderLoc_, xP_, q + ni, sj);
  const Vec2 d = ti.r[0] - sj.r[0], t = ti.r[1];

  // z = (d, t) and z_q (4 x n): d = r_i(s) - r_j, t = r_i'(s).
  ZJacobian zq = ZJacobian::Zero(4, n);
  zq.block(0, 0, 2, ni) = ti.r_q[0].leftCols(ni);
  zq.block(0, ni, 2, nj) = -sj.r_q[0].leftCols(nj);
  zq.block(0, is, 2, 1) = ti.r[1];
  zq.block(2, 0, 2, ni) = ti.r_q[1].leftCols(ni);
  zq.block(2, is, 2, 1) = ti.r[2];

  Mat2 W; // rotation by +90 degrees: j = W i
  W << 0, -1, 1, 0;
  const Mat2 A[2] = {Mat2::Identity(), W};
  double g[2];
  Vec4 gz[2];
  Mat4 gzz[2];
  for (int k = 0; k < 2; ++k) rowFunction(A[k], d, t, g[k], gz[k], v || w ? &gzz[k] : nullptr);
  out.C.resize(2);
  out.Cq.resize(2, n);
  for (int k = 0; k < 2; ++k) {
    out.C[k] = g[k];
    out.Cq.row(k) = gz[k].transpose() * zq;
  }

  // Second derivatives of z with respect to q, contracted with a 4-vector u:
  // only the terms with s survive for linear centerlines,
  //   d_ss = r_i'', d_s,e_i = S_i', t_ss = r_i''', t_s,e_i = S_i''.
  auto zHessian = [&](const Vec4 &u, Eigen::MatrixXd &Hz) {
    Hz.setZero(n, n);
    const Vec2 ud = u.head<2>(), ut = u.tail<2>();
    Hz(is, is) = ud.dot(ti.r[2]) + ut.dot(ti.r[3]);
    const Eigen::RowVectorXd cross = ud.transpose() * ti.r_q[1].leftCols(ni) + ut.transpose() * ti.r_q[2].leftCols(ni);
    Hz.block(is, 0, 1, ni) = cross;
    Hz.block(0, is, ni, 1) = cross.transpose();
    Eigen::Matrix<double, 8, 8> H8;
    if (!ti.linear) {
      track_->curvatureTerm(trackLoc_, s, q, 0, ud, H8);
      Hz.topLeftCorner(ni, ni) += H8.topLeftCorner(ni, ni);
      track_->curvatureTerm(trackLoc_, s, q, 1, ut, H8);
      Hz.topLeftCorner(ni, ni) += H8.topLeftCorner(ni, ni);
    }
    if (!sj.linear) {
      slider_->curvatureTerm(sliderLoc_, xP_, q + ni, 0, -ud, H8);
      Hz.block(ni, ni, nj, nj) += H8.topLeftCorner(nj, nj);
    }
  };

  Eigen::MatrixXd Hz;
  if (v) {
    const Eigen::Map<const Eigen::VectorXd> vv(v, n);
    const Vec4 zdot = zq * vv;
    out.gamma.resize(2);
    for (int k = 0; k < 2; ++k) {
      zHessian(gz[k], Hz);
      out.gamma[k] = vv.dot(Hz * vv) + zdot.dot(gzz[k] * zdot);
    }
  }
  if (w) {
    const Vec4 u = w[0] * gz[0] + w[1] * gz[1];
    const Mat4 G = w[0] * gzz[0] + w[1] * gzz[1];
    zHessian(u, Hz);
    out.H = zq.transpose() * G * zq + Hz;
  }
}

} // namespace boomdyn
