#include "boomdyn/generalized_alpha.hpp"

#include "boomdyn/direct_solver.hpp"
#include "boomdyn/lanes.hpp"
#include "boomdyn/log_events.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace boomdyn {

namespace {
std::string timeText(double t)
{
  std::ostringstream os;
  os << t;
  return os.str();
}
} // namespace

AlphaParameters AlphaParameters::fromRhoInf(double rho)
{
  AlphaParameters p;
  p.alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
  p.alpha_f = rho / (rho + 1.0);
  p.gamma = 0.5 - p.alpha_m + p.alpha_f;
  p.beta = 0.25 * (p.gamma + 0.5) * (p.gamma + 0.5);
  return p;
}

PetscErrorCode GeneralizedAlpha::setUp(PetscInt maxNewton)
{
  PetscFunctionBeginUser;
  for (PetscHandle<Vec> *v : {&q_, &v_, &qdd_, &a_, &lambda_, &x_, &qp_, &vc_, &ac_, &zero_, &shift_, &impulse_, &reported_})
    PetscCall(assembler_.createVector(v->address()));
  // Spatial models iterate with full Newton by default: with a kept matrix
  // the Euler parameters' equations (inertia of size J, far below the
  // translational masses) converged slowly without the residual norm
  // noticing, and a gyroscope spinning at 100 rad/s fell over (measured;
  // full Newton: 2-3 iterations a step at h = 2 ms).
  PetscCall(newton_.setUp(assembler_, nullptr, maxNewton, assembler_.model().scene().dimension == 2));
  accelerationRestart_ =
      assembler_.model().scene().dimension == 3 && std::abs(params_.alpha_m - params_.alpha_f) < 1e-12;
  maxNewton_ = maxNewton;
  PetscCall(sliders_.setUp(x_));
  breakpoints_.clear();
  for (const ConstraintItem *c : assembler_.model().constraints()) {
    hasDrives_ = hasDrives_ || c->constraint().dependsOnTime();
    c->constraint().velocityBreakpoints(breakpoints_);
  }
  driveKinks_ = breakpoints_;
  std::sort(driveKinks_.begin(), driveKinks_.end());
  // A drive's acceleration jump: the index-3 multipliers would carry the
  // jump's error in the algorithmic accelerations for many steps (forever at
  // rho_inf = 1); landing on it and restarting with consistent
  // accelerations removes it (docs/model.md §4.8). No velocity projection there.
  for (const ConstraintItem *c : assembler_.model().constraints()) c->constraint().accelerationBreakpoints(breakpoints_);
  for (const auto &item : assembler_.model().items()) item->breakpoints(breakpoints_); // winches, releases
  std::sort(breakpoints_.begin(), breakpoints_.end());
  breakpoints_.erase(std::unique(breakpoints_.begin(), breakpoints_.end()), breakpoints_.end());
  PetscReal stiffness;
  PetscCall(assembler_.characteristicScales(zero_, &massScale_, &stiffness));
  if (massScale_ <= 0) massScale_ = 1.0;
  PetscFunctionReturn(0);
}

// Applies op(local index, q_n, vc, x) to the owned first-order entries.
template <class Op>
PetscErrorCode GeneralizedAlpha::forFirstOrder(Op op)
{
  PetscInt lo, hi;
  const PetscScalar *q;
  PetscScalar *vc, *x;
  PetscFunctionBeginUser;
  if (assembler_.model().firstOrderCoordinates().empty()) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(q_, &lo, &hi));
  PetscCall(VecGetArrayRead(q_, &q));
  PetscCall(VecGetArray(vc_, &vc));
  PetscCall(VecGetArray(x_, &x));
  for (PetscInt g : assembler_.model().firstOrderCoordinates())
    if (g >= lo && g < hi) op(g - lo, q, vc, x);
  PetscCall(VecRestoreArray(x_, &x));
  PetscCall(VecRestoreArray(vc_, &vc));
  PetscCall(VecRestoreArrayRead(q_, &q));
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlpha::initialize(double t0, Vec q0, Vec v0)
{
  PetscFunctionBeginUser;
  t_ = t0;
  impulseWork_ = 0;
  PetscCall(VecCopy(q0, q_));
  PetscCall(VecCopy(v0, v_));
  PetscCall(VecSet(impulse_, 0.0));
  // A drive that moves at t0 (a ramp starting at 0) needs velocities that
  // follow it: the same projection as at a kink.
  if (kinkRestart_ && hasDrives_) PetscCall(projectVelocities());
  PetscCall(consistentAccelerations());
  PetscCall(VecCopy(lambda_, reported_));
  PetscFunctionReturn(0);
}

// The matrix [M C_q^T; C_q 0] at t_ in x = [qdd | lambda_hat]
// (consistent accelerations), or with velocity-level constraint rows
// C_q v + C_t in x = [dv | P_hat] (the impulsive projection at a kink).
void GeneralizedAlpha::setAccelerationLevelContext(NewtonSolver &solver, bool velocityLevel)
{
  solver.ctx = AssemblyContext{};
  solver.ctx.t = t_;
  solver.ctx.kin = {0.0, 0.0, 1.0};
  solver.ctx.sigma = massScale_;
  solver.ctx.accelerationLevel = true;
  solver.ctx.velocityLevel = velocityLevel;
  solver.ctx.rightLimit = true; // the state at t_ has passed any jump at t_ (a released mass is gone)
}

