// Assembly of the residual and Jacobian of the saddle-point system into
// PETSc objects. Each rank evaluates the work items whose first coordinate
// it owns; the values they need arrive through one VecScatter into a local
// array (on one rank x's own array, no scatter), residuals return by a
// reverse scatter (ADD; on one rank straight into F), and Jacobian blocks go
// through MatSetValuesCOO on a pattern preallocated exactly once from the
// items' dof lists (docs/petsc-notes.md, trap 1 and 2: one pattern, never mixed with
// MatSetValues).
#pragma once

#include "boomdyn/model.hpp"
#include "boomdyn/petsc_handle.hpp"
#include "boomdyn/work_item.hpp"

#include <petscmat.h>
#include <petscvec.h>

#include <vector>

namespace boomdyn {

class Assembler {
public:
  explicit Assembler(const Model &model) : model_(model) {}
  Assembler(const Assembler &) = delete;
  Assembler &operator=(const Assembler &) = delete;

  PetscErrorCode setUp(MPI_Comm comm);
  // After sliding joints relocate: rebuild the pattern (collective). Matrices
  // made by createMatrix() before are stale: make new ones (docs/petsc-notes.md trap 1).
  PetscErrorCode rebuildPattern();
  int patternVersion() const { return patternVersion_; }
  // A vector with the layout of x = [q | lambda_hat].
  PetscErrorCode createVector(Vec *x) const;
  // An MPIAIJ matrix with the exact preallocation of the Jacobian.
  PetscErrorCode createMatrix(Mat *J) const;
  // Constant parts of the affine map q = qc + cQ x, v = vc + cV x,
  // a = ac + cA x (layout of x; multiplier entries ignored). Null = zero.
  PetscErrorCode setOffsets(Vec qc, Vec vc, Vec ac);
  // Residual into F and Jacobian into J (either may be null).
  PetscErrorCode evaluate(const AssemblyContext &ctx, Vec x, Vec F, Mat J);
  // The eigen-analysis' matrices at the state x = [q | lambda_hat] (time,
  // sigma from ctx) in one pass over the items, each item's values gathered
  // once: A = dR/dq (stiffness with the constraint blocks), B = dR/da (mass,
  // zero constraint blocks), D = dR/dv at v = 0 (damping, zero constraint
  // blocks; skipped when null). The same matrices, bit for bit, as three
  // evaluate() passes with those maps (q = x, v = 0; a = 0 or a = x). Leaves
  // the offsets at q = x (setOffsets(x, null, null)).
  PetscErrorCode evaluatePencil(const AssemblyContext &ctx, Vec x, Mat A, Mat B, Mat D);
  // Energy and max |C| over all constraint rows at the state given by x
  // through the affine map. With `forces`, also the damping forces there
  // (as dampingForces(q, v) with q and v from the same map: the energy check
  // of every step needs both at the state reached, and one pass over the
  // items gathers their values once instead of twice).
  struct DampingForces;
  PetscErrorCode diagnostics(const AssemblyContext &ctx, Vec x, EnergyParts *energy, PetscReal *maxViolation,
                             DampingForces *forces = nullptr);
  // The damping forces Q_d(q, v) of this rank's items, item by item
  // (DampingForces), and their work dq . Q_d along an increment dq (summed
  // over the items and the ranks; collective): the energy check evaluates
  // the forces once per state and takes their work along two steps. dampingForces
  // leaves the offsets set (the solvers set their own before every assembly).
  struct DampingForces {
    std::vector<std::size_t> items; // items with damping forces
    std::vector<int> first;         // where each one's forces start in f
    std::vector<double> f;
    std::size_t used = 0; // while a pass fills f: entries taken so far
  };
  PetscErrorCode dampingForces(Vec q, Vec v, DampingForces *forces);
  // The work of `count` sets of damping forces along one increment dq:
  // work[k] = dq . f_k, summed item by item. Sets over the same items (two
  // states of one model) in one pass; otherwise one pass per set.
  PetscErrorCode dampingWork(const DampingForces *const forces[], int count, Vec dq, PetscReal work[]);
  // The strain energy 1/2 s^T K s of a mode shape s (layout of x, the
  // multiplier part ignored) by kind, summed over the items and the ranks
  // (WorkItem::modeEnergy; collective): K is the pencil's stiffness at the
  // state x = [q | lambda_hat] with ctx's time and sigma (pencilState),
  // v = a = 0. Leaves the offsets at zero.
  PetscErrorCode modeEnergy(const AssemblyContext &ctx, Vec x, Vec shape, ModeEnergy *out);
  // Mean diagonal of mass and stiffness over position coordinates at q = x.
  PetscErrorCode characteristicScales(Vec x, PetscReal *mass, PetscReal *stiffness);

