#include "boomdyn/generalized_alpha.hpp"

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
  for (PetscHandle<Vec> *v : {&q_, &v_, &qdd_, &a_, &lambda_, &x_, &qp_, &vc_, &ac_, &zero_, &shift_, &impulse_})
    PetscCall(assembler_.createVector(v->address()));
  PetscCall(newton_.setUp(assembler_, nullptr, maxNewton));
  PetscCall(sliders_.setUp(x_));
  breakpoints_.clear();
  for (const ConstraintItem *c : assembler_.model().constraints()) {
    hasDrives_ = hasDrives_ || c->constraint().dependsOnTime();
    c->constraint().velocityBreakpoints(breakpoints_);
  }
  driveKinks_ = breakpoints_;
  std::sort(driveKinks_.begin(), driveKinks_.end());
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

// Applies op(local index, q_n, x_{n+1}, v, a, qdd) to the owned first-order entries.
template <class Op>
PetscErrorCode GeneralizedAlpha::forFirstOrderState(Op op)
{
  PetscInt lo, hi;
  const PetscScalar *q, *x;
  PetscScalar *v, *a, *qdd;
  PetscFunctionBeginUser;
  if (assembler_.model().firstOrderCoordinates().empty()) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(q_, &lo, &hi));
  PetscCall(VecGetArrayRead(q_, &q));
  PetscCall(VecGetArrayRead(x_, &x));
  PetscCall(VecGetArray(v_, &v));
  PetscCall(VecGetArray(a_, &a));
  PetscCall(VecGetArray(qdd_, &qdd));
  for (PetscInt g : assembler_.model().firstOrderCoordinates())
    if (g >= lo && g < hi) op(g - lo, q, x, v, a, qdd);
  PetscCall(VecRestoreArray(qdd_, &qdd));
  PetscCall(VecRestoreArray(a_, &a));
  PetscCall(VecRestoreArray(v_, &v));
  PetscCall(VecRestoreArrayRead(x_, &x));
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
  PetscFunctionReturn(0);
}

// The matrix [M C_q^T; C_q 0] at t_ in x = [qdd | lambda_hat]
// (consistent accelerations), or with velocity-level constraint rows
// C_q v + C_t in x = [dv | P_hat] (the impulsive projection at a kink).
void GeneralizedAlpha::setAccelerationLevelContext(bool velocityLevel)
{
  newton_.ctx = AssemblyContext{};
  newton_.ctx.t = t_;
  newton_.ctx.kin = {0.0, 0.0, 1.0};
  newton_.ctx.sigma = massScale_;
  newton_.ctx.accelerationLevel = true;
  newton_.ctx.velocityLevel = velocityLevel;
  newton_.ctx.rightLimit = true; // the state at t_ has passed any jump at t_ (a released mass is gone)
}

