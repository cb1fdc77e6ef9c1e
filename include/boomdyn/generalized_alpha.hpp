// Generalized-alpha for constrained mechanical systems in the form of
// Arnold & Bruls (Multibody Syst. Dyn. 18, 2007):
//   M qdd_{n+1} + C_q^T lambda_{n+1} = Q(q_{n+1}, v_{n+1}, t_{n+1})
//   C(q_{n+1}, t_{n+1}) = 0
//   q_{n+1} = q_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}
//   v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1}
//   (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) qdd_{n+1} + alpha_f qdd_n
// with consistent initial accelerations and multipliers from the
// acceleration-level equations, constraints at t_{n+1} and multipliers and
// constraint rows scaled by sigma = m beta' (m: mean mass diagonal), which
// keeps the iteration matrix conditioned independently of h. Newton runs on
// q_{n+1} and lambda_{n+1} through SNES (NewtonSolver).
#pragma once

#include "boomdyn/newton_solver.hpp"
#include "boomdyn/petsc_handle.hpp"
#include "boomdyn/slider_tracker.hpp"
#include "boomdyn/state_archive.hpp"

#include <string>
#include <vector>

namespace boomdyn {

struct AlphaParameters {
  double alpha_m, alpha_f, beta, gamma;
  // Chung & Hulbert's optimal choice for spectral radius rho_inf at h -> inf.
  static AlphaParameters fromRhoInf(double rho_inf);
};

struct StepResult {
  bool converged = false;
  PetscInt iterations = 0;
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  std::string event; // set when the step cannot be taken at any h (a slider left its track)
  // Local error of the positions, max over coordinates [m or 1]: the
  // Newmark estimate h^2 |beta - 1/6| |a_{n+1} - a_n| (Zienkiewicz and Xie).
  double errorEstimate = 0;
  bool errorRejected = false; // converged, but errorEstimate > the error tolerance
  // The step ended on a velocity breakpoint of a drive and the integrator
  // restarted there (velocity projection + consistent accelerations).
  bool restarted = false;
};

class GeneralizedAlpha {
public:
  GeneralizedAlpha(Assembler &assembler, double rho_inf)
    : assembler_(assembler), params_(AlphaParameters::fromRhoInf(rho_inf)), sliders_(assembler)
  {
  }
  GeneralizedAlpha(const GeneralizedAlpha &) = delete;
  GeneralizedAlpha &operator=(const GeneralizedAlpha &) = delete;

  PetscErrorCode setUp(PetscInt maxNewton);
  // Start at t0 from coordinates q0 and velocities v0 (layout of x; the
  // multiplier part is ignored): solves for consistent qdd_0 and lambda_0.
  PetscErrorCode initialize(double t0, Vec q0, Vec v0);
  // Checkpoints: the state vectors and time; restore() replaces initialize()
  // and moves the sliding joints to the elements that hold the restored s.
  PetscErrorCode save(StateWriter &out) const;
  PetscErrorCode restore(const StateReader &in);
  // Attempt one step of size h. On failure the state is left unchanged.
  PetscErrorCode step(double h, StepResult *result);
  // Attempt the step that ends exactly on nextBreakpoint() and, when it
  // converges, restart there (docs/model.md §4.8): project the velocities
  // onto C_q v + C_t = 0 with the right-hand rates of the drives (an
  // impulsive step M dv + C_q^T P + friction impulse = 0), then solve for
  // consistent accelerations and multipliers and reset the auxiliary
  // acceleration a to them. Without kink restarts it is step(h).
  PetscErrorCode stepToBreakpoint(StepResult *result);
  // The first velocity breakpoint of a drive after the current time
  // (+infinity when none is left or kink restarts are off).
  double nextBreakpoint() const;
  // -boom_kink_restart (default on): land on the drives' velocity kinks
  // and restart there. Set before initialize().
  void setKinkRestart(bool on) { kinkRestart_ = on; }
  bool kinkRestart() const { return kinkRestart_; }
  // -boom_acceleration_predictor (default on): start Newton from
  // q_n + h v_n + h^2/2 a_n whenever that predicted the last step's
  // solution better than q_n + h v_n (docs/model.md §4.2). Set before initialize().
  void setAccelerationPredictor(bool on) { accelerationPredictor_ = on; }
  // -boom_filtered_start (default on): the first step after a start or a
  // restart begins from an algorithmic acceleration a from which the modes
  // the step cannot resolve (omega h >> 1) are filtered out, instead of
  // a = qdd (docs/model.md §4.3). Set before initialize().
  void setFilteredStart(bool on) { filteredStart_ = on; }
  // Impulse of the last velocity projection (N s or N m s) in the
  // multiplier entries, SI units; zero before any.
  Vec lastImpulse() const { return impulse_; }

