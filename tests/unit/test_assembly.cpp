// The assembled Jacobian of the whole saddle-point system against central
// finite differences of the assembled residual, for every analysis mode
// (dynamic iteration matrix, static tangent, acceleration level), at a
// random deformed state with nonzero multipliers. Beams a and sled carry
// Kelvin-Voigt damping (its cV and cQ blocks), b none.
#include "boomdyn/assembler.hpp"
#include "boomdyn/scene_reader.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace boomdyn;

namespace {

const char *kScene = R"(
name: jacobian-check
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - name: a
    length: 1.0
    elements: 3
    section: {EA: 1.0e7, EI: 2.0e4, rhoA: 10.0, eta_axial: 1.0e-3, eta_bending: 5.0e-3}
  - name: b
    length: 0.8
    elements: 2
    origin: [1.0, 0.0]
    section: {EA: 5.0e6, EI: 1.0e4, rhoA: 8.0}
  - {name: rail, type: rigid, length: 1.5, origin: [0, -0.5], angle: 10, section: {rhoA: 4.0}}
  - {name: block, type: rigid, length: 0.3, origin: [0.49240387650610395, -0.41317591116653485], angle: 10, section: {rhoA: 6.0}}
  - name: sled
    length: 0.6
    elements: 2
    origin: [0.9, 0.0]
    section: {EA: 2.0e6, EI: 3.0e3, rhoA: 5.0, damping_ratio: 0.03, damping_frequency: 4.0}
constraints:
  - type: clamp
    body: a
    at: start
    angle: {type: sine, amplitude: 10, frequency: 0.5}
  - type: pin
    body: a
    at: end
    other: b
    other_at: 0.0
  - {type: clamp, body: rail, at: start}
  - type: sliding_joint
    name: rub
    body: block
    at: start
    track: rail
    friction: {mu_s: 0.3, mu_c: 0.2, v_s: 0.05, alpha: 2, sigma0: 1.0e4, sigma1: 30, sigma2: 2}
  - {type: sliding_joint, name: rub2, body: block, at: end, track: rail}
  - {type: clamp, body: sled, at: start}
  - type: sliding_joint
    name: beamrub
    body: b
    at: 0.1
    track: sled
    friction: {mu_s: 0.2, mu_c: 0.1, v_s: 0.01, alpha: 1.5, sigma0: 1.0e3, sigma1: 5}
loads:
  - type: point_force
    body: b
    at: 0.55
    force: [30, -200]
    scale: {type: ramp, t0: 0, t1: 1, from: 0, to: 1}
masses:
  - body: b
    at: end
    mass: 3.0
springs:
  - {body: a, at: 0.5, other: block, other_at: 0.1, stiffness: 300, damping: 2}
  - {body: b, at: 0.4, point: [1.2, 0.3], stiffness: 500, rest_length: 0.1, damping: 1}
dynamic: {t_end: 1.0, dt: 1.0e-3}
)";

// Dense copy of an assembled matrix (single rank, small).
Eigen::MatrixXd dense(Mat J, PetscInt n)
{
  Eigen::MatrixXd D(n, n);
  std::vector<PetscInt> idx(n);
  for (PetscInt i = 0; i < n; ++i) idx[i] = i;
  std::vector<PetscScalar> row(n);
  for (PetscInt i = 0; i < n; ++i) {
    PetscCallAbort(PETSC_COMM_SELF, MatGetValues(J, 1, &i, n, idx.data(), row.data()));
    for (PetscInt j = 0; j < n; ++j) D(i, j) = row[j];
  }
  return D;
}

Eigen::VectorXd values(Vec v)
{
  PetscInt n;
  const PetscScalar *a;
  PetscCallAbort(PETSC_COMM_SELF, VecGetSize(v, &n));
  PetscCallAbort(PETSC_COMM_SELF, VecGetArrayRead(v, &a));
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(a, n);
  PetscCallAbort(PETSC_COMM_SELF, VecRestoreArrayRead(v, &a));
  return out;
}

void setValues(Vec v, const Eigen::VectorXd &x)
{
  PetscScalar *a;
  PetscCallAbort(PETSC_COMM_SELF, VecGetArray(v, &a));
  for (Eigen::Index i = 0; i < x.size(); ++i) a[i] = x[i];
  PetscCallAbort(PETSC_COMM_SELF, VecRestoreArray(v, &a));
}

