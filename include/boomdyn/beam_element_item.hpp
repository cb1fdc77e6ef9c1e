// One ANCF element of a beam as an assembly work item: inertia, elastic
// forces, Kelvin-Voigt damping and gravity with their Jacobian
// cA M + cV D + cQ (K + dfd/dq).
#pragma once

#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/work_item.hpp"

#include <memory>

namespace boomdyn {

class BeamElementItem : public WorkItem {
public:
  // mass: the element mass matrix, shared by all elements of the beam.
  BeamElementItem(const AncfBeam &beam, int element, std::shared_ptr<const ancf::Mat8> mass, const Vec2 &gravity);
  std::string name() const override;
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  // A damped element: one damping kernel call for the stiffness pass's
  // dfd/dq and the damping pass's dfd/dv, the mass pass without any kernel.
  void evaluatePencil(const PencilPass (&pass)[kPencilPasses], int n, double *scratch) const override;
  // Elements of one beam (same length and section): their internal forces,
  // and damping forces when damped, in one batched kernel call
  // (ancf::internalForceLanes, ancf::internalAndDampingForceLanes), bit for
  // bit evaluate()'s residuals, damping memo included.
  const void *residualBatchKey() const override;
  void evaluateResiduals(const AssemblyContext &ctx, const WorkItem *const items[], const ItemValues in[],
                         double *const residual[], int count) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  bool energyAndDampingForce(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e,
                             double *f) const override;
  void scales(const ItemValues &in, double &massDiag, double &stiffDiag, int &count) const override;
  bool physicalDamping() const override;
  bool dampingForce(const ItemValues &in, double *f) const override;
  // Mode labels: the element's strain energy by strain (axial, bending),
  // its stress stiffening as geometric (docs/model.md §5).
  void modeEnergy(const PencilPass &stiffness, int n, const double *shape, double *scratch,
                  ModeEnergy &out) const override;

  // residual = M a + f - loadFactor g (inertia, internal force f, gravity g).
  void inertiaAndForces(const double *a, const ancf::Vec8 &f, double loadFactor, double *residual) const;
  // M v, bit-identical to Eigen's (*mass_) * v (the Kronecker form when M = m ⊗ I2).
  ancf::Vec8 massTimes(const double *v) const;
  // True when the damping force and power at in's (q, v) are kept (tests:
  // a residual, batched or not, keeps those of its state).
  bool dampingKeptAt(const ItemValues &in) const
  {
    return dampingMemo_.valid && dampingMemo_.q == Eigen::Map<const ancf::Vec8>(in.q) &&
           dampingMemo_.v == Eigen::Map<const ancf::Vec8>(in.v);
  }

private:
  // Kelvin-Voigt damping force into the residual, D (times cV) and dfd/dq (times cQ) into J.
  void addDamping(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const;

  // Damping force and dissipated power at (q, v), kept for the last state
  // (also by the residual of a damped element, evaluate() and
  // evaluateResiduals()): after every step the energy diagnostics (energy())
  // and the energy check (dampingForce()) ask for the state of Newton's last
  // residual.
  double dampingAt(const ItemValues &in, ancf::Vec8 &fd) const;
  // energy(), leaving the damping force in fd (damped sections; untouched otherwise).
  void energyAt(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e, ancf::Vec8 &fd) const;
  struct DampingMemo {
    bool valid = false;
    ancf::Vec8 q, v, fd;
    double power = 0;
  };
  mutable DampingMemo dampingMemo_;

  const AncfBeam *beam_;
  int element_;
  std::shared_ptr<const ancf::Mat8> mass_;
  ancf::Vec8 gravity_; // generalized gravity force of the element
  bool kroneckerMass_ = true; // *mass_ is m ⊗ I2 (see inertiaAndForces)
};

} // namespace boomdyn
