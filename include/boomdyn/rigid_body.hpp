// Planar rigid body with a straight axis of length L, as a boom that does not
// deform. Coordinates q = (x_c, y_c, theta): the centre of mass (mid-axis)
// and the axis direction, so the mass matrix diag(m, m, m L^2/12) is
// constant. Centerline r(s) = p_c + (s - L/2) (cos theta, sin theta): the
// same interface as a beam, nonlinear in theta (see curvatureTerm).
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/work_item.hpp"

namespace boomdyn {

class RigidBody : public Body {
public:
  RigidBody(std::string name, double length, double mass, Vec2 origin, double angle, PetscInt first);
  PetscInt numCoordinates() const override { return 3; }
  void initialCoordinates(double *q) const override;
  CenterlineLocation locate(double s) const override;
  void sample(const CenterlineLocation &loc, double s, const double *values, CenterlineSample &out) const override;
  void curvatureTerm(const CenterlineLocation &loc, double s, const double *values, int k, const Vec2 &w,
                     Eigen::Matrix<double, 8, 8> &H) const override;
  double mass() const { return mass_; }
  double inertia() const { return mass_ * length_ * length_ / 12.0; }

private:
  double mass_;
  Vec2 origin_;
  double angle_;
};

// Inertia and weight of a rigid body.
class RigidBodyItem : public WorkItem {
public:
  RigidBodyItem(const RigidBody &body, const Vec2 &gravity) : body_(&body), gravity_(gravity) {}
  std::string name() const override { return body_->name(); }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  void scales(const ItemValues &in, double &massDiag, double &stiffDiag, int &count) const override;

private:
  const RigidBody *body_;
  Vec2 gravity_;
};

} // namespace boomdyn
