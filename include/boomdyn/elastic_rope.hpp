// Elastic tension-only rope over point pulleys (docs/model.md §7): the
// spanned length l(q) of a RopePath, an unstretched length L0(t) = L0 +
// dL0(t) (dL0: the length a winch at the first end has paid out, zero
// without a winch), axial stiffness EA and damping c [N s/m] on the
// stretch rate:
//     k = EA/L0(t),  f = k (l - L0) + c (dl/dt - dL0/dt),
//     T = f if l > L0 and f > 0, else 0,
// and the generalized force -T l_q^T (residual +T l_q^T). While taut the
// Jacobian is exact: cQ (T l_qq + k l_q^T l_q + c l_q^T (l_qq v)^T)
// + cV c l_q^T l_q; while slack the rope adds nothing. The winch makes the
// force depend on t explicitly: its rate jumps are breakpoints of the
// integrator, and its power enters the energy balance (winchPower()).
#pragma once

#include "boomdyn/rope_path.hpp"
#include "boomdyn/time_function.hpp"
#include "boomdyn/work_item.hpp"

namespace boomdyn {

class ElasticRope : public WorkItem {
public:
  ModeEnergyKind modeEnergyKind() const override { return ModeEnergyKind::Rope; } // mode labels
  // payout: dL0(t) [m], the winch's paid-out length (hoisting: decreasing).
  ElasticRope(std::string name, RopePath path, double EA, double restLength, double damping,
              TimeFunction payout = TimeFunction());
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override { path_.coordinates(dofs); }
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  // The path's geometry and Hessian once for the passes at the same q.
  void evaluatePencil(const PencilPass (&pass)[kPencilPasses], int n, double *scratch) const override;
  // Strain energy (EA/(2 L0)) (l - L0)^2 while l > L0; dissipation T s' - (EA/L0)(l - L0)+ s' >= 0
  // (s = l - L0); input power: the winch power.
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  // The winch's rate jumps (a ramp's start and end, table knots).
  void breakpoints(std::vector<double> &out) const override { payout_.velocityBreakpoints(out); }

  // The rope at time t and state (q, v in coordinates() order).
  struct State {
    double length = 0, rate = 0; // l, dl/dt
    double restLength = 0;       // L0(t)
    double payout = 0;           // dL0(t), paid out by the winch since t = 0
    double payoutRate = 0;       // dL0/dt
    double stretch = 0;          // l - L0 (negative while slack by length)
    double force = 0;            // f = k (l - L0) + c (dl/dt - dL0/dt), before the tension-only cut
    double tension = 0;          // T
    bool taut = false;
    // Power the winch feeds into the rope span and the bodies:
    //   P = -(T + EA eps^2 / 2) dL0/dt,  eps = (l - L0)/L0 while l > L0,
    // the work against the tension plus the strain energy the hauled-in
    // rope takes onto the drum (dE/dt = P - dissipation exactly). > 0 while
    // hoisting (dL0/dt < 0) a taut rope.
    double winchPower = 0;
  };
  State state(double t, const double *q, const double *v) const;
  const RopePath &path() const { return path_; }
  double stiffness(double t) const { return EA_ / restLength(t); } // EA / L0(t), N/m
  double restLength(double t) const { return L0_ + payout_.value(t); }
  double payout(double t) const { return payout_.value(t); }
  double damping() const { return c_; }
  bool hasWinch() const { return winch_; }
  // The first non-finite force met (a segment of zero length, a NaN state):
  // never taken for slack.
  std::string fault() const override { return fault_; }

private:
  // evaluate() after the path's geometry g at in.q and, with J, its Hessian lqq.
  void evaluateAt(const AssemblyContext &ctx, const ItemValues &in, const RopePath::Geometry &g,
                  const Eigen::MatrixXd &lqq, double *residual, double *J) const;

  std::string name_;
  RopePath path_;
  double EA_, L0_, c_;
  TimeFunction payout_;
  bool winch_;
  mutable std::string fault_;
};

} // namespace boomdyn