// The index-3 multipliers of a step are those of its algorithmic
// accelerations: M qdd_{n+1} + C_q^T lambda_{n+1} = Q with qdd_{n+1} from
// the recursion of §4.2, which follows a prescribed acceleration only with
// an error that alternates in sign from step to step (its spurious root,
// -rho_inf per step): every jump of a drive's acceleration excites it (a
// rigid block on a trapezoidal profile: up to 2 m a, never decaying at
// rho_inf = 1), and a drive whose acceleration varies (an S-curve's jerk
// phases) keeps it at O(h). The acceleration-level equations at the step's
// (t, q, v, z) give the multipliers of that state instead, exact for a
// prescribed rigid motion and as accurate as q and v otherwise
// (docs/model.md §4.8). Its own solver: the step's kept factorization stays
// valid. The solve starts from zero with a fresh matrix and ends on the
// Newton tolerances, so the reported values depend on the state alone
// (restarts report the same).
PetscErrorCode GeneralizedAlpha::reportMultipliers()
{
  PetscInt its;
  SNESConvergedReason reason;
  PetscFunctionBeginUser;
  if (!consistentMultipliers_) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(logEvents().multipliers, 0, 0, 0, 0));
  // Its own matrix, only in runs that report this way; full Newton (a fresh
  // factorization per solve): with the matrix kept from the last step the
  // block test accepted drive forces 23-36 % off on a LuGre block at
  // 2e-4 and 3e-3 m/s (LuGre.SteadySliding*); fresh, 1e-11.
  if (!reportSolverReady_) {
    PetscCall(reportSolver_.setUp(assembler_, nullptr, maxNewton_, false));
    reportSolverReady_ = true;
  }
  setAccelerationLevelContext(reportSolver_, false);
  PetscCall(assembler_.setOffsets(q_, v_, nullptr));
  PetscCall(VecSet(x_, 0.0));
  PetscCall(reportSolver_.solve(x_, &its, &reason));
  if (reason <= 0)
    throw std::runtime_error(std::string("the multipliers at t = ") + timeText(t_) +
                             " s could not be solved from the acceleration-level equations (" +
                             SNESConvergedReasons[reason] +
                             "); -boom_consistent_multipliers 0 reports the step's own (index-3) multipliers");
  PetscCall(VecSet(reported_, 0.0));
  PetscCall(assembler_.copyMultipliers(x_, reported_, massScale_));
  PetscCall(PetscLogEventEnd(logEvents().multipliers, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlpha::consistentAccelerations()
{
  PetscInt its;
  SNESConvergedReason reason;
  PetscFunctionBeginUser;
  // Acceleration-level system [M C_q^T; C_q 0] [qdd; lambda] = [Q; -gamma]:
  // linear in x = [qdd | lambda_hat], so one Newton step solves it.
  setAccelerationLevelContext(newton_, false);
  PetscCall(assembler_.setOffsets(q_, v_, nullptr));
  PetscCall(VecSet(x_, 0.0));
  PetscCall(newton_.solve(x_, &its, &reason));
  if (reason <= 0)
    throw std::runtime_error(std::string("the equations of motion are singular at t = ") + timeText(t_) + " s (" +
                             SNESConvergedReasons[reason] +
                             "): a body or a motion without support, or redundant or contradictory constraints "
                             "(two drives on one joint, a clamp plus an angle drive at the same point, ...)");
  PetscCall(VecCopy(x_, qdd_));
  PetscCall(VecCopy(x_, a_));
  // Consistent accelerations after a start or a load jump carry the stiff
  // modes' transients (see advance()): the first step predicts without them,
  // and starts from a filtered a (filterStartAcceleration).
  predictWithAcceleration_ = false;
  startPending_ = filteredStart_;
  PetscCall(VecSet(lambda_, 0.0));
  PetscCall(assembler_.copyMultipliers(x_, lambda_, massScale_));
  PetscFunctionReturn(0);
}

// Impulsive step at t_ (docs/model.md §4.8): unknowns x = [dv | P_hat],
//   M dv + C_q^T P + f_fric(P) = 0,   C_q (v + dv) + C_t = 0,
// P = sigma P_hat. The acceleration-level residual with velocity-level
// constraint rows is R(x) = [M dv - Q(q, v) + C_q^T P + f_fric(P); C_q (v + dv) + C_t];
// subtracting its coordinate rows at x = 0 removes the finite forces Q, so
// only the impulses act. The step is frictionless (LuGreFriction adds no
// force at velocity level; z is left as it is): friction acts through the
// finite forces before and after. The linear system is the matrix of the
// consistent-acceleration solve, so one Newton iteration solves it. A
// Coulomb impulse g |P_n| bounded by stick was tried: Newton on its
// regularized sign law stalled on the study scene (docs/model.md §4.8).
PetscErrorCode GeneralizedAlpha::projectVelocities()
{
  PetscInt its;
  SNESConvergedReason reason;
  PetscReal violation, initialResidual;
  PetscFunctionBeginUser;
  setAccelerationLevelContext(newton_, true);
  PetscCall(assembler_.setOffsets(q_, v_, nullptr));
  PetscCall(VecSet(x_, 0.0));
  PetscCall(assembler_.evaluate(newton_.ctx, x_, shift_, nullptr));
  // The velocity-level constraint rows stay in the residual: C_q v + C_t.
  PetscCall(VecCopy(shift_, impulse_));
  PetscCall(assembler_.copyMultipliers(zero_, shift_, 0.0));
  PetscCall(VecAXPY(impulse_, -1.0, shift_));
  PetscCall(VecNorm(impulse_, NORM_INFINITY, &violation));
  PetscCall(VecNorm(impulse_, NORM_2, &initialResidual));
  PetscCall(VecSet(impulse_, 0.0));
  if (violation == 0) PetscFunctionReturn(0); // consistent: nothing to project
  newton_.residualShift = shift_;
  PetscErrorCode ierr = newton_.solve(x_, &its, &reason);
  newton_.residualShift = nullptr;
  PetscCall(ierr);
  // The system is linear, and its coordinate rows start at zero residual, so
  // the block test (block_convergence.cpp) can stop them only by the size of
  // the increment, which the solve's round-off can keep above 1e-10 relative
  // (stick-slip scene at h = 5e-4 s: increments 2e-10, residual 2e-13 after
  // the first iteration against 0.21 at the start). What decides is the
  // residual: the relative test of the SNES tolerance on the whole system.
  // Not in BlockConvergence itself: there a block that starts at zero
  // residual (LuGre states at rest, a coordinate block in a step) must
  // converge by its increment, since a relative test on zero cannot pass.
  if (reason <= 0) {
    PetscReal rtol, atol, stol, finalResidual;
    PetscInt maxIt, maxF;
    PetscCall(SNESGetTolerances(newton_.snes(), &atol, &rtol, &stol, &maxIt, &maxF));
    PetscCall(newton_.lastFunctionNorm(&finalResidual));
    if (std::isfinite(finalResidual) && finalResidual <= rtol * initialResidual) reason = SNES_CONVERGED_FNORM_RELATIVE;
  }
  if (reason <= 0)
    throw std::runtime_error(std::string("the velocity projection at the drive kink t = ") + timeText(t_) +
                             " s did not converge (" + SNESConvergedReasons[reason] + ")");
  PetscCall(assembler_.copyMultipliers(x_, impulse_, massScale_));
  // v += dv on the coordinates (the multiplier entries of x are P_hat); the
  // kinetic energy it adds is the impulses' work (q does not move).
  EnergyParts before, after;
  PetscCall(diagnostics(&before, &violation));
  PetscCall(assembler_.copyMultipliers(zero_, x_, 0.0));
  PetscCall(VecAXPY(v_, 1.0, x_));
  PetscCall(diagnostics(&after, &violation));
  impulseWork_ += after.kinetic - before.kinetic;
  PetscFunctionReturn(0);
}

double GeneralizedAlpha::nextBreakpoint() const
{
  if (!kinkRestart_) return std::numeric_limits<double>::infinity();
  const auto next = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), t_);
  return next == breakpoints_.end() ? std::numeric_limits<double>::infinity() : *next;
}

