#include "boomdyn/spatial_sliding_joint.hpp"

#include "boomdyn/slack_track.hpp"
#include "boomdyn/spatial_beam_slack_frame.hpp"

namespace boomdyn {

namespace sb = spatial_beam;

// The row's parts in y (15) and q_b (nb).
struct SpatialSlidingJoint::RowParts {
  double C = 0;
  sb::Vec15 Cy;
  Eigen::VectorXd Cb;
  sb::Mat15 Hyy;                               // when wanted
  Eigen::Matrix<double, sb::kSlackVariables, Eigen::Dynamic> Hyb; // 15 x nb
  Eigen::MatrixXd Hbb;                          // nb x nb
};

SpatialSlidingJoint::SpatialSlidingJoint(std::string name, const SpatialAncfBeam &track, const SpatialBody &slider,
                                         double sliderPoint, PetscInt slackIndex, double s0, bool align, bool roll,
                                         const Vec3 &v2, const Vec3 &v3, std::array<bool, 2> rigid)
  : name_(std::move(name)), track_(&track), slider_(&slider), xP_(sliderPoint), slack_(slackIndex),
    trackLoc_(track.locate(s0)), sliderLoc_(slider.locate(sliderPoint)), align_(align), roll_(roll), rigid_(rigid)
{
  for (int k = 0; k < 3; ++k)
    if (k == 0 || rigid_[k - 1]) rows_.push_back({k, true, Vec3::Zero(), -1.0});
  if (align_) rows_.push_back({0, false, v2, 1.0}), rows_.push_back({0, false, v3, 1.0});
  if (roll_) rows_.push_back({1, false, v3, 1.0});
}

void SpatialSlidingJoint::coordinates(std::vector<PetscInt> &dofs) const
{
  dofs.assign(trackLoc_.dofs.begin(), trackLoc_.dofs.begin() + trackLoc_.count);
  dofs.insert(dofs.end(), sliderLoc_.dofs.begin(), sliderLoc_.dofs.begin() + sliderLoc_.count);
  dofs.push_back(slack_);
}

bool SpatialSlidingJoint::relocate(double s)
{
  double sc;
  if (!slackLeavesElement(s, trackLoc_.begin, trackLoc_.end, track_->length(), &sc)) return false;
  const SpatialLocation loc = track_->locate(sc);
  if (loc.element == trackLoc_.element) return false;
  trackLoc_ = loc;
  return true;
}

void SpatialSlidingJoint::evaluate(double, const double *q, const double *v, const double *w, ConstraintEval &out) const
{
  constexpr int nt = sb::kCoordinates;
  const int nb = sliderLoc_.count, n = nt + nb + 1, is = n - 1, m = numRows();
  const double *qb = q + nt;
  const double s = q[is];
  const sb::SlackFrame F =
      sb::slackFrame(track_->geometry(trackLoc_.element), Eigen::Map<const sb::Vec14>(q), (s - trackLoc_.begin) / track_->elementLength());
  SpatialSample pb;
  slider_->sample(sliderLoc_, xP_, qb, pb);

  const bool second = v || w;
  // y-space values of the velocities: the element's, then s's.
  sb::Vec15 vy;
  Eigen::VectorXd vb;
  if (v) {
    vy.head<nt>() = Eigen::Map<const sb::Vec14>(v);
    vy[sb::kSlackIndex] = v[is];
    vb = Eigen::Map<const Eigen::VectorXd>(v + nt, nb);
  }
  out.C.resize(m);
  out.Cq.setZero(m, n);
  if (v) out.gamma.setZero(m);
  if (w) out.H.setZero(n, n);
  RowParts p;
  for (int row = 0; row < m; ++row) {
    rowAt(rows_[row], F, qb, pb, second, p);
    out.C[row] = p.C;
    out.Cq.block(row, 0, 1, nt) = p.Cy.head<nt>().transpose();
    out.Cq(row, is) = p.Cy[sb::kSlackIndex];
    out.Cq.block(row, nt, 1, nb) = p.Cb.transpose();
    if (!second) continue;
    if (v) out.gamma[row] = vy.dot(p.Hyy * vy) + 2.0 * vy.dot(p.Hyb * vb) + vb.dot(p.Hbb * vb);
    if (w && w[row] != 0.0) {
      const double wr = w[row];
      // y = (element, s) -> local (0..nt-1, is); q_b -> nt..nt+nb-1.
      out.H.topLeftCorner(nt, nt) += wr * p.Hyy.topLeftCorner<nt, nt>();
      out.H.block(0, is, nt, 1) += wr * p.Hyy.block<nt, 1>(0, sb::kSlackIndex);
      out.H.block(is, 0, 1, nt) += wr * p.Hyy.block<1, nt>(sb::kSlackIndex, 0);
      out.H(is, is) += wr * p.Hyy(sb::kSlackIndex, sb::kSlackIndex);
      out.H.block(0, nt, nt, nb) += wr * p.Hyb.topRows(nt);
      out.H.block(nt, 0, nb, nt) += wr * p.Hyb.topRows(nt).transpose();
      out.H.block(is, nt, 1, nb) += wr * p.Hyb.row(sb::kSlackIndex);
      out.H.block(nt, is, nb, 1) += wr * p.Hyb.row(sb::kSlackIndex).transpose();
      out.H.block(nt, nt, nb, nb) += wr * p.Hbb;
    }
  }
}

void SpatialSlidingJoint::rowAt(const Row &r, const sb::SlackFrame &F, const double *qb, const SpatialSample &pb,
                                bool second, RowParts &p) const
{
  constexpr int ny = sb::kSlackVariables;
  const int nb = sliderLoc_.count;
  Vec3 a, b;
  Eigen::Matrix<double, 3, ny> ay;
  for (int c = 0; c < 3; ++c) {
    a[c] = F.d[r.director][c].value;
    ay.row(c) = F.d[r.director][c].grad.transpose();
  }
  Eigen::MatrixXd bq;
  if (r.position) {
    b = pb.r;
    bq = pb.r_q.leftCols(nb);
  } else {
    b = pb.triad * r.c;
    bq = r.c[0] * pb.d_q[0].leftCols(nb) + r.c[1] * pb.d_q[1].leftCols(nb) + r.c[2] * pb.d_q[2].leftCols(nb);
  }
  const sb::SlackScalar *f = r.position ? &F.rd[r.director] : nullptr;
  p.C = (f ? f->value : 0.0) + r.sign * a.dot(b);
  p.Cy = r.sign * ay.transpose() * b;
  if (f) p.Cy += f->grad;
  p.Cb = r.sign * bq.transpose() * a;
  if (!second) return;
  // Second derivatives: in y from the jets, across y and q_b from the
  // product, in q_b from the slider body's curvature terms.
  SpatialHessian h;
  p.Hyy = f ? f->hess : sb::Mat15::Zero();
  for (int c = 0; c < 3; ++c) p.Hyy += (r.sign * b[c]) * F.d[r.director][c].hess;
  p.Hyb = r.sign * ay.transpose() * bq;
  p.Hbb.setZero(nb, nb);
  if (r.position) {
    slider_->curvatureTerm(sliderLoc_, xP_, qb, SpatialField::Position, a, h);
    p.Hbb += r.sign * h.topLeftCorner(nb, nb);
  } else {
    for (int k = 0; k < 3; ++k) {
      if (r.c[k] == 0.0) continue;
      slider_->curvatureTerm(sliderLoc_, xP_, qb, static_cast<SpatialField>(k + 1), a, h);
      p.Hbb += (r.sign * r.c[k]) * h.topLeftCorner(nb, nb);
    }
  }
}

void SpatialSlidingJoint::lateralGap(int k, const double *q, double &g, Eigen::VectorXd &gq,
                                     Eigen::MatrixXd *gqq) const
{
  constexpr int nt = sb::kCoordinates;
  const int nb = sliderLoc_.count, n = nt + nb + 1, is = n - 1;
  const double *qb = q + nt;
  const sb::SlackFrame F =
      sb::slackFrame(track_->geometry(trackLoc_.element), Eigen::Map<const sb::Vec14>(q), (q[is] - trackLoc_.begin) / track_->elementLength());
  SpatialSample pb;
  slider_->sample(sliderLoc_, xP_, qb, pb);
  RowParts p;
  rowAt({k - 1, true, Vec3::Zero(), -1.0}, F, qb, pb, gqq != nullptr, p);
  // g = -C_k.
  g = -p.C;
  gq.resize(n);
  gq.head(nt) = -p.Cy.head<nt>();
  gq.segment(nt, nb) = -p.Cb;
  gq[is] = -p.Cy[sb::kSlackIndex];
  if (!gqq) return;
  Eigen::MatrixXd &H = *gqq;
  H.setZero(n, n);
  H.topLeftCorner(nt, nt) = -p.Hyy.topLeftCorner<nt, nt>();
  H.block(0, is, nt, 1) = -p.Hyy.block<nt, 1>(0, sb::kSlackIndex);
  H.block(is, 0, 1, nt) = -p.Hyy.block<1, nt>(sb::kSlackIndex, 0);
  H(is, is) = -p.Hyy(sb::kSlackIndex, sb::kSlackIndex);
  H.block(0, nt, nt, nb) = -p.Hyb.topRows(nt);
  H.block(nt, 0, nb, nt) = -p.Hyb.topRows(nt).transpose();
  H.block(is, nt, 1, nb) = -p.Hyb.row(sb::kSlackIndex);
  H.block(nt, is, nb, 1) = -p.Hyb.row(sb::kSlackIndex).transpose();
  H.block(nt, nt, nb, nb) = -p.Hbb;
}


} // namespace boomdyn
