// The contract between the physics (elements, loads, constraints) and the
// assembler. Every contribution to the saddle-point system is a WorkItem: it
// names the global unknowns it touches (coordinates first, then its
// multiplier rows) and adds a dense residual and Jacobian block over them.
//
// One global unknown vector x = [q | lambda_hat]. The solvers choose how q,
// its velocity and acceleration follow from x through an affine map
//     q = qc + cQ x,   v = vc + cV x,   a = ac + cA x
// (dynamics: cQ = 1, cV = gamma', cA = beta'; consistent accelerations:
// cQ = cV = 0, cA = 1; statics: cQ = 1, cV = cA = 0), so that one Jacobian
// d(residual)/dx = cA M + cV D + cQ K serves every analysis.
//
// Multipliers are scaled: lambda = sigma * lambda_hat and constraint rows
// are sigma * C, which keeps the iteration matrix well conditioned at any
// step size (Bottasso, Bauchau & Cardona 2007).
#pragma once

#include <petscsys.h>

#include <algorithm>
#include <string>
#include <vector>

namespace boomdyn {

// First-order states (LuGre friction z) are unknowns too, but their rate
// follows from x with their own coefficient: zdot = vc + cZ x (backward Euler
// in dynamics: cZ = 1/h).
struct Kinematics {
  double cQ = 1, cV = 0, cA = 0, cZ = 0;
};

struct AssemblyContext {
  double t = 0;
  Kinematics kin;
  double sigma = 1;          // multiplier / constraint-row scaling
  double loadFactor = 1;     // multiplies external loads and gravity (static load stepping)
  // Constraint rows at acceleration level: sigma (C_q a + gamma) instead of sigma C.
  bool accelerationLevel = false;
  // With accelerationLevel: constraint rows at velocity level,
  // sigma (C_q a + C_q v + C_t), a being a velocity change (the impulsive
  // velocity projection at a drive's kink, docs/model.md §4.8).
  bool velocityLevel = false;
  // Emit zeros in every constraint block (the mass pencil B of the eigenproblem).
  bool constraintBlocks = true;
  // At a breakpoint t_b of an item whose forces or inertia jump there (a
  // released mass): false gives the state just before t_b (the step that
  // lands on t_b), true the state just after (the restart at t_b and the
  // diagnostics of the state reached). Items without jumps ignore it.
  bool rightLimit = false;
  // False when the caller keeps only the Jacobian (Assembler::evaluate
  // without F: the eigen-analysis' passes). An item may then skip forces
  // that do not enter the Jacobian asked for (a beam's internal force in a
  // mass or damping pass); the residual it writes is discarded.
  bool residualWanted = true;
  // The passes of the eigen-analysis' pencil (Assembler::evaluatePencil,
  // assembleDamping): first-order states that are not frozen there enter
  // through their linearization about the state (a hydraulic cylinder's
  // chamber pressures: docs/model.md §2.6) instead of their static rows.
  bool pencil = false;
};

// Values of the item's unknowns, in the order of dofs(): q, v, a of the
// coordinates, and x (= lambda_hat) of the multiplier rows.
struct ItemValues {
  const double *q = nullptr;
  const double *v = nullptr;
  const double *a = nullptr;
  const double *lambda = nullptr; // lambda_hat of the multiplier rows (after the coordinates)
};

struct EnergyParts {
  double kinetic = 0, strain = 0, potential = 0;
  // Rate at which the explicit time dependence of loads and driven
  // constraints feeds energy in (W): dE/dt = inputPower - dissipation.
  double inputPower = 0;
  // The input power just before t less inputPower (the right limit), where
  // the rate of a load or winch jumps at t (a ramp's end): the step that
  // lands on t takes its power at its end from its own segment, so that
  // the quadrature of a 1 ms haul is not the 0 of the rate after it.
  // Zero elsewhere.
  double inputPowerJump = 0;
  // Power dissipated by material damping (W, >= 0): edot . fd of the
  // Kelvin-Voigt forces (docs/model.md §1.1).
  double dissipation = 0;
  // Work of the drives' impulses at their velocity kinks since the start of
  // the run (J, cumulative): the kinetic energy each velocity projection
  // adds (docs/model.md §4.8). Set by the integrator, not by work items.
  double impulseWork = 0;
  // Size of the round-off in these sums (J): the strain energy of a short
  // element comes from differences of nodal values of size |q| over its
  // length, so it carries an error that grows like |q|^2 / l^3 (bending).
  double roundoff = 0;
};

// The kinds of strain energy a mode is labelled by (docs/model.md §5, "Mode
// labels"): beams split theirs by strain (axial, bending about the
// section's d3 axis = in the plane of the axis and `up`, in planar models
// in the model's plane; bending about d2 = out of that plane; torsion) and
// report the rest of their tangent (stress stiffening) as geometric; every
// other item reports all of its stiffness as one kind (modeEnergyKind()).
enum class ModeEnergyKind : int {
  Axial, BendingInPlane, BendingOutOfPlane, Torsion, Spring, Rope, Contact, Hydraulic, Friction, Geometric
};
constexpr int kModeEnergyKinds = 10;
// The names used in the output (/modal/energy_kinds, the log's labels).
inline const char *modeEnergyKindName(int kind)
{
  static const char *const names[kModeEnergyKinds] = {"axial",   "bending_in_plane", "bending_out_of_plane",
                                                      "torsion", "spring",           "rope",
                                                      "contact", "hydraulic",        "friction",
                                                      "geometric"};
  return kind >= 0 && kind < kModeEnergyKinds ? names[kind] : "?";
}
// 1/2 s^T K s of a mode shape s by kind (J for a shape in m and rad).
struct ModeEnergy {
  double kind[kModeEnergyKinds] = {};
  void add(ModeEnergyKind k, double e) { kind[static_cast<int>(k)] += e; }
};

// One of the eigen-analysis' three Jacobian passes over an item
// (Assembler::evaluatePencil): its context, the item's values under that
// pass's map, and its n x n block (row-major, zeroed on entry; null: the
// matrix is not wanted).
struct PencilPass {
  AssemblyContext ctx;
  ItemValues in;
  double *J = nullptr;
};
// The passes, in this order: stiffness A (cQ = 1, constraint blocks),
// mass B (cA = 1), damping D (cV = 1).
constexpr int kPencilPasses = 3;
// Largest number of items one evaluateResiduals() call receives.
constexpr int kResidualBatch = 4;

class WorkItem {
public:
  virtual ~WorkItem() = default;
  virtual std::string name() const = 0;
  // Coordinates touched now, in order; then multiplier rows (global indices).
  virtual void coordinates(std::vector<PetscInt> &dofs) const = 0;
  virtual void multiplierRows(std::vector<PetscInt> &rows) const { rows.clear(); }
  // Add the residual (size n = #coordinates + #rows) and, if J is not null,
  // the Jacobian d(residual)/dx (n x n, row-major) for the context.
  virtual void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const = 0;
  // The eigen-analysis' blocks in one call: every pass[p].J (when not null)
  // must receive bitwise what evaluate(pass[p].ctx, pass[p].in, residual,
  // pass[p].J) adds to it; n is the block size and scratch an array of n
  // entries for the residuals, which are discarded. The default makes those
  // evaluate() calls (scratch zeroed before each); items override it where
  // the passes can share work (the same kernel on the same values: a beam's
  // strains, a rope's path geometry, a pad's gap).
  virtual void evaluatePencil(const PencilPass (&pass)[kPencilPasses], int n, double *scratch) const;
  // Residuals without Jacobians of several items in one call: items that
  // return the same non-null key and follow one another in the model are
  // handed to the first one's evaluateResiduals() in groups of up to
  // kResidualBatch (Assembler::evaluate). Each residual[j] must receive
  // bitwise what evaluate(ctx, in[j], residual[j], nullptr) adds to it.
  // The default evaluates them one by one; a beam's elements share one SIMD
  // kernel call (one element per lane).
  virtual const void *residualBatchKey() const { return nullptr; }
  virtual void evaluateResiduals(const AssemblyContext &ctx, const WorkItem *const items[], const ItemValues in[],
                                 double *const residual[], int count) const;
  // Diagnostics at a state.
  virtual void energy(const AssemblyContext &, const ItemValues &, EnergyParts &) const {}
  virtual double constraintViolation(const AssemblyContext &, const ItemValues &) const { return 0; }
  // Times at which the item's explicit time dependence jumps in rate (a
  // winch speed) or in value (a released mass), appended to out: the
  // integrator lands a step on each and restarts there with consistent
  // accelerations (docs/model.md §4.8), like at a drive's velocity kink.
  virtual void breakpoints(std::vector<double> &out) const { (void)out; }
  // Physical damping: true when the item adds a dissipative force that
  // depends on the velocities as material behaviour (Kelvin-Voigt sections,
  // dampers), which selects the damped (PEP) eigen-analysis. Friction's
  // velocity terms do not count: they are a slip law, not a damping of the
  // vibration (modal_analysis.hpp).
  virtual bool physicalDamping() const { return false; }
  // Q_d(q, v): the item's damping forces at the state given, over its
  // coordinates (f gets one entry per coordinate); returns false for an item
  // without any. The energy balance takes their work along each step's own
  // increment (EnergyCheck, Assembler::dampingForces).
  virtual bool dampingForce(const ItemValues &, double * /*f*/) const { return false; }
  // energy() and dampingForce() at one state in one call: the diagnostics
  // after every step ask for both (Assembler::diagnostics with forces), and
  // an item whose energy already forms its damping force (the dissipated
  // power) need not form or look it up again.
  virtual bool energyAndDampingForce(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e,
                                     double *f) const
  {
    energy(ctx, in, e);
    return dampingForce(in, f);
  }
  // A fault the item met while it was evaluated on this rank (a force that
  // is not finite), for the message of a run that fails; empty if none.
  // The item makes its residual NaN then, so that no step is accepted.
  virtual std::string fault() const { return {}; }
  // The strain energy 1/2 s^T K s of a mode shape s in this item, by kind,
  // added to out (the mode labels, docs/model.md §5). stiffness: the
  // pencil's stiffness pass at the state (ctx with cQ = 1, pencil; in: q at
  // the state, v = a = 0, the multipliers) with stiffness.J an n x n block
  // zeroed on entry; shape: the mode's values of the item's n unknowns
  // (zero on its multiplier rows); scratch: n entries. The default forms
  // the stiffness block (evaluate()) and adds its 1/2 s^T J s to
  // modeEnergyKind(); beam elements split theirs by strain.
  virtual void modeEnergy(const PencilPass &stiffness, int n, const double *shape, double *scratch,
                          ModeEnergy &out) const;
  // The kind the default modeEnergy() reports the item's whole stiffness as:
  // geometric (gravity and joint reactions through the constraints'
  // curvature, follower loads) unless the item says otherwise.
  virtual ModeEnergyKind modeEnergyKind() const { return ModeEnergyKind::Geometric; }
  // Contribution to a characteristic mass / stiffness (diagonal sums) used to scale multipliers.
  virtual void scales(const ItemValues &, double &massDiag, double &stiffDiag, int &count) const
  {
    (void)massDiag, (void)stiffDiag, (void)count;
  }
};

inline void WorkItem::evaluatePencil(const PencilPass (&pass)[kPencilPasses], int n, double *scratch) const
{
  for (const PencilPass &p : pass) {
    if (!p.J) continue;
    std::fill(scratch, scratch + n, 0.0);
    evaluate(p.ctx, p.in, scratch, p.J);
  }
}

// 1/2 s^T J s of an n x n row-major block.
inline double halfQuadraticForm(const double *J, int n, const double *s)
{
  double e = 0;
  for (int i = 0; i < n; ++i) {
    if (s[i] == 0) continue;
    double row = 0;
    for (int j = 0; j < n; ++j) row += J[i * n + j] * s[j];
    e += s[i] * row;
  }
  return 0.5 * e;
}

inline void WorkItem::modeEnergy(const PencilPass &stiffness, int n, const double *shape, double *scratch,
                                 ModeEnergy &out) const
{
  std::fill(scratch, scratch + n, 0.0);
  evaluate(stiffness.ctx, stiffness.in, scratch, stiffness.J);
  out.add(modeEnergyKind(), halfQuadraticForm(stiffness.J, n, shape));
}

inline void WorkItem::evaluateResiduals(const AssemblyContext &ctx, const WorkItem *const items[],
                                        const ItemValues in[], double *const residual[], int count) const
{
  for (int j = 0; j < count; ++j) items[j]->evaluate(ctx, in[j], residual[j], nullptr);
}

} // namespace boomdyn