PetscErrorCode GeneralizedAlpha::stepToBreakpoint(StepResult *result)
{
  PetscFunctionBeginUser;
  const double tb = nextBreakpoint();
  PetscCheck(std::isfinite(tb), assembler_.comm(), PETSC_ERR_ORDER, "stepToBreakpoint: no breakpoint after t = %g s",
             t_);
  PetscCall(advance(tb - t_, tb, result));
  if (!result->converged) PetscFunctionReturn(0);
  // Items whose value jumps at tb (a released mass) change the energy at
  // fixed q and v: the energy they take out (or bring in) counts as the
  // work of the event, like the drives' impulses below.
  EnergyParts left, right;
  PetscReal violation;
  PetscCall(diagnostics(&left, &violation, false));
  PetscCall(diagnostics(&right, &violation, true));
  impulseWork_ += (right.kinetic + right.strain + right.potential) - (left.kinetic + left.strain + left.potential);
  // The velocity projection only where a drive's rate jumps: at the
  // breakpoints of force elements no constraint changes, and the
  // velocities are as consistent as after any step (projecting their
  // round-off-level violation is a solve that cannot meet its tolerances).
  if (std::binary_search(driveKinks_.begin(), driveKinks_.end(), tb)) PetscCall(projectVelocities());
  PetscCall(consistentAccelerations());
  PetscCall(VecCopy(lambda_, reported_)); // right limits, consistent by construction
  result->restarted = true;
  PetscFunctionReturn(0);
}

namespace {

struct PredictorCoefficients {
  double h, cA, am, af, mBetaP, cV, mGammaP, halfH2;
};

// GeneralizedAlpha::predict's loop; the vectors do not overlap (restrict:
// vectorized), the two branches taken outside the loop.
template <bool AmOne, bool WithA>
void predictEntries(PetscInt n, const PredictorCoefficients c, const double *__restrict q, const double *__restrict v,
                    const double *__restrict a, const double *__restrict qdd, double *__restrict qp,
                    double *__restrict ac, double *__restrict vc, double *__restrict x)
{
  for (PetscInt i = 0; i < n; ++i) {
    const double qpi = c.h * v[i] + c.cA * a[i] + q[i];
    qp[i] = qpi;
    const double acPart = AmOne ? a[i] + c.af * qdd[i] + 0.0 * ac[i] : c.am * a[i] + c.af * qdd[i];
    ac[i] = acPart + c.mBetaP * qpi;
    vc[i] = c.cV * a[i] + c.mGammaP * qpi + v[i];
    double xi = q[i] + c.h * v[i];
    if (WithA) xi = xi + c.halfH2 * a[i];
    x[i] = xi;
  }
}

// The largest of m and |d| lane by lane, as std::max(m, std::abs(d)): |d|
// only where it is larger (a NaN is passed over; a zero's sign does not
// matter, the maxima start at +0 and take only larger values).
inline lanes::Lanes4 absMax(lanes::Lanes4 m, lanes::Lanes4 d)
{
  const lanes::Lanes4 zero{};
  const lanes::Lanes4 ad = d < zero ? -d : d;
  return ad > m ? ad : m;
}

// GeneralizedAlpha::estimateAndUpdate's update of entries [begin, end),
// with the estimate's maxima of the same entries first if Estimate (four
// entries at a time: the maximum of a set does not depend on the order in
// which it is taken).
template <bool Estimate>
void updateEntries(PetscInt begin, PetscInt end, double h, double h2b, double betaP, double gammaP,
                   const double *__restrict x, const double *__restrict qp, const double *__restrict ac,
                   const double *__restrict vc, double *__restrict a, double *__restrict q, double *__restrict v,
                   double *__restrict qdd, double largest[3])
{
  using lanes::Lanes4;
  const double s = 1.0 / h2b;
  PetscInt i = begin;
  Lanes4 m0{}, m1{}, m2{};
  if (Estimate)
    for (; i + 4 <= end; i += 4) {
      const Lanes4 xi = lanes::load(x + i), qpi = lanes::load(qp + i), ai = lanes::load(a + i);
      m0 = absMax(m0, (xi - qpi) / h2b - ai);
      const Lanes4 fromVelocity = xi - lanes::load(q + i) - h * lanes::load(v + i);
      m1 = absMax(m1, fromVelocity);
      m2 = absMax(m2, fromVelocity - 0.5 * h * h * ai);
      lanes::store(a + i, s * (xi - qpi));
      lanes::store(qdd + i, lanes::load(ac + i) + betaP * xi);
      lanes::store(v + i, lanes::load(vc + i) + gammaP * xi);
      lanes::store(q + i, xi);
    }
  double l0 = 0, l1 = 0, l2 = 0;
  for (; i < end; ++i) {
    const double xi = x[i];
    if (Estimate) {
      l0 = std::max(l0, std::abs((xi - qp[i]) / h2b - a[i]));
      const double fromVelocity = xi - q[i] - h * v[i];
      l1 = std::max(l1, std::abs(fromVelocity));
      l2 = std::max(l2, std::abs(fromVelocity - 0.5 * h * h * a[i]));
    }
    a[i] = s * (xi - qp[i]);
    qdd[i] = ac[i] + betaP * xi;
    v[i] = vc[i] + gammaP * xi;
    q[i] = xi;
  }
  if (Estimate) {
    for (int k = 0; k < lanes::kWidth; ++k) l0 = std::max(l0, m0[k]), l1 = std::max(l1, m1[k]), l2 = std::max(l2, m2[k]);
    largest[0] = l0, largest[1] = l1, largest[2] = l2;
  }
}

} // namespace

