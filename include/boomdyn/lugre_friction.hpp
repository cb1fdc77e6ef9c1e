// LuGre friction at a sliding joint (docs/model.md §3) as a work item: the
// friction force F_t = (sigma0 z + sigma1 zdot) |lambda_n| + sigma2 v_r acts
// along -i on the track at the contact point and along +i on the slider, and
// the bristle state z obeys
//     zdot = v_r - sigma0 |v_r| z / g(v_r),   g = mu_c + (mu_s - mu_c) exp(-|v_r/v_s|^alpha),
// with v_r = i . (velocity of the track's material point - slider's). z is an
// unknown of the same Newton system (first-order, backward Euler in
// dynamics); its row is scaled like the mechanical rows. The Jacobian,
// including the dependence on lambda_n, s and the velocities, is exact: it is
// computed by forward-mode automatic differentiation on top of the bodies'
// exact centerline derivatives.
//
// Modes: dynamics (cZ > 0) integrate z; at acceleration level (initial
// conditions) zdot is the law's value; statics and the eigen pencil freeze z
// (its row is the identity).
//
// At a joint with a compliant pad the normal force is the pad's force f(q, v)
// (PadContact) instead of lambda_n: the item then has no multiplier row, and
// the Jacobian carries |f|'s derivatives in q and v.
#pragma once

#include "boomdyn/sliding_joint.hpp"
#include "boomdyn/work_item.hpp"

#include <cmath>
#include <memory>

namespace boomdyn {

// LuGre friction parameters (docs/model.md §3): F_t = (sigma0 z + sigma1 zdot)
// |lambda_n| + sigma2 v_r with zdot = v_r - sigma0 |v_r| z / g(v_r),
// g(v) = mu_c + (mu_s - mu_c) exp(-|v / v_s|^alpha). The scene schema and
// its defaults are in src/constraints/sliding_joint_type.cpp.
struct FrictionSpec {
  double mu_s = 0.15, mu_c = 0.1; // static and kinetic coefficients
  double v_s = 1e-3;              // Stribeck velocity, m/s
  double alpha = 2.0;             // Stribeck exponent
  double sigma0 = 1e5;            // bristle stiffness per unit normal force, 1/m
  double sigma1 = 0.0;            // bristle damping per unit normal force, s/m
  double sigma2 = 0.0;            // viscous friction, N s/m
  double stick_velocity = -1;     // |v_r| below it counts as stick in the output, m/s (< 0: v_s / 10)
};

class PadContact;

class LuGreFriction : public WorkItem {
public:
  ModeEnergyKind modeEnergyKind() const override { return ModeEnergyKind::Friction; } // mode labels
  LuGreFriction(std::shared_ptr<const SlidingJoint> joint, PetscInt zIndex, PetscInt normalRow, const FrictionSpec &spec);
  // Friction at a padded joint: the normal force is the pad's |f|.
  LuGreFriction(std::shared_ptr<const SlidingJoint> joint, PetscInt zIndex, const PadContact *pad,
                const FrictionSpec &spec);
  std::string name() const override { return joint_->name() + ".friction"; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void multiplierRows(std::vector<PetscInt> &rows) const override
  {
    if (pad_) rows.clear();
    else rows.assign(1, normalRow_);
  }
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;

  // Stribeck curve g(v) (dimensionless) and the steady-sliding force per unit
  // normal force and the viscous part: g(v) sign(v) |lambda_n| + sigma2 v.
  double stribeck(double v) const;
  PetscInt stateIndex() const { return z_; }
  // The multiplier row of lambda_n; -1 at a padded joint (pad() gives the force).
  PetscInt normalRow() const { return normalRow_; }
  const PadContact *pad() const { return pad_; }
  const SlidingJoint &joint() const { return *joint_; }
  // Friction force F_t (N) from the state z, its rate, |lambda_n| and v_r.
  double force(double z, double zdot, double lambdaN, double vr) const
  {
    return (spec_.sigma0 * z + spec_.sigma1 * zdot) * std::abs(lambdaN) + spec_.sigma2 * vr;
  }
  const FrictionSpec &spec() const { return spec_; }

private:
  std::shared_ptr<const SlidingJoint> joint_;
  PetscInt z_, normalRow_;
  FrictionSpec spec_;
  const PadContact *pad_ = nullptr;
  mutable Eigen::VectorXd padFq_, padFv_; // the pad force's derivatives, arrays kept between residuals
};

} // namespace boomdyn
