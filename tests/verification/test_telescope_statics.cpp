// Static telescopic cantilever (the paper's three booms, retracted and fully
// extended) under gravity and a small tip load, against an independent
// reference written here: each boom a linear Euler-Bernoulli beam with exact
// Hermite elements, the booms coupled at the four pads by equal transverse
// displacement (the linearized normal condition of a frictionless sliding
// joint), all solved in one dense direct solve with Lagrange multipliers.
#include "support.hpp"
#include "telescope_reference.hpp"


#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

const double kA[3] = {6.944e-3, 5.264e-3, 3.816e-3}, kI[3] = {6.395214e-5, 3.720306e-5, 1.986431e-5};

// Tip deflection (y of boom 3's end) of the linear pad-coupled reference.
double referenceTipDeflection(const double x0[3])
{
  TelescopeReference ref;
  ref.tipLoad = 100.0;
  std::copy(x0, x0 + 3, ref.x0);
  return ref.tipDeflection();
}

std::string number(double v)
{
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", v); // std::to_string would print 6.395214e-5 as 0.000064
  return buf;
}

Scene telescope(const double x0[3])
{
  std::string s = "name: telescope-static\nanalysis: static\ngravity: [0, -9.81]\nbodies:\n";
  for (int b = 0; b < 3; ++b)
    s += "  - {name: boom" + std::to_string(b + 1) + ", length: 2.0, elements: 16, origin: [" + number(x0[b]) +
         ", 0], section: {E: 2.1e11, rho: 7850, A: " + number(kA[b]) + ", I: " + number(kI[b]) + "}}\n";
  s += R"(constraints:
  - {type: clamp, name: base, body: boom1, at: start}
  - {type: sliding_joint, name: j1, body: boom1, at: end, track: boom2}
  - {type: sliding_joint, name: j2, body: boom2, at: start, track: boom1}
  - {type: sliding_joint, name: j3, body: boom2, at: end, track: boom3}
  - {type: sliding_joint, name: j4, body: boom3, at: start, track: boom2}
  - {type: extraction_drive, name: extraction, joint: j2, displacement: 0}
  - {type: rope, name: rope, from: boom1, from_at: start, pulley: boom2, pulley_at: end, to: boom3, to_at: start}
loads:
  - {type: point_force, name: tip_load, body: boom3, at: end, force: [0, -100]}
static: {load_steps: 1}
output:
  sensors:
    - {name: tip, body: boom3, at: end}
)";
  return parseScene(s, "telescope-static.yaml");
}

} // namespace

class TelescopeStatics : public ::testing::TestWithParam<bool> {};

TEST_P(TelescopeStatics, TipDeflectionMatchesPadCoupledBeams)
{
  const bool extended = GetParam();
  const double retracted[3] = {0.0, 0.25, 0.5}, full[3] = {0.0, 1.5, 3.0};
  const double *x0 = extended ? full : retracted;
  const double reference = referenceTipDeflection(x0);
  const StaticOutcome out = runStatic(telescope(x0));
  ASSERT_TRUE(out.converged);
  double model = out.sensors.empty() ? 0.0 : out.sensors[0].position.y();
  MPI_Bcast(&model, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  const double rel = std::abs(model - reference) / std::abs(reference);
  PetscPrintf(PETSC_COMM_WORLD, "  telescope %s: tip deflection %.6e m, pad-coupled beams %.6e m, relative difference %.2e\n",
              extended ? "extended " : "retracted", model, reference, rel);
  EXPECT_LT(rel, 1e-3);
  EXPECT_LT(out.violation, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Configurations, TelescopeStatics, ::testing::Values(false, true),
                         [](const auto &info) { return std::string(info.param ? "Extended" : "Retracted"); });