// The step's predictor in one pass over the owned entries: qp, ac, vc and
// the first iterate x, entry by entry the operations (and the order of
// the sums) of the PETSc calls this replaced, so the same bits (PETSc's
// VecAXPBYPCZ, VecWAXPY and VecAXPY each compute z = a x + b y + c z etc.
// left to right; VecAXPBYPCZ with alpha = 1 adds gamma z even for gamma =
// 0, which only differs in the sign of a zero, kept too). The eight
// passes over vectors of the whole state (reading q, v, a, qdd up to
// three times each) were memory-bound on the 10^5-element boom.
PetscErrorCode GeneralizedAlpha::predict(double h, double betaP, double gammaP, double sigma)
{
  const AlphaParameters &p = params_;
  PetscInt lo, n;
  const PetscScalar *q, *v, *a, *qdd, *lambda;
  PetscScalar *qp, *ac, *vc, *x;
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(x_, &lo, nullptr));
  PetscCall(VecGetLocalSize(x_, &n));
  PetscCall(VecGetArrayRead(q_, &q));
  PetscCall(VecGetArrayRead(v_, &v));
  PetscCall(VecGetArrayRead(a_, &a));
  PetscCall(VecGetArrayRead(qdd_, &qdd));
  PetscCall(VecGetArrayRead(lambda_, &lambda));
  PetscCall(VecGetArray(qp_, &qp));
  PetscCall(VecGetArray(ac_, &ac));
  PetscCall(VecGetArray(vc_, &vc));
  PetscCall(VecGetArray(x_, &x));
  // qp = q + h v + h^2 (1/2 - beta) a: VecCopy(q, qp), VecAXPBYPCZ(qp, h, cA, 1, v, a).
  const double cA = h * h * (0.5 - p.beta);
  // ac = (alpha_m a - alpha_f qdd)/(1 - alpha_f) - beta' qp:
  // VecAXPBYPCZ(ac, am, af, 0, a, qdd), VecAXPY(ac, -beta', qp).
  const double am = p.alpha_m / (1.0 - p.alpha_f), af = -p.alpha_f / (1.0 - p.alpha_f), mBetaP = -betaP;
  const bool amOne = am == 1.0; // VecAXPBYPCZ's alpha = 1 branch (rho_inf = 1)
  // vc = v + h (1 - gamma) a - gamma' qp: VecCopy(v, vc), VecAXPBYPCZ(vc, cV, -gamma', 1, a, qp).
  const double cV = h * (1.0 - p.gamma), mGammaP = -gammaP;
  // x = q + h v (VecWAXPY(x, h, v, q)), + h^2/2 a (VecAXPY) with the acceleration predictor.
  const double halfH2 = 0.5 * h * h;
  const bool withA = predictWithAcceleration_;
  const PredictorCoefficients c{h, cA, am, af, mBetaP, cV, mGammaP, halfH2};
  if (amOne) {
    if (withA) predictEntries<true, true>(n, c, q, v, a, qdd, qp, ac, vc, x);
    else predictEntries<true, false>(n, c, q, v, a, qdd, qp, ac, vc, x);
  } else {
    if (withA) predictEntries<false, true>(n, c, q, v, a, qdd, qp, ac, vc, x);
    else predictEntries<false, false>(n, c, q, v, a, qdd, qp, ac, vc, x);
  }
  // The multipliers' entries of x: the last step's, scaled (copyMultipliers(lambda, x, 1/sigma)).
  const double scale = 1.0 / sigma;
  for (PetscInt i = std::max<PetscInt>(0, assembler_.model().numCoordinates() - lo); i < n; ++i) x[i] = scale * lambda[i];
  PetscCall(VecRestoreArray(x_, &x));
  PetscCall(VecRestoreArray(vc_, &vc));
  PetscCall(VecRestoreArray(ac_, &ac));
  PetscCall(VecRestoreArray(qp_, &qp));
  PetscCall(VecRestoreArrayRead(lambda_, &lambda));
  PetscCall(VecRestoreArrayRead(qdd_, &qdd));
  PetscCall(VecRestoreArrayRead(a_, &a));
  PetscCall(VecRestoreArrayRead(v_, &v));
  PetscCall(VecRestoreArrayRead(q_, &q));
  PetscFunctionReturn(0);
}