  double time() const { return t_; }
  // State in the layout of x: coordinates in the first nq entries.
  Vec positions() const { return q_; }
  Vec velocities() const { return v_; }
  Vec accelerations() const { return qdd_; }
  // Multipliers (unscaled, SI units) in the last nlambda entries: the
  // reported ones (see setConsistentMultipliers).
  Vec multipliers() const { return consistentMultipliers_ ? reported_ : lambda_; }
  // -boom_consistent_multipliers (default on): the multipliers reported
  // after each step are solved from the acceleration-level equations at the
  // step's (t, q, v, z), not the step's index-3 algorithmic ones, which carry
  // an alternating error after every jump of a prescribed acceleration and
  // O(h) errors where a drive's acceleration varies (docs/model.md §4.8).
  // Set before initialize().
  void setConsistentMultipliers(bool on) { consistentMultipliers_ = on; }
  // Context for diagnostics at the current state (energy, violation); with
  // rightLimit false, as the step that landed on t_ saw it (before a jump at t_).
  // With `forces`, the damping forces at that state in the same pass
  // (Assembler::diagnostics).
  PetscErrorCode diagnostics(EnergyParts *energy, PetscReal *violation, bool rightLimit = true,
                             Assembler::DampingForces *forces = nullptr);
  NewtonSolver &newton() { return newton_; }
  // Adaptive steps (-boom_adaptive_tol): a converged step whose error
  // estimate exceeds tol is not taken (result.errorRejected). 0: off.
  void setErrorTolerance(double tol) { errorTolerance_ = tol; }
  double errorTolerance() const { return errorTolerance_; }
  const AlphaParameters &parameters() const { return params_; }

private:
  // One step from t_ to tEnd = t_ + h (tEnd given exactly when landing on a breakpoint).
  PetscErrorCode advance(double h, double tEnd, StepResult *result);
  // The velocity projection at t_ (no-op when v_ is consistent).
  PetscErrorCode projectVelocities();
  // qdd_, a_ and lambda_ from the acceleration-level equations at (t_, q_, v_).
  PetscErrorCode consistentAccelerations();
  // a_ from qdd_ for the first step of size h after a (re)start (see there).
  PetscErrorCode filterStartAcceleration(double h, double betaP, double gammaP, double sigma);
  void setAccelerationLevelContext(NewtonSolver &solver, bool velocityLevel);
  // reported_ from the acceleration-level equations at (t_, q_, v_) (no-op
  // without consistent multipliers).
  PetscErrorCode reportMultipliers();
  template <class Op>
  PetscErrorCode forFirstOrder(Op op);
  // One-pass predictor and corrector of advance() (see there).
  PetscErrorCode predict(double h, double betaP, double gammaP, double sigma);
  PetscErrorCode estimateAndUpdate(double h, double betaP, double gammaP, double sigma, bool update, double *largest);
  std::vector<double> firstOrderQ_; // q_n of the owned first-order states (estimateAndUpdate)

  Assembler &assembler_;
  AlphaParameters params_;
  NewtonSolver newton_;
  NewtonSolver reportSolver_; // the acceleration-level solve of the reported multipliers (own matrix)
  SliderTracker sliders_;
  double t_ = 0, massScale_ = 1, errorTolerance_ = 0;
  bool hasDrives_ = false; // some constraint depends on time (its power needs the multipliers)
  bool kinkRestart_ = true;
  // Spatial models at rho_inf = 1: consistent accelerations after every step (step()).
  bool accelerationRestart_ = false;
  bool accelerationPredictor_ = true;
  bool filteredStart_ = true;
  bool consistentMultipliers_ = false;
  bool reportSolverReady_ = false;
  PetscInt maxNewton_ = 25;
  // qdd_ holds consistent accelerations of a (re)start that no step has
  // left yet: the next step filters a_ from them for its own h.
  bool startPending_ = false;
  // The next step starts from q_n + h v_n + h^2/2 a_n (else q_n + h v_n):
  // chosen after each step by which of the two was closer to its solution.
  bool predictWithAcceleration_ = false;
  double impulseWork_ = 0; // kinetic energy added by the velocity projections so far [J]
  std::vector<double> breakpoints_; // sorted velocity kinks of all drives and breakpoints of work items
  std::vector<double> driveKinks_;  // sorted velocity kinks of the drives alone (where to project velocities)
  PetscHandle<Vec> q_, v_, qdd_, a_, lambda_;       // state at t_
  PetscHandle<Vec> x_, qp_, vc_, ac_, zero_;        // work vectors of a step
  PetscHandle<Vec> shift_, impulse_;                // velocity projection
  PetscHandle<Vec> reported_;                       // reported multipliers (consistent with q_, v_ at t_)
};

} // namespace boomdyn
