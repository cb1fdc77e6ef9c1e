// Loads at a material point of a body: a dead force F scale(t) (global
// frame) and a point mass (inertia and weight) on an ANCF beam or on a rigid
// body's axis, which may be released at a given time (quick release:
// docs/model.md §7.3).
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/time_function.hpp"
#include "boomdyn/work_item.hpp"

#include <limits>

namespace boomdyn {

// The time at which a mass leaves the system (inertia and weight), +inf
// for never. The step that lands on it still carries the mass; the restart
// there (AssemblyContext::rightLimit) and every later time do not.
struct Release {
  double at = std::numeric_limits<double>::infinity();
  bool gone(const AssemblyContext &ctx) const { return ctx.t > at || (ctx.rightLimit && ctx.t >= at); }
  void breakpoints(std::vector<double> &out) const
  {
    if (at < std::numeric_limits<double>::infinity()) out.push_back(at);
  }
};

class PointForce : public WorkItem {
public:
  PointForce(std::string name, const Body &body, double s, Vec2 force, TimeFunction scale);
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;

private:
  std::string name_;
  const Body *body_;
  double s_;
  CenterlineLocation loc_;
  Vec2 force_;
  TimeFunction scale_;
};

// On an ANCF beam (linear centerline): m S^T (S a - g).
class PointMass : public WorkItem {
public:
  PointMass(std::string name, const Body &body, double s, double mass, Vec2 gravity, Release release = {});
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  void breakpoints(std::vector<double> &out) const override { release_.breakpoints(out); }

private:
  std::string name_;
  const Body *body_;
  double s_;
  CenterlineLocation loc_;
  double mass_;
  Vec2 gravity_;
  Release release_;
};

// On the axis of a rigid body (q = x_c, y_c, theta), at the offset
// d = s - L/2 from its centre: r = p_c + d (cos theta, sin theta), so
//   r'' = a_c + d theta'' e_perp - d theta'^2 e,  residual r_q^T m (r'' - g),
// with the exact Jacobian (the centripetal term depends on theta' and theta).
class RigidPointMass : public WorkItem {
public:
  RigidPointMass(std::string name, const Body &body, double s, double mass, Vec2 gravity, Release release = {});
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  void breakpoints(std::vector<double> &out) const override { release_.breakpoints(out); }
  void scales(const ItemValues &in, double &massDiag, double &stiffDiag, int &count) const override;

private:
  std::string name_;
  PetscInt first_;
  double d_, mass_;
  Vec2 gravity_;
  Release release_;
};

} // namespace boomdyn