// After a converged solve: the local error estimate's maxima (largest, on
// this rank's coordinates, if not null) and, if update, the new state
// a = (x - qp)/(h^2 beta), qdd = ac + beta' x, v = vc + gamma' x, q = x,
// lambda = sigma x on the multipliers, first-order states by backward
// Euler -- in one pass, each entry's estimate read before its update. The
// same operations as the PETSc calls they replaced (VecWAXPY(a, -1, qp,
// x), VecScale(a, 1/(h^2 beta)), VecWAXPY(qdd, beta', x, ac), VecWAXPY(v,
// gamma', x, vc), VecCopy(x, q), copyMultipliers(x, lambda, sigma)).
PetscErrorCode GeneralizedAlpha::estimateAndUpdate(double h, double betaP, double gammaP, double sigma, bool update,
                                                   double *largest)
{
  const AlphaParameters &p = params_;
  PetscInt begin, end, lo, hi;
  const PetscScalar *x, *qp, *ac, *vc;
  PetscScalar *a, *q, *v, *qdd = nullptr, *lambda = nullptr;
  PetscFunctionBeginUser;
  const double h2b = h * h * p.beta;
  PetscCall(assembler_.coordinateRange(&begin, &end));
  PetscCall(VecGetOwnershipRange(x_, &lo, &hi));
  PetscCall(VecGetArrayRead(x_, &x));
  PetscCall(VecGetArrayRead(qp_, &qp));
  PetscCall(VecGetArrayRead(ac_, &ac));
  PetscCall(VecGetArrayRead(vc_, &vc));
  // Write access only when updating (the state's object state stays as it is otherwise).
  if (update) {
    PetscCall(VecGetArray(a_, &a));
    PetscCall(VecGetArray(q_, &q));
    PetscCall(VecGetArray(v_, &v));
    PetscCall(VecGetArray(qdd_, &qdd));
    PetscCall(VecGetArray(lambda_, &lambda));
  } else {
    PetscCall(VecGetArrayRead(a_, const_cast<const PetscScalar **>(&a)));
    PetscCall(VecGetArrayRead(q_, const_cast<const PetscScalar **>(&q)));
    PetscCall(VecGetArrayRead(v_, const_cast<const PetscScalar **>(&v)));
  }
  // First-order states' q_n, read before the pass overwrites q.
  firstOrderQ_.clear();
  if (update)
    for (PetscInt g : assembler_.model().firstOrderCoordinates())
      if (g >= lo && g < hi) firstOrderQ_.push_back(q[g - lo]);
  const PetscInt n = hi - lo, cb = begin - lo, ce = std::max(begin, end) - lo;
  if (update) {
    updateEntries<false>(0, cb, h, h2b, betaP, gammaP, x, qp, ac, vc, a, q, v, qdd, nullptr);
    if (largest) updateEntries<true>(cb, ce, h, h2b, betaP, gammaP, x, qp, ac, vc, a, q, v, qdd, largest);
    else updateEntries<false>(cb, ce, h, h2b, betaP, gammaP, x, qp, ac, vc, a, q, v, qdd, nullptr);
    updateEntries<false>(ce, n, h, h2b, betaP, gammaP, x, qp, ac, vc, a, q, v, qdd, nullptr);
    for (PetscInt i = std::max<PetscInt>(0, assembler_.model().numCoordinates() - lo); i < n; ++i) lambda[i] = sigma * x[i];
    // First-order states: rate from backward Euler; no accelerations.
    std::size_t k = 0;
    for (PetscInt g : assembler_.model().firstOrderCoordinates())
      if (g >= lo && g < hi) {
        const PetscInt i = g - lo;
        v[i] = (x[i] - firstOrderQ_[k++]) / h;
        a[i] = qdd[i] = 0.0;
      }
  } else if (largest) {
    double l0 = 0, l1 = 0, l2 = 0;
    for (PetscInt i = cb; i < ce; ++i) {
      l0 = std::max(l0, std::abs((x[i] - qp[i]) / h2b - a[i]));
      const double fromVelocity = x[i] - q[i] - h * v[i];
      l1 = std::max(l1, std::abs(fromVelocity));
      l2 = std::max(l2, std::abs(fromVelocity - 0.5 * h * h * a[i]));
    }
    largest[0] = l0, largest[1] = l1, largest[2] = l2;
  }
  if (update) {
    PetscCall(VecRestoreArray(lambda_, &lambda));
    PetscCall(VecRestoreArray(qdd_, &qdd));
    PetscCall(VecRestoreArray(v_, &v));
    PetscCall(VecRestoreArray(q_, &q));
    PetscCall(VecRestoreArray(a_, &a));
  } else {
    PetscCall(VecRestoreArrayRead(v_, const_cast<const PetscScalar **>(&v)));
    PetscCall(VecRestoreArrayRead(q_, const_cast<const PetscScalar **>(&q)));
    PetscCall(VecRestoreArrayRead(a_, const_cast<const PetscScalar **>(&a)));
  }
  PetscCall(VecRestoreArrayRead(vc_, &vc));
  PetscCall(VecRestoreArrayRead(ac_, &ac));
  PetscCall(VecRestoreArrayRead(qp_, &qp));
  PetscCall(VecRestoreArrayRead(x_, &x));
  PetscFunctionReturn(0);
}

