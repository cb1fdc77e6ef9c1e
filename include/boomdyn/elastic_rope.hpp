// Elastic tension-only rope over point pulleys (docs/model.md §7): the
// spanned length l(q) of a RopePath, an unstretched length L0, axial
// stiffness EA and damping c [N s/m]:
//     f = (EA/L0)(l - L0) + c dl/dt,   T = f if l > L0 and f > 0, else 0,
// and the generalized force -T l_q^T (residual +T l_q^T). While taut the
// Jacobian is exact: cQ (T l_qq + (EA/L0) l_q^T l_q + c l_q^T (l_qq v)^T)
// + cV c l_q^T l_q; while slack the rope adds nothing.
#pragma once

#include "boomdyn/rope_path.hpp"
#include "boomdyn/work_item.hpp"

namespace boomdyn {

class ElasticRope : public WorkItem {
public:
  ElasticRope(std::string name, RopePath path, double EA, double restLength, double damping);
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override { path_.coordinates(dofs); }
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  // Strain energy (EA/(2 L0)) (l - L0)^2 while l > L0; dissipation T l' - (EA/L0)(l - L0)+ l' >= 0.
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;

  // The rope at a state (q, v in coordinates() order).
  struct State {
    double length = 0, rate = 0; // l, dl/dt
    double stretch = 0;          // l - L0 (negative while slack by length)
    double force = 0;            // f = (EA/L0)(l - L0) + c dl/dt, before the tension-only cut
    double tension = 0;          // T
    bool taut = false;
  };
  State state(const double *q, const double *v) const;
  const RopePath &path() const { return path_; }
  double stiffness() const { return EA_ / L0_; } // EA / L0, N/m
  double restLength() const { return L0_; }
  double damping() const { return c_; }

private:
  std::string name_;
  RopePath path_;
  double EA_, L0_, c_;
};

} // namespace boomdyn
