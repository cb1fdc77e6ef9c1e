// Newton convergence judged per block of unknowns, each on its own scale
// (docs/model.md §4.7). One test over the whole vector x = [q | lambda_hat]
// lets the large entries (positions of metres) hide the small ones: a step
// norm below 1e-10 |x| accepted LuGre bristle states z of size mu_s/sigma0
// ~ 1e-8 m that had not converged, so |z| exceeded its bound and a block
// that had to break away stuck (issue 13, item 1).
//
// The blocks are the body coordinates, the slack coordinates, the friction
// states and the scaled multipliers. A block has converged when
//   - its residual rows have fallen to rtol times their size at the first
//     iterate (max norm over the block), or
//   - its last Newton increment is below stol times the block's size
//     (2-norms, as PETSc's step test), or below the round-off of the
//     increments, 100 eps |q| (the coordinates' 2-norm): increments cannot
//     get smaller than that, however many iterations are made.
// Friction states are judged entry by entry against max(|z|, g_max/sigma0),
// their natural size (g_max = max(mu_s, mu_c) bounds |z| sigma0); the
// other first-order states (a hydraulic cylinder's pressures, stroke
// memory and spool) belong to the same block, each against max(|x|, its
// floor) (Model::firstOrderFloors).
// The iteration has converged when every block has. rtol and stol are
// SNES's own (-snes_rtol, -snes_stol); the test does not depend on whether
// the Jacobian is reused.
#pragma once

#include <petscsnes.h>

#include <array>
#include <string>
#include <vector>

namespace boomdyn {

class Model;

class BlockConvergence {
public:
  enum Block { Bodies = 0, Slacks, FirstOrderStates, Multipliers, NumBlocks };
  static const char *blockName(int b);

  // Which block each entry of x owned by this rank belongs to (x: a vector
  // with the solver's layout), and the size floor of the first-order states.
  PetscErrorCode setUp(const Model &model, Vec x);
  // The test after Newton iteration `it` at the iterate x with the last
  // increment dx (unused at it = 0) and the residual F.
  PetscErrorCode test(PetscInt it, Vec x, Vec dx, Vec F, PetscReal rtol, PetscReal stol, PetscReal atol,
                      SNESConvergedReason *reason);
  // The Newton update x -= dx on the owned entries (x + (-1) dx, as
  // VecAXPY), with the sums over x^2 and dx^2 that the next test() needs
  // taken in the same pass (that test then reads only F).
  PetscErrorCode step(Vec x, Vec dx);
  // The block that kept the last unconverged iteration going (for -info).
  int lastHolder() const { return lastHolder_; }
  // When that block was the first-order states: the one with the largest
  // relative increment, as its owner names it (Model::firstOrderNames(),
  // e.g. "piston pressure of hydraulic_cylinder 'luffing'"); else empty.
  const std::string &lastHolderState() const { return lastHolderState_; }
  // Whether the last increment of every block was below the round-off of
  // the increments (100 eps |q|): the iterate cannot get more accurate.
  bool incrementAtRoundoff() const { return incrementAtRoundoff_; }
  // That round-off of the increments (100 eps |q|) at the last test.
  double incrementRoundoff() const { return roundoff_; }
  // 2-norms of F, x and dx at the last test (dx: 0 at iteration 0).
  double fnorm() const { return fnorm_; }
  double xnorm() const { return xnorm_; }
  double snorm() const { return snorm_; }

private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  std::vector<unsigned char> block_; // per owned entry
  std::vector<double> zFloor_;       // per owned entry (first-order states only)
  std::vector<int> stateOf_;         // per owned entry: its position in Model::firstOrderNames(), or -1
  std::vector<std::string> stateNames_;
  std::string lastHolderState_;
  // Maximal runs of consecutive entries of one block (begin, end, block):
  // test() sums each run in registers.
  struct Run {
    std::size_t begin, end;
    int block;
  };
  std::vector<Run> runs_;
  std::array<int, NumBlocks> present_{};
  std::array<double, NumBlocks> initialResidual_{};
  std::array<double, NumBlocks> previousIncrement_{};
  int lastHolder_ = -1;
  bool incrementAtRoundoff_ = false;
  double roundoff_ = 0;
  double fnorm_ = 0, xnorm_ = 0, snorm_ = 0;
  std::array<double, 2 * NumBlocks> stepSums_{}; // x^2, dx^2 per block from step()
  bool haveStepSums_ = false;
};

} // namespace boomdyn