// The algorithmic acceleration of the first step after a start or a
// restart (docs/model.md §4.3). For one mode of frequency omega started
// with a_0 = qdd_0 = F/m (a load F switched on, m the modal mass), the
// first step of §4.2 leaves, as omega h -> inf, q_1 -> F/k (1 - alpha_m)/
// (2 beta (1 - alpha_f)) (bounded) but the velocity v_1 -> c h a_0 with
// c = 1 - gamma/(2 beta): a kinetic energy (c omega h)^2 F^2/(2k) that grows
// without bound with omega h (c = 0 only for rho_inf = 1; 0.0099 for 0.8).
// On a fine mesh the unresolved modes are many and omega h is large: the
// first step created 5.9 kJ on the hoist lift-off scene with 160 elements
// per boom (0.7 J of strain at the start), and Newton could not take the
// second step of the 512-element cantilever at any h. Filtered, a_0 solves
//   (M + mu (K_t + gamma' D)/beta') a_0 + C_q^T nu = M qdd_0,   C_q a_0 = C_q qdd_0,
// with mu = c^2: per mode a_0 = qdd_0 / (1 + mu theta (omega h)^2),
// theta = beta (1 - alpha_f)/(1 - alpha_m), so the first step's kinetic
// energy in any mode stays below F^2/(8 theta k) (0.49 F^2/k at rho_inf =
// 0.8: the size of the mode's static strain energy), and modes with
// omega h < 1/sqrt(mu theta) (200 at rho_inf = 0.8) keep a_0 = qdd_0 to
// (omega h)^2 mu theta: an O(h^2) change of the starting value, which keeps
// the scheme second order (Arnold & Bruls 2007 need a_0 = qdd_0 + O(h)).
// The matrix is the step's iteration matrix with beta'/mu in place of
// beta' (an assembly and a factorization per start). The constraints keep
// the acceleration level of qdd_0, and qdd_ itself stays the consistent
// acceleration (it enters the step as qdd_n).
PetscErrorCode GeneralizedAlpha::filterStartAcceleration(double h, double betaP, double gammaP, double sigma)
{
  PetscHandle<Vec> w, Mw, Jw, y;
  PetscInt lo, hi, nq = assembler_.model().numCoordinates();
  std::vector<PetscInt> firstOrder = assembler_.model().firstOrderCoordinates();
  std::sort(firstOrder.begin(), firstOrder.end());
  auto secondOrder = [&](PetscInt g) {
    return g < nq && !std::binary_search(firstOrder.begin(), firstOrder.end(), g);
  };
  const AlphaParameters &p = params_;
  const double c = 1.0 - p.gamma / (2.0 * p.beta), mu = c * c;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(qdd_, a_));
  if (mu < 1e-12) PetscFunctionReturn(0); // rho_inf = 1: no growth to filter
  const double massCoefficient = betaP / mu;
  for (PetscHandle<Vec> *v : {&w, &Mw, &Jw, &y}) PetscCall(assembler_.createVector(v->address()));
  // w = qdd_0 on the second-order coordinates, 0 elsewhere.
  PetscCall(VecGetOwnershipRange(w, &lo, &hi));
  {
    const PetscScalar *qdd;
    PetscScalar *wa;
    PetscCall(VecGetArrayRead(qdd_, &qdd));
    PetscCall(VecGetArray(w, &wa));
    for (PetscInt g = lo; g < hi; ++g) wa[g - lo] = secondOrder(g) ? qdd[g - lo] : 0.0;
    PetscCall(VecRestoreArray(w, &wa));
    PetscCall(VecRestoreArrayRead(qdd_, &qdd));
  }
  // M w: the acceleration-level residual is affine in x (M x - Q + ...).
  setAccelerationLevelContext(newton_, false);
  PetscCall(assembler_.setOffsets(q_, v_, nullptr));
  PetscCall(assembler_.evaluate(newton_.ctx, w, Mw, nullptr));
  PetscCall(assembler_.evaluate(newton_.ctx, zero_, Jw, nullptr));
  PetscCall(VecAXPY(Mw, -1.0, Jw));
  // (beta'/mu) M + gamma' D + K_t with its constraint blocks at the start
  // state: x = [q_0 | lambda_0/sigma] with offsets that give v = v_0 and
  // qdd = qdd_0 there (z: zdot = 0); constraint rows scaled like the mass.
  AssemblyContext ctx;
  ctx.t = t_;
  ctx.kin = {1.0, gammaP, massCoefficient, 1.0 / h};
  ctx.sigma = sigma / mu;
  ctx.rightLimit = true; // the state at t_ has passed any jump at t_
  ctx.residualWanted = false;
  PetscCall(VecCopy(q_, x_));
  PetscCall(assembler_.copyMultipliers(lambda_, x_, mu / sigma));
  PetscCall(VecWAXPY(vc_, -gammaP, q_, v_));
  // qdd = ac + cA x with cA = beta'/mu, not beta': an offset with beta'
  // left qdd = qdd_0 + beta' (1/mu - 1) q_0 (of size q_0/h^2) in the items
  // whose tangent depends on qdd (a mass matrix M(q): a rigid body's point
  // mass, Euler parameters), an O(1) change of a_0 that made the run first
  // order (planar pendulum with a tip mass: 6.2e-5 -> 3.1e-5 rad from h = 1
  // to 0.5 ms at rho_inf = 0.8).
  PetscCall(VecWAXPY(ac_, -massCoefficient, q_, qdd_));
  PetscCall(forFirstOrder([&](PetscInt i, const PetscScalar *q, PetscScalar *vc, PetscScalar *) { vc[i] = -q[i] / h; }));
  PetscCall(assembler_.setOffsets(nullptr, vc_, ac_));
  // Right-hand side: the constraint rows of J w, (beta'/mu) M w on the
  // second-order rows, 0 on the first-order ones. The matrix and its
  // factorization are the Newton solver's own (no second copy is held; a
  // singular matrix is left to the step, which reports it, and the start is
  // then the unfiltered a = qdd).
  bool solved = false;
  PetscCall(newton_.solveLinear(
    [&](Mat J) -> PetscErrorCode {
      PetscFunctionBeginUser;
      PetscCall(assembler_.evaluate(ctx, x_, nullptr, J));
      PetscCall(MatMult(J, w, Jw));
      const PetscScalar *m;
      PetscScalar *r;
      PetscCall(VecGetArrayRead(Mw, &m));
      PetscCall(VecGetArray(Jw, &r));
      for (PetscInt g = lo; g < std::min(hi, nq); ++g) r[g - lo] = secondOrder(g) ? massCoefficient * m[g - lo] : 0.0;
      PetscCall(VecRestoreArray(Jw, &r));
      PetscCall(VecRestoreArrayRead(Mw, &m));
      PetscFunctionReturn(0);
    },
    Jw, y, &solved));
  if (!solved) PetscFunctionReturn(0);
  {
    const PetscScalar *ya;
    PetscScalar *a;
    PetscCall(VecGetArrayRead(y, &ya));
    PetscCall(VecGetArray(a_, &a));
    for (PetscInt g = lo; g < std::min(hi, nq); ++g)
      if (secondOrder(g)) a[g - lo] = ya[g - lo];
    PetscCall(VecRestoreArray(a_, &a));
    PetscCall(VecRestoreArrayRead(y, &ya));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlpha::step(double h, StepResult *result)
{
  PetscFunctionBeginUser;
  PetscCall(advance(h, t_ + h, result));
  if (result->converged && accelerationRestart_) {
    // Spatial models at rho_inf = 1 (alpha_m = alpha_f: a = qdd): the
    // accelerations and multipliers of the index-3 solve carry an
    // alternating part that nothing damps at rho_inf = 1 and that the
    // Euler parameters' fast-turning constraint Jacobians drive: for a top
    // spinning at 100 rad/s it grew from the first step at every step size
    // until the energy check stopped the run at 0.27 s (damping needs
    // 1 - rho_inf >~ omega h). Replacing them by the
    // consistent accelerations of (q_{n+1}, v_{n+1}) after each step (one
    // linear solve) removes it: the top then precesses to 3.9e-5 of
    // m g l/(I3 w3) at h = 0.25 ms with its energy kept to 1e-10
    // (docs/model.md §9.1). q and v are those of the step.
    const bool predictor = predictWithAcceleration_;
    PetscCall(consistentAccelerations());
    startPending_ = false;
    predictWithAcceleration_ = predictor;
  }
  if (result->converged) PetscCall(reportMultipliers());
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlpha::advance(double h, double tEnd, StepResult *result)
{
  const AlphaParameters &p = params_;
  PetscFunctionBeginUser;
  const double h2b = h * h * p.beta;
  const double betaP = (1.0 - p.alpha_m) / (h2b * (1.0 - p.alpha_f));
  const double gammaP = p.gamma / (h * p.beta);
  const double sigma = massScale_ * betaP;
  // Part of the (re)start, like the consistent accelerations: not in BoomStep.
  if (startPending_) {
    PetscCall(PetscLogEventBegin(logEvents().start, 0, 0, 0, 0));
    PetscCall(filterStartAcceleration(h, betaP, gammaP, sigma));
    PetscCall(PetscLogEventEnd(logEvents().start, 0, 0, 0, 0));
  }
  PetscCall(PetscLogEventBegin(logEvents().step, 0, 0, 0, 0));

  // A converged solve whose contact points moved to other track elements is
  // redone with the pattern of the elements that hold them (a few times at
  // most: a fast slider may cross several elements in one step).
  bool relocated = false;
  for (int attempt = 0; attempt < 16; ++attempt) {
    // qp = q + h v + h^2 (1/2 - beta) a
    // qdd(x) = ac + beta' x with ac = -beta' qp + (alpha_m a - alpha_f qdd)/(1 - alpha_f)
    // v(x) = vc + gamma' x with vc = v + h (1 - gamma) a - gamma' qp
    // Predictor q_{n+1} = q_n + h v_n, or q_n + h v_n + h^2/2 a_n (a_{n+1}
    // = a_n in the update formula) when that predicted the previous step's
    // solution better. Always extrapolating accelerations carries the large
    // accelerations of stiff modes after a suddenly applied load or a
    // contact event over a whole step and starts Newton far from the
    // solution (stick-slip scene: the first step diverged from the consistent
    // initial accelerations); in smooth motion it saves about one Newton
    // iteration in six (paper extraction: 29 907 residuals instead of
    // 34 928, docs/performance-history.md).
    PetscCall(predict(h, betaP, gammaP, sigma));
    // First-order states (LuGre z): backward Euler, zdot = (z - z_n)/h, from z_n.
    PetscCall(forFirstOrder([&](PetscInt i, const PetscScalar *q, PetscScalar *vc, PetscScalar *x) {
      vc[i] = -q[i] / h;
      x[i] = q[i];
    }));

    newton_.ctx = AssemblyContext{};
    newton_.ctx.t = tEnd;
    newton_.ctx.kin = {1.0, gammaP, betaP, 1.0 / h};
    newton_.ctx.sigma = sigma;
    PetscCall(assembler_.setOffsets(nullptr, vc_, ac_));
    PetscCall(newton_.solve(x_, &result->iterations, &result->reason));
    result->converged = result->reason > 0;
    if (!result->converged && predictWithAcceleration_) {
      // Failed from the acceleration predictor (a large h, or the
      // accelerations just jumped): the same step again from q_n + h v_n,
      // so that the predictor never turns a step that q_n + h v_n solves
      // into a rejected one (cantilever at h = 50 ms under a step load:
      // steps cut down to 0.1 ms without this).
      PetscInt more = result->iterations;
      predictWithAcceleration_ = false;
      PetscCall(VecWAXPY(x_, h, v_, q_));
      PetscCall(assembler_.copyMultipliers(lambda_, x_, 1.0 / sigma));
      PetscCall(forFirstOrder([&](PetscInt i, const PetscScalar *q, PetscScalar *, PetscScalar *x) { x[i] = q[i]; }));
      PetscCall(newton_.solve(x_, &result->iterations, &result->reason));
      result->iterations += more;
      result->converged = result->reason > 0;
    }
    if (!result->converged) break;
    PetscCall(sliders_.update(x_, tEnd, &relocated, &result->event));
    if (!result->event.empty()) result->converged = false;
    if (!relocated || !result->event.empty()) break;
  }
  if (relocated && result->event.empty() && result->converged) result->converged = false; // still moving: give up this h
  if (result->converged) {
    // Local error estimate from the change of the acceleration-like variable
    // over the step, on this rank's coordinates (not the multipliers).
    // With it, the largest distance of the solution from each predictor.
    // Without an error tolerance the step is accepted whatever the estimate,
    // and the update of the state rides on the same pass.
    const bool mayReject = errorTolerance_ > 0;
    enum { Change, VelocityPredictor, AccelerationPredictor };
    double largest[3] = {0, 0, 0};
    PetscCall(estimateAndUpdate(h, betaP, gammaP, sigma, !mayReject, largest));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, largest, 3, MPI_DOUBLE, MPI_MAX, assembler_.comm()));
    result->errorEstimate = h * h * std::abs(p.beta - 1.0 / 6.0) * largest[Change];
    predictWithAcceleration_ =
      accelerationPredictor_ && largest[AccelerationPredictor] < largest[VelocityPredictor];
    if (mayReject && result->errorEstimate > errorTolerance_) {
      result->converged = false;
      result->errorRejected = true;
    }
    if (result->converged && mayReject) PetscCall(estimateAndUpdate(h, betaP, gammaP, sigma, true, nullptr));
  }
  if (result->converged) {
    t_ = tEnd;
    startPending_ = false;
    PetscCall(sliders_.rechart(q_, t_)); // spatial beams rebase their node references
  }
  PetscCall(PetscLogEventEnd(logEvents().step, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlpha::save(StateWriter &out) const
{
  PetscFunctionBeginUser;
  PetscCall(out.addVector("q", q_));
  PetscCall(out.addVector("v", v_));
  PetscCall(out.addVector("qdd", qdd_));
  PetscCall(out.addVector("a", a_));
  PetscCall(out.addVector("lambda", lambda_));
  out.addScalar("t", t_);
  out.addScalar("impulse_work", impulseWork_);
  out.addScalar("predict_with_acceleration", predictWithAcceleration_ ? 1.0 : 0.0);
  out.addScalar("start_pending", startPending_ ? 1.0 : 0.0);
  out.addArray("slider_locations", sliders_.locations());
  // Other post-step state (spatial beams' node references), if any.
  const std::vector<double> hookStates = sliders_.states();
  if (!hookStates.empty()) out.addArray("hook_states", hookStates);
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlpha::restore(const StateReader &in)
{
  PetscFunctionBeginUser;
  PetscCall(in.getVector("q", q_));
  PetscCall(in.getVector("v", v_));
  PetscCall(in.getVector("qdd", qdd_));
  PetscCall(in.getVector("a", a_));
  PetscCall(in.getVector("lambda", lambda_));
  t_ = in.scalar("t");
  impulseWork_ = in.hasScalar("impulse_work") ? in.scalar("impulse_work") : 0.0;
  // The predictor the run would have used next, so that restarts continue
  // bitwise (checkpoints from before it predicted without accelerations).
  predictWithAcceleration_ =
    accelerationPredictor_ && in.hasScalar("predict_with_acceleration") && in.scalar("predict_with_acceleration") != 0;
  // A checkpoint written at a restart (a drive kink) holds a = qdd: the
  // next step filters it as the run would have (checkpoints from before the
  // filter continue unfiltered, as they were run).
  startPending_ = filteredStart_ && in.hasScalar("start_pending") && in.scalar("start_pending") != 0;
  // The joints' elements as they were, not as a fresh search would choose
  // them within the relocation band: restarts continue bitwise.
  PetscCall(sliders_.setLocations(in.array("slider_locations")));
  // The beams' node references as they were: the same coordinates mean the
  // same state only in the same chart.
  if (!sliders_.states().empty()) PetscCall(sliders_.setStates(in.array("hook_states")));
  newton_.invalidateJacobian();
  // The reported multipliers depend on the state alone.
  if (consistentMultipliers_) PetscCall(reportMultipliers());
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlpha::diagnostics(EnergyParts *energy, PetscReal *violation, bool rightLimit,
                                             Assembler::DampingForces *forces)
{
  PetscFunctionBeginUser;
  AssemblyContext ctx;
  ctx.t = t_;
  ctx.rightLimit = rightLimit;
  ctx.kin = {1.0, 0.0, 0.0};
  // q from q_ itself (cQ = 1, qc = 0), v from v_ (cV = 0, vc = v_). Only
  // driven constraints read multipliers here (their power): for them, a copy
  // of q_ with the unscaled multipliers (qp_ is free between steps).
  PetscCall(assembler_.setOffsets(nullptr, v_, nullptr));
  if (!hasDrives_) {
    PetscCall(assembler_.diagnostics(ctx, q_, energy, violation, forces));
    if (energy) energy->impulseWork = impulseWork_;
    PetscFunctionReturn(0);
  }
  PetscCall(VecCopy(q_, qp_));
  PetscCall(assembler_.copyMultipliers(lambda_, qp_, 1.0));
  PetscCall(assembler_.diagnostics(ctx, qp_, energy, violation, forces));
  if (energy) energy->impulseWork = impulseWork_;
  PetscFunctionReturn(0);
}

} // namespace boomdyn
