// Cheap re-analysis of modes along a run (issue 18, item 2; docs/model.md §5
// "Refinement"). Between two tracking analyses the state changes little, so
// the modes of the last analysis are a nearly invariant subspace of the new
// pencil. Instead of a fresh Krylov-Schur solve, they are refined by subspace
// iteration with shift-and-invert and Rayleigh-Ritz:
//     W = (A - tau B)^{-1} B V,   (W^T A W) y = theta (W^T B W) y,   V <- W Y,
// until every wanted Ritz pair has ||A x - theta B x|| <= tol ||A x||
// (leading wanted pairs that met it are kept in W as they are: soft locking).
// The pencil's matrices and the factorization of A - tau B are kept between
// analyses: while the sparsity pattern holds (no contact point changed
// element) only the values are assembled and refactored numerically.
#pragma once

#include "boomdyn/compact_matrix.hpp"
#include "boomdyn/eigen_solver.hpp"
#include "boomdyn/local_block.hpp"
#include "boomdyn/petsc_handle.hpp"

#include <vector>

namespace boomdyn {

// The round-off floor of a pair's relative residual, DBL_EPSILON * scale /
// norm: for the symmetric pencil scale = (|A| + |theta| |B|) |x| and norm =
// |A x| (infinity norms of A, B; 2-norms of vectors), a residual there is a
// normwise backward error of one unit round-off. The refinements accept a
// pair whose residual stopped falling within floorFactor (4) of it: on the
// paper scene (16 elements per boom) the floors lie far below the
// tolerance 5e-9, but refined the lowest mode's residual stalls at 0.13 to
// 1.2 of this estimate (1.4e-8 with 64 elements per boom, 2.2e-7 with 128),
// which no fixed tolerance of 5e-9 accepts: every analysis then fell back
// to the full solve. A stall well above it (5-15 times, seen once in 21
// analyses of the 64-element test, where the solves themselves were
// accurate only to about 1e-6) is not accepted: the full solve runs.
double roundOffFloor(double scale, double norm);

// Infinity norms of a pencil's matrices (stiffness K or A, mass M or B,
// damping D) for the round-off floors, each taken (MatNorm, collective)
// when first asked for after set(). The floors matter only for a pair whose
// residual stopped falling, which on the paper scene never happens: three
// norms per analysis were about 1 % of the tracking's instructions. The
// callers ask on every rank alike (their tests use reduced values).
class PencilNorms {
public:
  // The matrices of the next requests (D may be null: its norm is 0).
  void set(Mat K, Mat M, Mat D);
  PetscErrorCode stiffness(PetscReal *v) { return get(0, v); }
  PetscErrorCode mass(PetscReal *v) { return get(1, v); }
  PetscErrorCode damping(PetscReal *v) { return get(2, v); }

private:
  PetscErrorCode get(int which, PetscReal *v);
  Mat mats_[3] = {nullptr, nullptr, nullptr};
  PetscReal values_[3] = {-1, -1, -1}; // < 0: not taken yet
};
constexpr double floorFactor = 4.0;

struct RefinedModes {
  std::vector<double> omega2;              // the `count` lowest Ritz values, ascending
  double worstResidual = 0;                // max of ||A x - w B x|| / ||A x|| over them
  int iterations = 0;
};

class ModeRefiner {
public:
  explicit ModeRefiner(Assembler &assembler) : assembler_(assembler) {}

  // basis: the m >= count vectors (layout of x) of the previous analysis. On
  // success (*converged) they are replaced by the new Ritz vectors in
  // ascending order of omega^2, B-orthonormal; the first `count` are the modes.
  PetscErrorCode refine(double t, Vec q, Vec lambda, double target, int count, std::vector<PetscHandle<Vec>> &basis,
                        RefinedModes *out, bool *converged);

  // Relative residual every reported pair must reach, or, where it stops
  // falling, within floorFactor of its round-off floor (roundOffFloor()).
  // 5e-9 (was 1e-9): the eigenvalue error is of the order of residual^2 /
  // gap, far below the 1e-8 acceptance, and 2 % fewer tracking instructions
  // (docs/performance-history.md); half the 1e-8 the tests demand, because
  // the residual recomputed from the final vectors differs by about the floor.
  // When the residuals stop falling with a pair above both, the full solve
  // runs.
  double tolerance = 5e-9;
  int maxIterations = 10;
  // Assemble the damping matrix D with A and B in prepare() (one pass over
  // the items, Assembler::evaluatePencil), for the damped refinement.
  bool withDamping = false;

  // A, B at the state and the factorization of A - target B (called by
  // refine(); the damped refinement calls it when refine() did not run).
  PetscErrorCode prepare(double t, Vec q, Vec lambda, double target, bool *factored);
  // The pencil and the factorization of the last prepare(). The matrices
  // are compact copies for products (compact_matrix.hpp: the same operator,
  // bitwise the same products, without the pattern's explicit zeros).
  Mat stiffness() const { return Ac_.get(); }
  Mat mass() const { return Bc_.get(); }
  Mat damping() const { return withDamping ? Dc_.get() : nullptr; } // with withDamping
  KSP shiftedSolver() const { return ksp_; }
  bool factoredAtLastPrepare() const { return factored_; }
  // The constraint scale sigma of the last prepare()'s pencil (pencilState).
  double pencilScale() const { return sigma_; }
  // Infinity norms of A, B, D of the last prepare() (round-off floors),
  // taken when first asked for.
  PencilNorms &norms() { return norms_; }

private:

  Assembler &assembler_;
  PetscHandle<Mat> A_, B_, S_, D_;
  PetscHandle<Vec> state_; // the pencil's state x = [q | lambda / sigma] (assemblePencil's work vector)
  CompactMatrix Ac_, Bc_, Dc_; // A, B, D without explicit zeros, for the products
  PetscHandle<KSP> ksp_;
  int pattern_ = -1;
  bool factored_ = false;
  double sigma_ = 0;
  PencilNorms norms_;
  LocalBlocks blocks_; // the vectors of the refinement as dense local blocks (local_block.hpp)
};

} // namespace boomdyn