  const Model &model() const { return model_; }
  MPI_Comm comm() const { return comm_; }
  PetscInt numLocalItems() const { return static_cast<PetscInt>(items_.size()); }
  // Index set of the coordinates (not multipliers) owned by this rank, in x's layout.
  PetscErrorCode coordinateRange(PetscInt *begin, PetscInt *end) const;
  // x = [initial coordinates of the model | 0].
  PetscErrorCode initialState(Vec x) const;
  // The initial velocities (Model::initialVelocities) in a vector of x's layout.
  PetscErrorCode initialVelocity(Vec v) const;
  // dst's multiplier entries = scale * src's multiplier entries (coordinates of dst untouched).
  PetscErrorCode copyMultipliers(Vec src, Vec dst, PetscReal scale) const;

private:
  PetscErrorCode buildPattern();
  // The local values of x (scattered, or x's own array in place) for the
  // items' gathers, with the coefficients of the map; endLocal() releases them.
  PetscErrorCode beginLocal(const AssemblyContext &ctx, Vec x);
  PetscErrorCode endLocal();
  void gather(std::size_t k, ItemValues &vals, int slot = 0);
  // Item k's residual block r into the local residual f (cleared after).
  void addResidual(std::size_t k, double *r, double *f) const;
  void startDampingForces(DampingForces *forces) const;
  void addDampingForce(std::size_t k, const ItemValues &vals, DampingForces *forces) const;
  void takeDampingForce(std::size_t k, DampingForces *forces) const;

  const Model &model_;
  MPI_Comm comm_ = MPI_COMM_NULL;
  int patternVersion_ = 0;
  PetscHandle<Vec> xTemplate_, xLocal_, fLocal_;
  PetscHandle<VecScatter> scatter_;
  std::vector<int> itemRank_;               // rank of every model item (empty: owner of its first unknown)
  std::vector<const WorkItem *> items_;
  std::vector<int> itemStart_, itemCoords_; // offsets into itemLocal_; coordinate counts
  std::vector<PetscInt> itemLocal_;         // local indices of each item's dofs
  std::vector<char> first_;                // per item entry: the first to touch its local entry
  std::vector<PetscInt> untouched_;         // local entries no item touches
  std::vector<char> plain_;                // item's local entries consecutive, no first-order state
  std::vector<unsigned char> batch_;       // items in the residual batch starting at each item (1: alone)
  std::size_t slot_ = 0;                    // size of one block of the per-item buffers (the largest item)
  std::vector<PetscCount> cooStart_;
  std::vector<PetscInt> cooI_, cooJ_;
  std::vector<PetscScalar> cooV_;
  std::vector<double> qc_, vc_, ac_;  // local offsets
  bool offsetZero_[3] = {true, true, true}; // qc_, vc_, ac_ known to be all zero (setOffsets)
  std::vector<char> firstOrder_;      // local entries that are first-order states
  bool inPlace_ = false;              // local vector = this rank's part of x, same order (no scatter)
  Vec localSource_ = nullptr;         // between beginLocal and endLocal: x or xLocal_
  const PetscScalar *xl_ = nullptr;   // its array
  Kinematics kin_;                    // the map's coefficients
  std::vector<double> bq_, bv_, ba_, bl_, br_; // per-item buffers (the Jacobian goes into cooV_; q, v, a
                                               // hold kPencilPasses blocks for evaluatePencil, and all
                                               // of them kResidualBatch blocks for batched residuals)
};

} // namespace boomdyn