PetscErrorCode GeneralizedAlpha::consistentAccelerations()
{
  PetscInt its;
  SNESConvergedReason reason;
  PetscFunctionBeginUser;
  // Acceleration-level system [M C_q^T; C_q 0] [qdd; lambda] = [Q; -gamma]:
  // linear in x = [qdd | lambda_hat], so one Newton step solves it.
  setAccelerationLevelContext(false);
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
  // modes' transients (see advance()): the first step predicts without them.
  predictWithAcceleration_ = false;
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
  setAccelerationLevelContext(true);
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
    PetscCall(SNESGetFunctionNorm(newton_.snes(), &finalResidual));
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
  result->restarted = true;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlpha::step(double h, StepResult *result) { return advance(h, t_ + h, result); }

PetscErrorCode GeneralizedAlpha::advance(double h, double tEnd, StepResult *result)
{
  const AlphaParameters &p = params_;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(logEvents().step, 0, 0, 0, 0));
  const double h2b = h * h * p.beta;
  const double betaP = (1.0 - p.alpha_m) / (h2b * (1.0 - p.alpha_f));
  const double gammaP = p.gamma / (h * p.beta);
  const double sigma = massScale_ * betaP;

  // A converged solve whose contact points moved to other track elements is
  // redone with the pattern of the elements that hold them (a few times at
  // most: a fast slider may cross several elements in one step).
  bool relocated = false;
  for (int attempt = 0; attempt < 16; ++attempt) {
    // qp = q + h v + h^2 (1/2 - beta) a
    PetscCall(VecCopy(q_, qp_));
    PetscCall(VecAXPBYPCZ(qp_, h, h * h * (0.5 - p.beta), 1.0, v_, a_));
    // qdd(x) = ac + beta' x with ac = -beta' qp + (alpha_m a - alpha_f qdd)/(1 - alpha_f)
    PetscCall(VecAXPBYPCZ(ac_, p.alpha_m / (1.0 - p.alpha_f), -p.alpha_f / (1.0 - p.alpha_f), 0.0, a_, qdd_));
    PetscCall(VecAXPY(ac_, -betaP, qp_));
    // v(x) = vc + gamma' x with vc = v + h (1 - gamma) a - gamma' qp
    PetscCall(VecCopy(v_, vc_));
    PetscCall(VecAXPBYPCZ(vc_, h * (1.0 - p.gamma), -gammaP, 1.0, a_, qp_));

    // Predictor q_{n+1} = q_n + h v_n, or q_n + h v_n + h^2/2 a_n (a_{n+1}
    // = a_n in the update formula) when that predicted the previous step's
    // solution better. Always extrapolating accelerations carries the large
    // accelerations of stiff modes after a suddenly applied load or a
    // contact event over a whole step and starts Newton far from the
    // solution (stick-slip scene: the first step diverged from the consistent
    // initial accelerations); in smooth motion it saves about one Newton
    // iteration in six (paper extraction: 29 907 residuals instead of
    // 34 928, docs/performance.md).
    PetscCall(VecWAXPY(x_, h, v_, q_));
    if (predictWithAcceleration_) PetscCall(VecAXPY(x_, 0.5 * h * h, a_));
    PetscCall(assembler_.copyMultipliers(lambda_, x_, 1.0 / sigma));
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
    PetscInt begin, end, lo;
    const PetscScalar *x, *qp, *a, *q, *v;
    PetscCall(assembler_.coordinateRange(&begin, &end));
    PetscCall(VecGetOwnershipRange(x_, &lo, nullptr));
    PetscCall(VecGetArrayRead(x_, &x));
    PetscCall(VecGetArrayRead(qp_, &qp));
    PetscCall(VecGetArrayRead(a_, &a));
    PetscCall(VecGetArrayRead(q_, &q));
    PetscCall(VecGetArrayRead(v_, &v));
    enum { Change, VelocityPredictor, AccelerationPredictor };
    double largest[3] = {0, 0, 0};
    for (PetscInt g = begin; g < end; ++g) {
      const PetscInt i = g - lo;
      largest[Change] = std::max(largest[Change], std::abs((x[i] - qp[i]) / h2b - a[i]));
      const double fromVelocity = x[i] - q[i] - h * v[i];
      largest[VelocityPredictor] = std::max(largest[VelocityPredictor], std::abs(fromVelocity));
      largest[AccelerationPredictor] =
        std::max(largest[AccelerationPredictor], std::abs(fromVelocity - 0.5 * h * h * a[i]));
    }
    PetscCall(VecRestoreArrayRead(v_, &v));
    PetscCall(VecRestoreArrayRead(q_, &q));
    PetscCall(VecRestoreArrayRead(a_, &a));
    PetscCall(VecRestoreArrayRead(qp_, &qp));
    PetscCall(VecRestoreArrayRead(x_, &x));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, largest, 3, MPI_DOUBLE, MPI_MAX, assembler_.comm()));
    result->errorEstimate = h * h * std::abs(p.beta - 1.0 / 6.0) * largest[Change];
    predictWithAcceleration_ =
      accelerationPredictor_ && largest[AccelerationPredictor] < largest[VelocityPredictor];
    if (errorTolerance_ > 0 && result->errorEstimate > errorTolerance_) {
      result->converged = false;
      result->errorRejected = true;
    }
  }
  if (result->converged) {
    // a_{n+1} = (q_{n+1} - qp)/(h^2 beta); qdd, v from the affine maps.
    PetscCall(VecWAXPY(a_, -1.0, qp_, x_));
    PetscCall(VecScale(a_, 1.0 / h2b));
    PetscCall(VecWAXPY(qdd_, betaP, x_, ac_));
    PetscCall(VecWAXPY(v_, gammaP, x_, vc_));
    // First-order states: rate from backward Euler; no accelerations.
    PetscCall(forFirstOrderState([&](PetscInt i, const PetscScalar *qn, const PetscScalar *x, PetscScalar *v, PetscScalar *a,
                                     PetscScalar *qdd) {
      v[i] = (x[i] - qn[i]) / h;
      a[i] = qdd[i] = 0.0;
    }));
    PetscCall(VecCopy(x_, q_));
    PetscCall(assembler_.copyMultipliers(x_, lambda_, sigma));
    t_ = tEnd;
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
  out.addArray("slider_locations", sliders_.locations());
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
  // The joints' elements as they were, not as a fresh search would choose
  // them within the relocation band: restarts continue bitwise.
  PetscCall(sliders_.setLocations(in.array("slider_locations")));
  newton_.invalidateJacobian();
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
