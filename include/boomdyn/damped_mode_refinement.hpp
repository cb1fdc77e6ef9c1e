// Cheap damped modes along a run (issue 18, item 2; docs/model.md §5
// "Damped refinement"). At a tracking analysis the undamped modes of the
// same state are already known (the symmetric refinement or full solve,
// mode_refinement.hpp) and the damping is light, so the damped modes lie
// nearly in their span. Instead of a fresh SLEPc PEP solve, the quadratic
// problem T(lambda) x = (lambda^2 M + lambda D + K) x = 0 is projected, for
// each wanted pair k, onto a small real subspace V_k of its own (nonlinear
// Arnoldi with Galerkin projection):
//     V_k = [undamped modes, u_k = P^{-1} D phi_k, P^{-1} M u_k],   P = K - tau M
//     (the symmetric refinement's factorization),
//     (lambda^2 V_k^T M V_k + lambda V_k^T D V_k + V_k^T K V_k) y = 0   (dense, small),
//     x = V_k y,  r = T(lambda) x,  V_k <- [V_k, P^{-1} Re r, P^{-1} Im r]
// until the pair has ||T(lambda) x|| <= tol ||K x||. The undamped modes'
// block is shared; the pairs' products and solves are one block per round.
// Separate subspaces keep the projected problems at p <= 14 instead of 28
// for one shared subspace (their dense solves grow like p^3). K, M and the
// factorization are the symmetric refinement's (no new assembly but D, no
// new factorization); all arithmetic is real (complex vectors as pairs).
#pragma once

#include "boomdyn/compact_matrix.hpp"
#include "boomdyn/damped_eigen_solver.hpp"
#include "boomdyn/local_block.hpp"
#include "boomdyn/mode_refinement.hpp"
#include "boomdyn/petsc_handle.hpp"

#include <complex>
#include <vector>

namespace boomdyn {

// z = T(l)^{-1} b for T(l) = K + l D + l^2 M with real p x p K, D, M (the
// projected quadratic problem of the refinement): the solve of its Rayleigh
// functional iteration. False when T(l) is singular to round-off.
bool solveShifted(const Eigen::MatrixXd &K, const Eigen::MatrixXd &D, const Eigen::MatrixXd &M,
                  std::complex<double> l, const Eigen::VectorXcd &b, Eigen::VectorXcd *z);

struct DampedRefinementInfo {
  int iterations = 0;      // projections solved
  int subspace = 0;        // largest dimension of a pair's subspace
  double worstResidual = 0; // max over the reported pairs of ||T(lambda) x|| / ||K x||
  // Per reported mode (the result's order): refined to the tolerance (or
  // its round-off floor), not only to provisionalTolerance (`needed`).
  std::vector<bool> exact;
};

class DampedModeRefiner {
public:
  explicit DampedModeRefiner(Assembler &assembler) : assembler_(assembler) {}

  // K, M: the symmetric pencil at (t, q, lambda); D: the damping matrix at
  // that state (ModeRefiner::damping()), or null to assemble it here;
  // solver: a factorization of
  // K - tau M (any tau near the modes); modes: undamped mode vectors at the
  // same state, ascending. On success (*converged) result holds the `count`
  // lowest oscillating damped modes by |lambda| (as solveDampedModes), with
  // their vectors.
  PetscErrorCode refine(double t, Vec q, Vec lambda, Mat K, Mat M, Mat D, KSP solver,
                        const std::vector<PetscHandle<Vec>> &modes, int count, DampedModalResult *result,
                        DampedRefinementInfo *info, bool *converged);

  // Relative residual every reported pair must reach. The round-off floor of
  // ||T(lambda) x|| / ||K x|| is about 1e-9 on the paper scene (the second
  // mode stalls at 3e-9 to 7e-9), and residuals near it make the expansion
  // noise: each pair stops at the first subspace where it passes, and keeps
  // its best iterate when its residual grows. Half the 1e-8 the
  // tests demand: recomputed from the final vectors the residual differs
  // from the iteration's by about the floor.
  double tolerance = 5e-9;
  int maxIterations = 6; // projections per pair
  // The pairs the caller needs exactly: positions in `modes` of the
  // undamped modes whose damped counterparts must reach `tolerance` (the
  // tracking's followed modes). The other pairs stop as soon as they reach
  // provisionalTolerance: at their first projection in 99 % of the paper
  // scene's pairs (median residual 1.2e-4, 90 % below 2.5e-4). That is
  // enough to compare their shapes by MAC (FrequencyTracker::analyzeDamped:
  // the angle to the exact vector is about residual / relative gap, so the
  // MAC is off by less than 0.014 for modes 15 % apart in omega^2), not to
  // report them. Empty, or a position that is not among the `count`
  // oscillating modes: every pair to `tolerance`.
  std::vector<int> needed;
  double provisionalTolerance = 1e-3;
  // Fill DampedModalResult::real, imag (tracking without a consumer of the
  // vectors skips their copies).
  bool keepVectors = true;
  // The constraint scale of the pencil K, M at this state (ModeRefiner::
  // pencilScale()), so that D is assembled without computing it again;
  // 0: computed (assembleDamping).
  double pencilScale = 0;
  // Infinity norms of K, D, M (ModeRefiner::norms() of the same pencil) for
  // the pairs' round-off floors eps (|K| + |l| |D| + |l|^2 |M|) |x| / |K x|:
  // a pair that stopped improving within floorFactor of its floor is
  // accepted (roundOffFloor(), mode_refinement.hpp); null: taken here.
  // Asked for only when a pair missed its tolerance.
  PencilNorms *norms = nullptr;

private:
  Assembler &assembler_;
  PetscHandle<Mat> D_;
  CompactMatrix Dc_; // D without explicit zeros, for the products (compact_matrix.hpp)
  int pattern_ = -1;
  LocalBlocks blocks_; // the vectors of the refinement as dense local blocks (local_block.hpp)
};

} // namespace boomdyn