struct Mode {
  const char *name;
  Kinematics kin;
  bool accelerationLevel;
};

} // namespace

class AssembledJacobian : public ::testing::TestWithParam<Mode> {};

TEST_P(AssembledJacobian, MatchesCentralDifferencesOfResidual)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size > 1) GTEST_SKIP() << "dense comparison on one rank";
  const Mode mode = GetParam();
  Scene scene = parseScene(kScene, "jacobian-check.yaml");
  Model model(scene);
  Assembler assembler(model);
  ASSERT_EQ(assembler.setUp(PETSC_COMM_WORLD), 0);
  const PetscInt n = model.size();
  Vec x, F, qc, vc, ac;
  Mat J;
  for (Vec *v : {&x, &F, &qc, &vc, &ac}) ASSERT_EQ(assembler.createVector(v), 0);
  ASSERT_EQ(assembler.createMatrix(&J), 0);

  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd x0(n), q0 = Eigen::VectorXd::Zero(n);
  const std::vector<double> init = model.initialCoordinates();
  for (PetscInt i = 0; i < n; ++i) {
    q0[i] = i < model.numCoordinates() ? init[i] + 0.02 * u(rng) : 0.0;
    x0[i] = i < model.numCoordinates() ? q0[i] : 50.0 * u(rng); // multipliers
  }
  Eigen::VectorXd vcv(n), acv(n);
  for (PetscInt i = 0; i < n; ++i) vcv[i] = u(rng), acv[i] = 10 * u(rng);
  setValues(vc, vcv);
  setValues(ac, acv);
  setValues(qc, q0);
  AssemblyContext ctx;
  ctx.t = 0.3;
  ctx.kin = mode.kin;
  ctx.sigma = 7.0;
  ctx.loadFactor = 0.8;
  ctx.accelerationLevel = mode.accelerationLevel;
  ASSERT_EQ(assembler.setOffsets(mode.kin.cQ == 0 ? qc : nullptr, vc, ac), 0);
  if (mode.kin.cQ == 0) // acceleration level: x holds accelerations and multipliers
    for (PetscInt i = 0; i < model.numCoordinates(); ++i) x0[i] = 5 * u(rng);
  setValues(x, x0);
  ASSERT_EQ(assembler.evaluate(ctx, x, F, J), 0);
  const Eigen::MatrixXd Ja = dense(J, n);

  Eigen::MatrixXd Jfd(n, n);
  for (PetscInt j = 0; j < n; ++j) {
    // The acceleration-level residual is linear in x: a large step avoids round-off.
    const double h = (mode.accelerationLevel ? 1e-2 : 1e-6) * std::max(1.0, std::abs(x0[j]));
    Eigen::VectorXd xp = x0, xm = x0;
    xp[j] += h, xm[j] -= h;
    setValues(x, xp);
    ASSERT_EQ(assembler.evaluate(ctx, x, F, nullptr), 0);
    const Eigen::VectorXd fp = values(F);
    setValues(x, xm);
    ASSERT_EQ(assembler.evaluate(ctx, x, F, nullptr), 0);
    Jfd.col(j) = (fp - values(F)) / (2 * h);
  }
  const double err = (Ja - Jfd).norm() / Jfd.norm();
  EXPECT_LT(err, 1e-7) << mode.name;
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt j = 0; j < n; ++j)
      EXPECT_NEAR(Ja(i, j), Jfd(i, j), 1e-6 * Jfd.norm() / n) << mode.name << " entry " << i << "," << j;
  for (Vec *v : {&x, &F, &qc, &vc, &ac}) VecDestroy(v);
  MatDestroy(&J);
}

INSTANTIATE_TEST_SUITE_P(Modes, AssembledJacobian,
                         ::testing::Values(Mode{"dynamic", {1.0, 2e3, 4e6, 1e3}, false},
                                           Mode{"static", {1.0, 0.0, 0.0, 0.0}, false},
                                           Mode{"acceleration", {0.0, 0.0, 1.0, 0.0}, true}),
                         [](const auto &info) { return std::string(info.param.name); });
