// Sliding joint (docs/model.md §2.1): a slider point P, fixed on body j at
// material coordinate x_P, moves along the centerline of the track body i.
// The slack coordinate s (material coordinate of the contact point on the
// track) is an unknown without mass. Two rows:
//     C_d = i(s) . (r_i(s) - r_j(x_P)) = 0      (defines s)
//     C_n = j(s) . (r_i(s) - r_j(x_P)) = 0      (no normal gap)
// with i = r_i'/|r_i'| and j = (-i_y, i_x). Row n's multiplier is the normal
// contact force in N (when the rows are not scaled).
//
// The rows are f(z(q)) with z = (d, t), d = r_i(s) - r_j(x_P), t = r_i'(s):
// the Jacobian, the multiplier-weighted Hessian and the acceleration term
// follow from the first and second derivatives of f and of z.
//
// The coordinates the rows touch depend on which track element holds s:
// relocate() moves the joint to the element that holds a new s; the caller
// rebuilds the assembly pattern when it returns true.
//
// A joint with a compliant pad (docs/model.md §2.1, pad variant) keeps only
// row d as a constraint (numRows() == 1): the normal direction is left to a
// PadContact force item, which reads the signed gap d = -C_n and its
// derivatives through normalGap().
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/constraint.hpp"
#include "boomdyn/pad_gap.hpp"

namespace boomdyn {

class SlidingJoint : public Constraint, public PadGap {
public:
  SlidingJoint(std::string name, const Body &track, const Body &slider, double sliderPoint, PetscInt slackIndex,
               double s0, bool normalRow = true);
  std::string name() const override { return name_; }
  int numRows() const override { return normalRow_ ? 2 : 1; }
  // False when a pad takes the normal direction (only row d is a constraint).
  bool hasNormalRow() const { return normalRow_; }
  std::string padName() const override { return name_ + ".pad"; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override;
  bool dependsOnTime() const override { return false; }
  // The signed normal gap d = j(s) . (r_j(x_P) - r_i(s)) = -C_n of the slider
  // point (positive on the left of the track's direction), its gradient d_q
  // and Hessian d_qq over coordinates() (row n of evaluate() with w = (0, 1)).
  void normalGap(const double *q, double &d, Eigen::VectorXd &dq, Eigen::MatrixXd &dqq) const override;
  // The same d and d_q without the Hessian (residuals, outputs, energies:
  // the Hessian's curvature terms are most of the cost).
  void normalGap(const double *q, double &d, Eigen::VectorXd &dq) const override;

  PetscInt slackIndex() const { return slack_; }
  const Body &track() const { return *track_; }
  const Body &slider() const { return *slider_; }
  double sliderPoint() const { return xP_; }
  const CenterlineLocation &trackLocation() const { return trackLoc_; }
  const CenterlineLocation &sliderLocation() const { return sliderLoc_; }
  // Moves the joint to the element of the track that holds s; true if it
  // changed. A contact point stays with its element until it is more than
  // a small fraction of the element length past its end: the centerline is
  // C1 across nodes, so evaluating the element a little outside its span is
  // accurate, and without this band a joint resting on a node would switch
  // elements (and the solver its sparsity pattern) at every vibration.
  bool relocate(double s);
  static constexpr double relocationHysteresis = 1e-3; // of the element length
  // Puts the contact point on the element that holds s, unconditionally (restarts).
  void setTrackLocation(double s)
  {
    trackLoc_ = track_->locate(s);
    rowsValid_ = false;
  }
  // True when s lies in [0, track length].
  bool onTrack(double s) const { return s >= 0.0 && s <= track_->length(); }

private:
  // Both rows; w (two weights) may be null.
  void evaluateRows(const double *q, const double *v, const double *w, ConstraintEval &out) const;

  std::string name_;
  const Body *track_, *slider_;
  double xP_;
  PetscInt slack_;
  CenterlineLocation trackLoc_, sliderLoc_;
  bool normalRow_;
  // Both rows for normalGap() and the one-row evaluate(), kept between
  // calls so that their arrays are not allocated per residual.
  mutable ConstraintEval scratch_;
  // C and C_q of both rows (no v, no w) at the last q asked for: a padded
  // joint's constraint row and its pad ask for the same q in every residual
  // and after every step (the same values, computed once).
  const ConstraintEval &rowsAt(const double *q) const;
  static constexpr int kMaxRowCoordinates = 17; // 8 + 8 + the slack coordinate
  mutable ConstraintEval rows_;
  mutable double rowsQ_[kMaxRowCoordinates] = {};
  mutable bool rowsValid_ = false;
};

} // namespace boomdyn
