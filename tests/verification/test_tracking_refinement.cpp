// Cheap frequency tracking (issue 18, item 2): along the paper's extraction
// scene (shortened to 0.5 s of extraction, so that the contact points cross
// elements and the pattern changes), two trackers analyze the same states
// every 10 ms: one with the full Krylov-Schur solve at every analysis (the
// path before refinement, -boom_tracking_full) and one that refines the
// previous modes. The frequencies must agree to 1e-8 relative, the MAC must
// pick the same mode, every refined mode must satisfy the eigen-equation of
// the pencil assembled independently here to 1e-8, and refinement must
// actually carry the analyses (not the fallback).
#include "support.hpp"

#include "boomdyn/frequency_tracker.hpp"

#include <slepcsys.h>

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// max over the first `count` basis vectors of ||A x - w B x|| / ||A x||,
// with A and B assembled afresh at the state.
double worstEigenResidual(Assembler &assembler, double t, Vec q, Vec lambda, const std::vector<PetscHandle<Vec>> &basis,
                          const std::vector<double> &omega2)
{
  PetscHandle<Mat> A, B;
  PetscHandle<Vec> ax, bx;
  check(assembler.createMatrix(A.address()));
  check(assembler.createMatrix(B.address()));
  check(assemblePencil(assembler, t, q, lambda, A, B));
  check(VecDuplicate(basis[0], ax.address()));
  check(VecDuplicate(basis[0], bx.address()));
  double worst = 0;
  for (std::size_t k = 0; k < omega2.size(); ++k) {
    PetscReal an, rn;
    check(MatMult(A, basis[k], ax));
    check(MatMult(B, basis[k], bx));
    check(VecNorm(ax, NORM_2, &an));
    check(VecAXPY(ax, -omega2[k], bx));
    check(VecNorm(ax, NORM_2, &rn));
    worst = std::max(worst, rn / an);
  }
  return worst;
}

} // namespace

TEST(TrackingRefinement, EqualsFullSolveAlongExtraction)
{
  const Scene scene = shortenedExtraction(0.5);
  Model model(scene);
  Assembler assembler(model);
  Vec x, zero;
  check(assembler.setUp(PETSC_COMM_WORLD));
  check(assembler.createVector(&x));
  check(assembler.createVector(&zero));
  check(assembler.initialState(x));
  GeneralizedAlpha integrator(assembler, scene.dynamic.rho_inf);
  check(integrator.setUp(scene.dynamic.max_newton));
  check(integrator.initialize(0.0, x, zero));
  check(SlepcInitialize(nullptr, nullptr, nullptr, nullptr));
  const int count = scene.tracking.count;
  FrequencyTracker full(assembler, count, true), refined(assembler, count);
  int analyses = 0, refinedAnalyses = 0, differentPick = 0;
  double worstFrequency = 0, worstResidual = 0;
  double next = 0.0;
  auto onStep = [&](const StepInfo &s) -> PetscErrorCode {
    PetscFunctionBeginUser;
    if (s.t >= next - 1e-9) {
      TrackedModes a, b;
      PetscCall(full.analyze(s.t, integrator.positions(), integrator.multipliers(), &a));
      PetscCall(refined.analyze(s.t, integrator.positions(), integrator.multipliers(), &b));
      ++analyses;
      differentPick += a.index != b.index;
      for (int k = 0; k < count; ++k) {
        const double d = std::abs(a.frequencyHz[k] - b.frequencyHz[k]) / a.frequencyHz[k];
        if (d > 5e-9)
          PetscPrintf(PETSC_COMM_WORLD, "  t = %.3f s, mode %d: %.10f Hz (full) vs %.10f Hz (%s), relative difference %.2e\n",
                      s.t, k + 1, a.frequencyHz[k], b.frequencyHz[k], b.refined ? "refined" : "fallback", d);
        worstFrequency = std::max(worstFrequency, d);
      }
      if (b.refined) {
        ++refinedAnalyses;
        std::vector<double> omega2;
        for (double f : b.frequencyHz) omega2.push_back(std::pow(2 * M_PI * f, 2));
        worstResidual = std::max(worstResidual, worstEigenResidual(assembler, s.t, integrator.positions(),
                                                                   integrator.multipliers(), refined.basis(), omega2));
      }
      next += 0.01;
    }
    PetscFunctionReturn(0);
  };
  RunSummary summary;
  check(integrate(integrator, scene.dynamic, onStep, &summary));
  EXPECT_TRUE(summary.completed);
  PetscPrintf(PETSC_COMM_WORLD,
              "  %d analyses, %d refined; frequencies vs full solve: max relative difference %.2e; different MAC pick: "
              "%d; worst refined eigen-residual %.2e; pattern rebuilds %d\n",
              analyses, refinedAnalyses, worstFrequency, differentPick, worstResidual, assembler.patternVersion());
  EXPECT_GE(analyses, 50);
  EXPECT_GE(assembler.patternVersion(), 1) << "the run must cross elements (pattern changes)";
  EXPECT_GE(refinedAnalyses, analyses * 8 / 10) << "refinement must carry the analyses, not the fallback";
  EXPECT_LT(worstFrequency, 1e-8);
  EXPECT_EQ(differentPick, 0);
  EXPECT_LT(worstResidual, 1e-8);
  VecDestroy(&x);
  VecDestroy(&zero);
}
