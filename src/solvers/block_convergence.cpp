#include "boomdyn/block_convergence.hpp"

#include "boomdyn/lugre_friction.hpp"
#include "boomdyn/model.hpp"
#include "boomdyn/sliding_joint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace boomdyn {

const char *BlockConvergence::blockName(int b)
{
  static const char *names[] = {"body coordinates", "slack coordinates", "first-order states", "multipliers"};
  return b >= 0 && b < NumBlocks ? names[b] : "none";
}

PetscErrorCode BlockConvergence::setUp(const Model &model, Vec x)
{
  PetscInt lo, hi;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)x, &comm_));
  PetscCall(VecGetOwnershipRange(x, &lo, &hi));
  block_.assign(hi - lo, Bodies);
  zFloor_.assign(hi - lo, 0.0);
  auto owned = [&](PetscInt g) { return g >= lo && g < hi; };
  for (PetscInt g = std::max(lo, model.numCoordinates()); g < hi; ++g) block_[g - lo] = Multipliers;
  for (const auto &joint : model.slidingJoints())
    if (owned(joint->slackIndex())) block_[joint->slackIndex() - lo] = Slacks;
  // First-order states (LuGre z, a cylinder's pressures) are judged entry
  // by entry against their own size: max(|x|, floor), the floor given by
  // their owner or, for LuGre z, the friction law's bound below.
  stateOf_.assign(hi - lo, -1);
  stateNames_ = model.firstOrderNames();
  for (std::size_t k = 0; k < model.firstOrderCoordinates().size(); ++k) {
    const PetscInt g = model.firstOrderCoordinates()[k];
    if (!owned(g)) continue;
    stateOf_[g - lo] = static_cast<int>(k);
    if (!(model.firstOrderFloors()[k] > 0)) continue;
    block_[g - lo] = FirstOrderStates;
    zFloor_[g - lo] = model.firstOrderFloors()[k];
  }
  for (const LuGreFriction *f : model.frictions()) {
    const PetscInt g = f->stateIndex();
    if (!owned(g)) continue;
    block_[g - lo] = FirstOrderStates;
    zFloor_[g - lo] = std::max(f->spec().mu_s, f->spec().mu_c) / f->spec().sigma0;
  }
  runs_.clear();
  for (std::size_t i = 0; i < block_.size(); ++i)
    if (runs_.empty() || runs_.back().block != block_[i]) runs_.push_back({i, i + 1, block_[i]});
    else runs_.back().end = i + 1;
  std::array<int, NumBlocks> local{};
  for (unsigned char b : block_) local[b] = 1;
  PetscCallMPI(MPI_Allreduce(local.data(), present_.data(), NumBlocks, MPI_INT, MPI_MAX, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode BlockConvergence::step(Vec x, Vec dx)
{
  PetscScalar *xa;
  const PetscScalar *da;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(x, &xa));
  PetscCall(VecGetArrayRead(dx, &da));
  // x - dx is x + (-1) dx, what VecAXPY(x, -1, dx) stores; the sums are
  // test()'s, run by run in the entries' order.
  stepSums_.fill(0.0);
  for (const Run &run : runs_) {
    const int b = run.block;
    double x2 = stepSums_[b], d2 = stepSums_[NumBlocks + b];
    for (std::size_t i = run.begin; i < run.end; ++i) {
      const double xi = xa[i] - da[i];
      xa[i] = xi;
      x2 += xi * xi;
      d2 += da[i] * da[i];
    }
    stepSums_[b] = x2, stepSums_[NumBlocks + b] = d2;
  }
  PetscCall(VecRestoreArrayRead(dx, &da));
  PetscCall(VecRestoreArray(x, &xa));
  haveStepSums_ = true;
  PetscFunctionReturn(0);
}

PetscErrorCode BlockConvergence::test(PetscInt it, Vec x, Vec dx, Vec F, PetscReal rtol, PetscReal stol, PetscReal atol,
                                      SNESConvergedReason *reason)
{
  const PetscScalar *xa, *da = nullptr, *fa;
  PetscFunctionBeginUser;
  *reason = SNES_CONVERGED_ITERATING;
  // Per block: sum of x^2, sum of dx^2, max |F|, and for the first-order states
  // the largest increment relative to the entry's own size; then the 2-norm
  // of F for PETSc's absolute test. Summed or maximized over the ranks.
  enum { X2 = 0, D2 = NumBlocks, FMAX = 2 * NumBlocks, ZRATIO = 3 * NumBlocks, F2, N };
  double local[N] = {0};
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArrayRead(F, &fa));
  if (it > 0) PetscCall(VecGetArrayRead(dx, &da));
  // Run by run (blocks are long runs: a body's coordinates, the
  // multipliers), each sum in a register and in the entries' order, so the
  // same sums as entry by entry through the array (which stored and
  // reloaded every partial sum: 33 instructions per unknown on the long
  // boom, a third of a residual's framework cost).
  // After step() (the update x -= dx), the sums of x^2 and dx^2 are
  // there already: then only F is read (and x, dx at the first-order states).
  const bool stepped = da && haveStepSums_;
  haveStepSums_ = false;
  if (stepped)
    for (int b = 0; b < NumBlocks; ++b) local[X2 + b] = stepSums_[b], local[D2 + b] = stepSums_[NumBlocks + b];
  double f2 = local[F2];
  int largestState = -1; // the first-order state of local[ZRATIO]
  for (const Run &run : runs_) {
    const int b = run.block;
    double fmax = local[FMAX + b];
    if (stepped)
      for (std::size_t i = run.begin; i < run.end; ++i) {
        fmax = std::max(fmax, std::abs(fa[i]));
        f2 += fa[i] * fa[i];
      }
    else {
      double x2 = local[X2 + b];
      for (std::size_t i = run.begin; i < run.end; ++i) {
        x2 += xa[i] * xa[i];
        fmax = std::max(fmax, std::abs(fa[i]));
        f2 += fa[i] * fa[i];
      }
      local[X2 + b] = x2;
    }
    local[FMAX + b] = fmax;
    if (!da) continue;
    if (!stepped) {
      double d2 = local[D2 + b];
      for (std::size_t i = run.begin; i < run.end; ++i) d2 += da[i] * da[i];
      local[D2 + b] = d2;
    }
    if (b == FirstOrderStates)
      for (std::size_t i = run.begin; i < run.end; ++i) {
        const double ratio = std::abs(da[i]) / std::max(std::abs(xa[i]), zFloor_[i]);
        if (ratio > local[ZRATIO]) local[ZRATIO] = ratio, largestState = stateOf_[i];
      }
  }
  local[F2] = f2;
  if (da) PetscCall(VecRestoreArrayRead(dx, &da));
  PetscCall(VecRestoreArrayRead(F, &fa));
  PetscCall(VecRestoreArrayRead(x, &xa));
  // Two reductions: the sums, then the maxima.
  double sums[2 * NumBlocks + 1], maxima[NumBlocks + 1], all[N];
  for (int b = 0; b < 2 * NumBlocks; ++b) sums[b] = local[b];
  sums[2 * NumBlocks] = local[F2];
  for (int b = 0; b <= NumBlocks; ++b) maxima[b] = local[FMAX + b];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sums, 2 * NumBlocks + 1, MPI_DOUBLE, MPI_SUM, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, maxima, NumBlocks + 1, MPI_DOUBLE, MPI_MAX, comm_));
  for (int b = 0; b < 2 * NumBlocks; ++b) all[b] = sums[b];
  all[F2] = sums[2 * NumBlocks];
  for (int b = 0; b <= NumBlocks; ++b) all[FMAX + b] = maxima[b];

  const double fnorm = std::sqrt(all[F2]);
  // The whole vectors' 2-norms (NewtonSolver's tests without the line
  // search's norms): the blocks' sums summed in the blocks' order.
  double x2 = 0, d2 = 0;
  for (int b = 0; b < NumBlocks; ++b) x2 += all[X2 + b], d2 += all[D2 + b];
  fnorm_ = fnorm, xnorm_ = std::sqrt(x2), snorm_ = it > 0 ? std::sqrt(d2) : 0.0;
  if (std::isnan(fnorm) || std::isinf(fnorm)) {
    *reason = SNES_DIVERGED_FNORM_NAN;
    PetscFunctionReturn(0);
  }
  if (fnorm <= atol) {
    *reason = SNES_CONVERGED_FNORM_ABS;
    PetscFunctionReturn(0);
  }
  incrementAtRoundoff_ = false;
  if (it == 0) {
    for (int b = 0; b < NumBlocks; ++b) initialResidual_[b] = all[FMAX + b];
    previousIncrement_.fill(0.0);
    PetscFunctionReturn(0);
  }
  // Increments below this are round-off: the coordinates' size times a
  // hundred machine epsilons.
  const double roundoff = 100 * std::numeric_limits<double>::epsilon() * std::sqrt(all[X2 + Bodies] + all[X2 + Slacks]);
  roundoff_ = roundoff;
  bool allResiduals = true;
  lastHolder_ = -1;
  lastHolderState_.clear();
  incrementAtRoundoff_ = true;
  std::array<double, NumBlocks> increments{};
  for (int b = 0; b < NumBlocks; ++b) {
    // The size of the block's increment, for the first-order states relative
    // to each entry's own size.
    increments[b] = b == FirstOrderStates ? all[ZRATIO] : std::sqrt(all[D2 + b]);
    if (!present_[b]) continue;
    const bool residual = all[FMAX + b] <= rtol * initialResidual_[b];
    // The error left after this increment, estimated from the contraction
    // theta = |dx_k| / |dx_{k-1}| as theta / (1 - theta) |dx_k| (Hairer &
    // Wanner, Solving ODEs II, IV.8); at the first iteration, or without
    // contraction, |dx_k| itself.
    const double theta = it > 1 && previousIncrement_[b] > 0 ? increments[b] / previousIncrement_[b] : 1.0;
    const double left = theta < 1 ? theta / (1 - theta) * increments[b] : increments[b];
    const double step = std::sqrt(all[D2 + b]);
    incrementAtRoundoff_ = incrementAtRoundoff_ && step <= roundoff;
    const bool increment = step <= roundoff || (b == FirstOrderStates ? left <= stol : left <= stol * std::sqrt(all[X2 + b]));
    allResiduals = allResiduals && residual;
    if (!residual && !increment && lastHolder_ < 0) {
      lastHolder_ = b;
      if (b == FirstOrderStates) {
        // Which state: the owner of the largest relative increment over the
        // ranks (the same branch on every rank: all[] is reduced).
        struct {
          double ratio;
          int state;
        } mine{local[ZRATIO], largestState}, worst;
        PetscCallMPI(MPI_Allreduce(&mine, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm_));
        if (worst.state >= 0 && worst.state < (int)stateNames_.size()) lastHolderState_ = stateNames_[worst.state];
      }
      PetscCall(PetscInfo(nullptr,
                          "iteration %d: %s not converged: residual %g (%g at the first iterate), increment %g (block size %g, "
                          "largest relative increment of a first-order state %g%s%s%s, estimated error left %g, round-off %g)\n",
                          (int)it, blockName(b), all[FMAX + b], initialResidual_[b], step, std::sqrt(all[X2 + b]), all[ZRATIO],
                          lastHolderState_.empty() ? "" : " (", lastHolderState_.c_str(),
                          lastHolderState_.empty() ? "" : ")", left, roundoff));
    }
  }
  previousIncrement_ = increments;
  if (lastHolder_ >= 0) PetscFunctionReturn(0);
  *reason = allResiduals ? SNES_CONVERGED_FNORM_RELATIVE : SNES_CONVERGED_SNORM_RELATIVE;
  PetscFunctionReturn(0);
}

} // namespace boomdyn
