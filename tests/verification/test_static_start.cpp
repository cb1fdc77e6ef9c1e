// dynamic.initial: static — a dynamic run that starts from the static
// equilibrium under its loads at t = 0 stays there: a cantilever under
// gravity and a tip load (moderately large deflection) keeps its tip still
// to 1e-9 m over 1 s, at the static solution to 1e-10 m.
#include "boomdyn/scene_reader.hpp"
#include "support.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

std::string cantilever(const std::string &analysis)
{
  return R"(
name: static-start
analysis: )" + analysis + R"(
gravity: [0, -9.81]
bodies:
  - {name: boom, length: 1.0, elements: 8, section: {EA: 1.0e7, EI: 1.0e3, rhoA: 5.0}}
constraints:
  - {type: clamp, body: boom, at: start}
loads:
  - {type: point_force, body: boom, at: end, force: [0, -500]}
output:
  sensors:
    - {name: tip, body: boom, at: end}
)";
}

} // namespace

TEST(StaticStart, CantileverUnderLoadStaysAtRest)
{
  const StaticOutcome statics = runStatic(parseScene(cantilever("static"), "static.yaml"), PETSC_COMM_SELF);
  ASSERT_TRUE(statics.converged);
  const Vec2 equilibrium = statics.sensors[0].position;
  const Scene scene = parseScene(cantilever("dynamic") + "dynamic: {t_end: 1.0, dt: 1.0e-3, initial: static}\n",
                                 "dynamic.yaml");
  ASSERT_TRUE(scene.dynamic.startStatic);
  const DynamicHistory h = runDynamic(scene, PETSC_COMM_SELF);
  ASSERT_TRUE(h.summary.completed) << h.summary.failure;
  double motion = 0, offStatic = 0, speed = 0;
  for (std::size_t k = 0; k < h.time.size(); ++k) {
    motion = std::max(motion, (h.sensors[k][0].position - h.sensors[0][0].position).norm());
    offStatic = std::max(offStatic, (h.sensors[k][0].position - equilibrium).norm());
    speed = std::max(speed, h.sensors[k][0].velocity.norm());
  }
  PetscPrintf(PETSC_COMM_SELF,
              "  static start: tip deflection %.4f m; over 1 s tip motion %.2e m, distance from the static solution "
              "%.2e m, speed %.2e m/s\n",
              -equilibrium.y(), motion, offStatic, speed);
  EXPECT_GT(-equilibrium.y(), 0.1); // a real deflection (P L^3 / 3 EI = 0.17 m linear)
  EXPECT_LT(motion, 1e-9);
  EXPECT_LT(offStatic, 1e-10);
}
