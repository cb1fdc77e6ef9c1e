// Spatial sliding joint (type `sliding_joint` of spatial scenes, docs/model.md
// §9.5): a point of the slider body (a rigid sleeve, or a material point of
// another beam) moves along the deformable axis of a spatial beam, the
// track. As in the planar joint (sliding_joint.hpp) the contact point is the
// slack coordinate s, the arc length on the track, an unknown without mass
// that moves across element boundaries. With d = r_track(s) - r_slider(x_P)
// and (d1, d2, d3) the track's section triad at s:
//     position (3 rows):           d_k(s) . d = 0,  k = 1, 2, 3
//     tangent alignment (2 rows):  d1(s) . v2 = 0,  d1(s) . v3 = 0
//     roll (1 row):                d2(s) . v3 = 0
// where v2, v3 are vectors fixed in the slider's section triad at x_P, equal
// at the start to the track's d2, d3 at s0 (the sleeve's axes across the
// track). Row 1 defines s, rows 2 and 3 hold the slider point on the axis;
// alignment keeps the sleeve's axis along the tangent, roll ties the
// sleeve's rotation about the axis to the twisted section of the track.
//
// Because the rows are projections on the track's section triad, their
// multipliers are the reactions on the slider in that frame (when the rows
// hold): the force lambda_k along d_k, the moment lambda_A2 about d3, -lambda_A3
// about d2 and the torque lambda_R about the axis d1 (docs/model.md §9.5).
//
// Pads (docs/model.md §9.5): a lateral position row (k = 2 or 3) may be
// left out (rigid[k-2] false) and the direction given to a compliant pad
// (PadContact through SpatialPadGap) acting on the gap
//     g_k = -C_k = d_k(s) . (r_slider - r_track(s)),
// the slider point's offset from the axis along d_k.
//
// Like the planar joint, the coordinates the rows touch depend on which track
// element holds s: relocate() moves the joint to that element (with the same
// hysteresis band, slack_track.hpp) and the caller rebuilds the pattern.
#pragma once

#include "boomdyn/constraint.hpp"
#include "boomdyn/pad_gap.hpp"
#include "boomdyn/spatial_ancf_beam.hpp"
#include "boomdyn/spatial_body.hpp"

#include <array>
#include <memory>
#include <vector>

namespace boomdyn {

namespace spatial_beam {
struct SlackFrame;
}

class SpatialSlidingJoint : public Constraint {
public:
  // v2, v3: the sleeve's vectors across the track in the slider's section
  // axes at sliderPoint (used by the alignment and roll rows).
  SpatialSlidingJoint(std::string name, const SpatialAncfBeam &track, const SpatialBody &slider, double sliderPoint,
                      PetscInt slackIndex, double s0, bool align, bool roll, const Vec3 &v2, const Vec3 &v3,
                      std::array<bool, 2> rigid = {true, true});
  std::string name() const override { return name_; }
  int numRows() const override { return static_cast<int>(rows_.size()); }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override;
  bool dependsOnTime() const override { return false; }
  const char *rowUnit(int row) const override { return row < 3 ? "m" : "rad"; }

  bool aligned() const { return align_; }
  // True when the position row along d_k (k = 2, 3) is a constraint (else a pad's).
  bool rigidAlong(int k) const { return rigid_[k - 2]; }
  // The row index of the first rotation row (alignment, then roll).
  int firstRotationRow() const { return 1 + (rigid_[0] ? 1 : 0) + (rigid_[1] ? 1 : 0); }
  // The gap g_k = -C_k along d_k (k = 2, 3), its gradient and (if dqq is
  // not null) Hessian over coordinates().
  void lateralGap(int k, const double *q, double &g, Eigen::VectorXd &gq, Eigen::MatrixXd *gqq) const;
  bool rolled() const { return roll_; }
  PetscInt slackIndex() const { return slack_; }
  const SpatialAncfBeam &track() const { return *track_; }
  const SpatialBody &slider() const { return *slider_; }
  const SpatialLocation &trackLocation() const { return trackLoc_; }
  // Moves the joint to the element of the track that holds s (hysteresis as
  // the planar joint's); true if it changed.
  bool relocate(double s);
  void setTrackLocation(double s) { trackLoc_ = track_->locate(s); }
  bool onTrack(double s) const { return s >= 0.0 && s <= track_->length(); }

private:
  std::string name_;
  const SpatialAncfBeam *track_;
  const SpatialBody *slider_;
  double xP_;
  PetscInt slack_;
  SpatialLocation trackLoc_, sliderLoc_;
  bool align_, roll_;
  std::array<bool, 2> rigid_;
  // Each row is f(y) + sign a(y) . b(q_b) (docs/model.md §9.5): a the
  // track's director d_{director+1} at s; b the slider point (position
  // rows, f = a . r_track) or the slider-fixed vector with components c in
  // its section axes (rotation rows, f = 0).
  struct Row {
    int director;
    bool position;
    Vec3 c;
    double sign;
  };
  std::vector<Row> rows_;
  struct RowParts;
  // One row's value and derivatives in y = (element, s) and q_b at q.
  void rowAt(const Row &r, const spatial_beam::SlackFrame &F, const double *qb, const SpatialSample &pb, bool second,
             RowParts &p) const;
};

// The gap along d_k of a spatial sliding joint as a pad's gap (PadContact).
class SpatialPadGap : public PadGap {
public:
  SpatialPadGap(std::shared_ptr<const SpatialSlidingJoint> joint, int direction)
    : joint_(std::move(joint)), k_(direction)
  {
  }
  std::string padName() const override { return joint_->name() + ".pad_" + std::to_string(k_); }
  void coordinates(std::vector<PetscInt> &dofs) const override { joint_->coordinates(dofs); }
  void normalGap(const double *q, double &d, Eigen::VectorXd &dq, Eigen::MatrixXd &dqq) const override
  {
    joint_->lateralGap(k_, q, d, dq, &dqq);
  }
  void normalGap(const double *q, double &d, Eigen::VectorXd &dq) const override
  {
    joint_->lateralGap(k_, q, d, dq, nullptr);
  }
  int direction() const { return k_; }
  const SpatialSlidingJoint &joint() const { return *joint_; }

private:
  std::shared_ptr<const SpatialSlidingJoint> joint_;
  int k_;
};

} // namespace boomdyn
