// Compliant slide pad with clearance at a sliding joint (docs/model.md §2.1,
// pad variant, §7 and §9.5): the joint keeps its tangential row (which
// defines the slack coordinate s) as a constraint; across the track the
// slider point moves freely within the clearance +-g and meets a one-sided
// elastic pad on either side. With d the signed gap (PadGap::normalGap: the
// planar joint's normal gap, d > 0 on the left of the track's direction, or
// a spatial joint's gap along the section direction d2 or d3) the force on
// the slider along that direction n is
//     f = -k (d - g) - c ddot   for d >  g   (side +1)
//     f = -k (d + g) - c ddot   for d < -g   (side -1)
//     f = 0                     otherwise     (side  0, lift-off)
// and the generalized force is Q = f d_q (equal and opposite on the track at
// s). Its Jacobian is exact: -dQ/dx = cQ [(k d_q + c d_qq v) d_q^T - f d_qq]
// + cV c d_q d_q^T in contact (a static tangent inside the clearance is
// regularized, see evaluate()). The damping force is not clipped at zero: a
// pad that separates fast may pull briefly (linear Kelvin-Voigt pad).
#pragma once

#include "boomdyn/pad_gap.hpp"
#include "boomdyn/work_item.hpp"

#include <memory>

namespace boomdyn {

struct PadSpec {
  double stiffness = 0; // k_pad, N/m (> 0)
  double clearance = 0; // g, m (>= 0): free play on either side
  double damping = 0;   // c_pad, N s/m (>= 0), only while in contact
};

// The pad's state at one (q, v): what the output reports.
struct PadState {
  double gap = 0;         // d, m
  double force = 0;       // f along n on the slider, N (elastic + damping)
  double penetration = 0; // |d| - g in contact (> 0), else the negative free play |d| - g (<= 0)
  int side = 0;           // +1 / -1: in contact on that side of the clearance, 0: free
};

class PadContact : public WorkItem {
public:
  ModeEnergyKind modeEnergyKind() const override { return ModeEnergyKind::Contact; } // mode labels
  PadContact(std::shared_ptr<const PadGap> gap, const PadSpec &spec);
  std::string name() const override { return joint_->padName(); }
  void coordinates(std::vector<PetscInt> &dofs) const override { joint_->coordinates(dofs); }
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  // The gap and its derivatives once for the passes at the same q.
  void evaluatePencil(const PencilPass (&pass)[kPencilPasses], int n, double *scratch) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &parts) const override;

  // State at q, v over coordinates() (v may be null: no damping part).
  PadState state(const double *q, const double *v) const;
  // The pad force f and its derivatives f_q, f_v over coordinates().
  void force(const double *q, const double *v, double &f, Eigen::VectorXd &fq, Eigen::VectorXd &fv) const;
  const PadSpec &spec() const { return spec_; }
  // The side of contact; without clearance the pad is always in contact (bilateral).
  static int sideOf(double d, double clearance)
  {
    if (clearance == 0) return d >= 0 ? 1 : -1;
    return d > clearance ? 1 : (d < -clearance ? -1 : 0);
  }
  // Static tangent only, in the clearance: stiffness gapStiffness * k_pad (evaluate()).
  static constexpr double gapStiffness = 1e-4;

private:
  // evaluate() after the gap d, d_q (dq_) and, with J, d_qq (dqq_) at in.q.
  void evaluateAtGap(const AssemblyContext &ctx, const ItemValues &in, double d, double *residual, double *J) const;

  std::shared_ptr<const PadGap> joint_; // the gap d
  PadSpec spec_;
  // d_q and d_qq of the last evaluation, kept so that their arrays are not
  // allocated per residual.
  mutable Eigen::VectorXd dq_;
  mutable Eigen::MatrixXd dqq_;
};

} // namespace boomdyn
