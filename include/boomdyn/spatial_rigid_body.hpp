// Spatial rigid body: coordinates q = (x, p), the centre of mass x (3) and
// the Euler parameters p (4) of the rotation R(p) from body to global axes
// (euler_parameters.hpp), with the normalization row p.p - 1 = 0
// (EulerNormalization). The body has an axis of length L along its body x
// axis, on which material coordinates s run from the point s = 0; the
// centre of mass sits at c' in body axes from that point, so the axis point
// at s is r(s) = x + R(p) ((s, 0, 0) - c') and the section triad is R(p).
// Its inertia (SpatialRigidInertia) is the mass m at x and the inertia
// tensor J' about the centre of mass in body axes: M = diag(m I, 4 G^T J' G),
// with the gyroscopic term 8 G(pdot)^T J' G pdot (docs/model.md §9).
#pragma once

#include "boomdyn/constraint.hpp"
#include "boomdyn/spatial_body.hpp"
#include "boomdyn/work_item.hpp"

namespace boomdyn {

class SpatialRigidBody : public SpatialBody {
public:
  // origin: the point s = 0 at t = 0; axes: the initial body axes as the
  // columns of a rotation matrix; centerOfMass: c' (body axes, from s = 0).
  SpatialRigidBody(std::string name, double length, double mass, const Mat3 &inertia, const Vec3 &centerOfMass,
                   const Vec3 &origin, const Mat3 &axes, PetscInt first);
  PetscInt numCoordinates() const override { return 7; }
  void initialCoordinates(double *q) const override;
  void initialVelocities(double *v) const override;
  // The initial velocity of the point s = 0 and angular velocity (global axes).
  void setInitialVelocity(const Vec3 &velocity, const Vec3 &angularVelocity)
  {
    velocity_ = velocity, angularVelocity_ = angularVelocity;
  }
  SpatialLocation locate(double s) const override;
  void sample(const SpatialLocation &loc, double s, const double *values, SpatialSample &out) const override;
  void curvatureTerm(const SpatialLocation &loc, double s, const double *values, SpatialField field, const Vec3 &w,
                     SpatialHessian &H) const override;
  Vec3 initialPosition(double s) const override { return origin_ + axes_.col(0) * s; }
  Mat3 initialTriad(double) const override { return axes_; }
  double mass() const { return mass_; }
  const Mat3 &inertia() const { return inertia_; }
  // The material point s relative to the centre of mass, in body axes.
  Vec3 bodyPoint(double s) const { return Vec3(s, 0, 0) - centerOfMass_; }

private:
  double mass_;
  Mat3 inertia_;
  Vec3 centerOfMass_, origin_;
  Mat3 axes_;
  Vec3 velocity_ = Vec3::Zero(), angularVelocity_ = Vec3::Zero();
};

// Inertia and weight of a spatial rigid body.
class SpatialRigidInertia : public WorkItem {
public:
  SpatialRigidInertia(const SpatialRigidBody &body, const Vec3 &gravity) : body_(&body), gravity_(gravity) {}
  std::string name() const override { return body_->name(); }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  void scales(const ItemValues &in, double &massDiag, double &stiffDiag, int &count) const override;

private:
  const SpatialRigidBody *body_;
  Vec3 gravity_;
};

// p.p - 1 = 0 for the Euler parameters at coordinates first .. first + 3.
class EulerNormalization : public Constraint {
public:
  EulerNormalization(std::string name, PetscInt first) : name_(std::move(name)), first_(first) {}
  std::string name() const override { return name_; }
  int numRows() const override { return 1; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override;
  bool dependsOnTime() const override { return false; }
  const char *rowUnit(int) const override { return "(dimensionless)"; }

private:
  std::string name_;
  PetscInt first_;
};

} // namespace boomdyn
