// Adapter from a Constraint kernel to a WorkItem: adds sigma C_q^T lambda_hat
// to the coordinate rows and sigma C (or sigma (C_q a + gamma) at
// acceleration level) as the multiplier rows.
#pragma once

#include "boomdyn/constraint.hpp"

#include <memory>

namespace boomdyn {

class ConstraintItem : public WorkItem {
public:
  ConstraintItem(std::shared_ptr<const Constraint> constraint, PetscInt firstRow);
  std::string name() const override { return constraint_->name(); }
  void coordinates(std::vector<PetscInt> &dofs) const override { constraint_->coordinates(dofs); }
  void multiplierRows(std::vector<PetscInt> &rows) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  // Power of the constraint forces, lambda . dC/dt (non-zero for drives only);
  // in.lambda holds the unscaled multipliers here.
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  double constraintViolation(const AssemblyContext &ctx, const ItemValues &in) const override;
  ModeEnergyKind modeEnergyKind() const override { return constraint_->modeEnergyKind(); }
  const Constraint &constraint() const { return *constraint_; }
  PetscInt firstRow() const { return firstRow_; }

private:
  std::shared_ptr<const Constraint> constraint_;
  PetscInt firstRow_;
  mutable ConstraintEval eval_; // evaluate()'s work arrays, kept between calls
  // The products C_q^T lambda and C_q a of evaluate(), formed here instead
  // of in Eigen's heap temporaries (one malloc and free per residual and
  // constraint: 220 000 on the paper scene); same operations.
  mutable Eigen::VectorXd product_;
};

} // namespace boomdyn
