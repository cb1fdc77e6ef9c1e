// The per-block Newton convergence test (include/boomdyn/block_convergence.hpp,
// docs/model.md §4.7) on hand-made iterates of a block on a rail with LuGre
// friction: a friction-state increment that PETSc's test on the whole vector
// accepts is refused, and every block is judged on its own size.
#include "cylinder_block.hpp"

#include "boomdyn/assembler.hpp"
#include "boomdyn/block_convergence.hpp"
#include "boomdyn/lugre_friction.hpp"
#include "boomdyn/model.hpp"
#include "boomdyn/scene_reader.hpp"
#include "boomdyn/sliding_joint.hpp"

#include <gtest/gtest.h>

using namespace boomdyn;

namespace {

const char *kScene = R"(
name: block-on-rail
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: rail, type: rigid, length: 40.0, section: {rhoA: 10.0}}
  - {name: block, type: rigid, length: 0.4, origin: [30.0, 0.0], section: {rhoA: 25.0}}
constraints:
  - {type: clamp, body: rail, at: start}
  - {type: sliding_joint, name: rear, body: block, at: start, track: rail, friction: {mu_s: 0.15, mu_c: 0.1, sigma0: 1.0e7}}
  - {type: sliding_joint, name: front, body: block, at: end, track: rail}
dynamic: {t_end: 1, dt: 1.0e-3}
)";

struct Fixture {
  Model model{parseScene(kScene, "block-on-rail.yaml")};
  Assembler assembler{model};
  Vec x = nullptr, dx = nullptr, F = nullptr;
  BlockConvergence blocks;
  PetscInt z = -1, slack = -1, multiplier = -1;
  Fixture()
  {
    EXPECT_EQ(assembler.setUp(PETSC_COMM_WORLD), 0);
    for (Vec *v : {&x, &dx, &F}) EXPECT_EQ(assembler.createVector(v), 0);
    EXPECT_EQ(blocks.setUp(model, x), 0);
    z = model.frictions().at(0)->stateIndex();
    slack = model.slidingJoints().at(0)->slackIndex();
    multiplier = model.numCoordinates();
  }
  ~Fixture()
  {
    for (Vec *v : {&x, &dx, &F}) VecDestroy(v);
  }
  // x: the model's initial coordinates, z = 1e-8 m, multipliers of 1e-2;
  // F: 1 everywhere at the first iterate.
  void start()
  {
    const std::vector<double> q0 = model.initialCoordinates();
    for (PetscInt i = 0; i < model.size(); ++i) VecSetValue(x, i, i < model.numCoordinates() ? q0[i] : 1e-2, INSERT_VALUES);
    VecSetValue(x, z, 1e-8, INSERT_VALUES);
    VecAssemblyBegin(x), VecAssemblyEnd(x);
    VecSet(F, 1.0);
    VecSet(dx, 0.0);
  }
  SNESConvergedReason test(PetscInt it)
  {
    SNESConvergedReason reason;
    EXPECT_EQ(blocks.test(it, x, dx, F, 1e-10, 1e-10, 1e-50, &reason), 0);
    return reason;
  }
  void setEntry(Vec v, PetscInt i, double value)
  {
    VecSetValue(v, i, value, INSERT_VALUES);
    VecAssemblyBegin(v), VecAssemblyEnd(v);
  }
};

} // namespace

TEST(BlockConvergence, RefusesAnUnconvergedFrictionStateThatTheWholeVectorTestAccepts)
{
  Fixture f;
  f.start();
  EXPECT_EQ(f.test(0), SNES_CONVERGED_ITERATING);
  // Residual not reduced; an increment of 1e-10 m in z only: 1 % of z, but
  // 3e-12 of |x| (PETSc's step test, stol 1e-10, accepts it).
  f.setEntry(f.dx, f.z, 1e-10);
  PetscReal xnorm, snorm;
  VecNorm(f.x, NORM_2, &xnorm);
  VecNorm(f.dx, NORM_2, &snorm);
  EXPECT_LT(snorm, 1e-10 * xnorm) << "the whole-vector test would have accepted this iterate";
  EXPECT_EQ(f.test(1), SNES_CONVERGED_ITERATING);
  EXPECT_EQ(f.blocks.lastHolder(), BlockConvergence::FirstOrderStates);
  EXPECT_EQ(f.blocks.lastHolderState(), "LuGre z of sliding_joint 'rear'");
  // An increment of 1e-19 m (1e-11 of z) is converged.
  f.setEntry(f.dx, f.z, 1e-19);
  EXPECT_EQ(f.test(2), SNES_CONVERGED_SNORM_RELATIVE);
}

