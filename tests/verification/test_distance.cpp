// The distance constraint end to end: scene text -> registry -> Model ->
// static solution -> its output channel. A beam pinned at its start and held
// at its end by a vertical link carries half its weight in the link.
#include "boomdyn/assembler.hpp"
#include "boomdyn/model.hpp"
#include "boomdyn/scene_reader.hpp"
#include "boomdyn/sensors.hpp"
#include "boomdyn/static_solver.hpp"

#include <gtest/gtest.h>

using namespace boomdyn;

TEST(DistanceConstraint, VerticalLinkCarriesHalfTheWeightOfAPinnedBeam)
{
  const Scene scene = parseScene(R"(name: stayed_beam
analysis: static
gravity: [0, -9.81]
bodies:
  - {name: beam, length: 2, elements: 8, section: {EA: 1.0e10, EI: 1.0e8, rhoA: 30}}
constraints:
  - {type: pin, body: beam, at: start}
  - {type: distance, name: stay, body: beam, at: end, point: [2, 1]}
static: {load_steps: 2}
)",
                                 "stayed_beam.yaml");
  Model model(scene);
  ASSERT_EQ(model.numMultipliers(), 3); // pin: 2 rows, stay: 1 row
  ASSERT_EQ(model.outputChannels().size(), 1u);
  const OutputChannel &tension = model.outputChannels()[0];
  EXPECT_EQ(tension.group, "distance");
  EXPECT_EQ(tension.name, "stay");
  EXPECT_EQ(tension.index, 2);

  Assembler assembler(model);
  ASSERT_EQ(assembler.setUp(PETSC_COMM_WORLD), 0);
  Vec x;
  ASSERT_EQ(assembler.createVector(&x), 0);
  ASSERT_EQ(assembler.initialState(x), 0);
  StaticSolver solver(assembler);
  ASSERT_EQ(solver.setUp(), 0);
  PetscBool converged = PETSC_FALSE;
  ASSERT_EQ(solver.solve(scene.statics.time, scene.statics.load_steps, x, nullptr, &converged), 0);
  ASSERT_TRUE(converged);
  SensorProbe probe(model);
  ASSERT_EQ(probe.setUp(x), 0);
  std::vector<double> slacks, multipliers;
  ASSERT_EQ(probe.readJoints(x, solver.multipliers(), slacks, multipliers), 0);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) {
    // Moments about the pin: T L = W L / 2 (the sag of a stiff beam moves
    // the centre of mass and the link by far less than 1e-6 relative).
    const double weight = 30 * 2 * 9.81;
    EXPECT_NEAR(tension.factor * multipliers.at(tension.index), weight / 2, 1e-6 * weight);
  }
  VecDestroy(&x);
}
