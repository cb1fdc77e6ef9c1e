// Loads at a material point of a body: a dead force F scale(t) (global
// frame) and a point mass (inertia and weight).
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/time_function.hpp"
#include "boomdyn/work_item.hpp"

namespace boomdyn {

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

class PointMass : public WorkItem {
public:
  PointMass(std::string name, const Body &body, double s, double mass, Vec2 gravity);
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;

private:
  std::string name_;
  const Body *body_;
  double s_;
  CenterlineLocation loc_;
  double mass_;
  Vec2 gravity_;
};

} // namespace boomdyn