TEST(BlockConvergence, JudgesMultipliersAndSlackOnTheirOwnSize)
{
  Fixture f;
  f.start();
  EXPECT_EQ(f.test(0), SNES_CONVERGED_ITERATING);
  // A multiplier increment of 4e-6 of the multipliers (1e-7 absolute,
  // 2e-9 of |x|): not converged.
  f.setEntry(f.dx, f.multiplier, 1e-7);
  EXPECT_EQ(f.test(1), SNES_CONVERGED_ITERATING);
  EXPECT_EQ(f.blocks.lastHolder(), BlockConvergence::Multipliers);
  // The next increment, 1e-10, is still 4e-9 of the block, but it
  // contracted by theta = 1e-3: the error left, theta/(1 - theta) |dx| ~ 1e-13,
  // is below 1e-10 of the block (2.6e-12). Converged.
  f.setEntry(f.dx, f.multiplier, 1e-10);
  EXPECT_EQ(f.test(2), SNES_CONVERGED_SNORM_RELATIVE);
  // A slack increment above 1e-10 of the slack coordinates is not.
  f.start();
  EXPECT_EQ(f.test(0), SNES_CONVERGED_ITERATING);
  f.setEntry(f.dx, f.slack, 1e-7);
  EXPECT_EQ(f.test(1), SNES_CONVERGED_ITERATING);
  EXPECT_EQ(f.blocks.lastHolder(), BlockConvergence::Slacks);
}

TEST(BlockConvergence, ResidualsReducedInEveryBlockConverge)
{
  Fixture f;
  f.start();
  EXPECT_EQ(f.test(0), SNES_CONVERGED_ITERATING);
  // Large increments everywhere, but every block's residual fell by 1e-11.
  VecSet(f.dx, 1.0);
  VecSet(f.F, 1e-11);
  EXPECT_EQ(f.test(1), SNES_CONVERGED_FNORM_RELATIVE);
  // One row not reduced enough: not converged.
  f.setEntry(f.F, f.z, 1e-9);
  EXPECT_EQ(f.test(1), SNES_CONVERGED_ITERATING);
  EXPECT_EQ(f.blocks.lastHolder(), BlockConvergence::FirstOrderStates);
  // A NaN anywhere ends the solve.
  f.setEntry(f.F, f.slack, std::nan(""));
  EXPECT_EQ(f.test(2), SNES_DIVERGED_FNORM_NAN);
}

// A hydraulic cylinder's states are named as what they are (their owner
// names them, Model::firstOrderNames()), not as friction states, and they
// are not frictional joints in the output's layout.
TEST(BlockConvergence, NamesACylinderPressureThatHolds)
{
  Model model(parseScene(boomdyn::testing::cylinder_block::scene("valve: closed, initial_pressure_piston: 1.0e+7", "{t_end: 1, dt: 1.0e-3}"),
                         "cylinder-block.yaml"));
  EXPECT_TRUE(model.frictionJointNames().empty());
  ASSERT_EQ(model.firstOrderNames().size(), 3u);
  EXPECT_EQ(model.firstOrderNames()[0], "piston pressure of hydraulic_cylinder 'lift'");
  EXPECT_EQ(model.firstOrderNames()[2], "stroke memory of hydraulic_cylinder 'lift'");
  Assembler assembler(model);
  ASSERT_EQ(assembler.setUp(PETSC_COMM_WORLD), 0);
  Vec x, dx, F;
  for (Vec *v : {&x, &dx, &F}) ASSERT_EQ(assembler.createVector(v), 0);
  ASSERT_EQ(assembler.initialState(x), 0);
  BlockConvergence blocks;
  ASSERT_EQ(blocks.setUp(model, x), 0);
  SNESConvergedReason reason;
  VecSet(F, 1.0);
  ASSERT_EQ(blocks.test(0, x, dx, F, 1e-10, 1e-10, 1e-50, &reason), 0);
  // 1 Pa on 100 bar (1e-7 of p1): a pressure that has not converged.
  const PetscInt p1 = model.firstOrderCoordinates()[0];
  VecSetValue(dx, p1, 1.0, INSERT_VALUES);
  VecAssemblyBegin(dx), VecAssemblyEnd(dx);
  ASSERT_EQ(blocks.test(1, x, dx, F, 1e-10, 1e-10, 1e-50, &reason), 0);
  EXPECT_EQ(reason, SNES_CONVERGED_ITERATING);
  EXPECT_EQ(blocks.lastHolder(), BlockConvergence::FirstOrderStates);
  EXPECT_EQ(blocks.lastHolderState(), "piston pressure of hydraulic_cylinder 'lift'");
  for (Vec *v : {&x, &dx, &F}) VecDestroy(v);
}
