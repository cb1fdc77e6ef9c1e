// Assembler::evaluatePencil (one pass over the items for the eigen-analysis'
// A, B and D) must give bitwise the matrices of the three separate passes it
// replaced (Assembler::evaluate with the maps q = x, v = 0 and a = 0 or x;
// the damping pass as assembleDamping). Checked on the damped paper
// extraction scene (beams with Kelvin-Voigt damping, sliding joints, pads,
// ropes) at states along 20 ms of its run, on any rank count (CTest entry
// mpi2.regression runs it on two).
#include "support.hpp"

#include "boomdyn/damped_eigen_solver.hpp"

#include <cstring>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// The old eigen-analysis passes: A with the constraint blocks, then B with q
// from the offsets (cQ = 0), as assemblePencil made them before.
void assembleSeparately(Assembler &assembler, double t, Vec q, Vec lambda, Mat A, Mat B, Mat D)
{
  PetscHandle<Vec> x;
  double sigma = 0;
  check(assembler.createVector(x.address()));
  check(pencilState(assembler, q, lambda, x, &sigma));
  AssemblyContext ctx;
  ctx.t = t;
  ctx.sigma = sigma;
  check(assembler.setOffsets(nullptr, nullptr, nullptr));
  ctx.kin = {1.0, 0.0, 0.0};
  check(assembler.evaluate(ctx, x, nullptr, A));
  ctx.kin = {0.0, 0.0, 1.0};
  ctx.constraintBlocks = false;
  check(assembler.setOffsets(x, nullptr, nullptr));
  check(assembler.evaluate(ctx, x, nullptr, B));
  check(assembleDamping(assembler, t, q, lambda, D, sigma));
}

// Entries of the local rows that differ in bits (and the entries compared).
int differingEntries(Mat P, Mat Q, int *compared)
{
  PetscInt lo, hi;
  int differ = 0;
  check(MatGetOwnershipRange(P, &lo, &hi));
  for (PetscInt i = lo; i < hi; ++i) {
    PetscInt np, nq;
    const PetscInt *cp, *cq;
    const PetscScalar *vp, *vq;
    check(MatGetRow(P, i, &np, &cp, &vp));
    check(MatGetRow(Q, i, &nq, &cq, &vq));
    EXPECT_EQ(np, nq);
    for (PetscInt k = 0; k < std::min(np, nq); ++k) {
      ++*compared;
      const bool d = cp[k] != cq[k] || std::memcmp(&vp[k], &vq[k], sizeof(PetscScalar)) != 0;
      differ += d;
    }
    check(MatRestoreRow(Q, i, &nq, &cq, &vq));
    check(MatRestoreRow(P, i, &np, &cp, &vp));
  }
  return differ;
}

} // namespace

TEST(PencilAssembly, OnePassEqualsTheSeparatePassesBitwise)
{
  Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/paper_extraction.yaml");
  scene.dynamic.t_end = 0.02;
  HandIntegration run(scene);
  Assembler &assembler = run.assembler;
  ASSERT_TRUE(run.model.hasPhysicalDamping());
  int states = 0, compared = 0, differ = 0, nonzeroD = 0;
  auto onStep = [&](const StepInfo &s) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscHandle<Mat> A, B, D, A1, B1, D1;
    for (Mat *m : {A.address(), B.address(), D.address(), A1.address(), B1.address(), D1.address()})
      PetscCall(assembler.createMatrix(m));
    Vec q = run.integrator->positions(), lambda = run.integrator->multipliers();
    // The same offsets before both: pencilState's scale sigma is computed
    // through the map the offsets leave (characteristicScales gathers
    // q = qc + x), so it would differ otherwise.
    PetscCall(assembler.setOffsets(nullptr, nullptr, nullptr));
    assembleSeparately(assembler, s.t, q, lambda, A, B, D);
    PetscCall(assembler.setOffsets(nullptr, nullptr, nullptr));
    double sigma = 0;
    PetscCall(assemblePencil(assembler, s.t, q, lambda, A1, B1, &sigma, D1));
    EXPECT_GT(sigma, 0.0);
    differ += differingEntries(A, A1, &compared) + differingEntries(B, B1, &compared) +
              differingEntries(D, D1, &compared);
    PetscReal dnorm;
    PetscCall(MatNorm(D1, NORM_FROBENIUS, &dnorm));
    nonzeroD += dnorm > 0;
    ++states;
    PetscFunctionReturn(0);
  };
  RunSummary summary;
  check(integrate(*run.integrator, scene.dynamic, onStep, &summary));
  EXPECT_TRUE(summary.completed);
  EXPECT_GE(states, 20);
  EXPECT_EQ(nonzeroD, states) << "the damping pass must have something to compare";
  EXPECT_GT(compared, 0);
  EXPECT_EQ(differ, 0) << "of " << compared << " entries";
}

// The constraint scale sigma of the pencil is the stiffness scale at the
// analysed state, whatever offsets earlier work left in the assembler: it
// once read q = qc + q when an earlier analysis had left qc = its state.
TEST(PencilAssembly, ScaleDoesNotDependOnTheOffsetsLeftBehind)
{
  Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/paper_extraction.yaml");
  scene.dynamic.t_end = 0.005;
  HandIntegration run(scene);
  Assembler &assembler = run.assembler;
  int states = 0;
  auto onStep = [&](const StepInfo &s) -> PetscErrorCode {
    PetscFunctionBeginUser;
    Vec q = run.integrator->positions(), lambda = run.integrator->multipliers();
    PetscHandle<Mat> A, B;
    PetscCall(assembler.createMatrix(A.address()));
    PetscCall(assembler.createMatrix(B.address()));
    double clean = 0, afterOffsets = 0, afterAnalysis = 0;
    PetscCall(assembler.setOffsets(nullptr, nullptr, nullptr));
    PetscCall(assemblePencil(assembler, s.t, q, lambda, A, B, &clean));
    // assemblePencil leaves qc = its state: a second analysis right after.
    PetscCall(assemblePencil(assembler, s.t, q, lambda, A, B, &afterAnalysis));
    PetscCall(assembler.setOffsets(q, nullptr, nullptr));
    PetscCall(assemblePencil(assembler, s.t, q, lambda, A, B, &afterOffsets));
    EXPECT_GT(clean, 0.0);
    EXPECT_EQ(clean, afterAnalysis);
    EXPECT_EQ(clean, afterOffsets);
    ++states;
    PetscFunctionReturn(0);
  };
  RunSummary summary;
  check(integrate(*run.integrator, scene.dynamic, onStep, &summary));
  EXPECT_TRUE(summary.completed);
  EXPECT_GE(states, 4);
}
