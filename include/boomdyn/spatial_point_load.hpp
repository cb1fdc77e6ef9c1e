// Point loads and masses of spatial scenes, on the spatial body interface
// (spatial_body.hpp).
//
// SpatialPointLoad: a force and a moment at a material point, times
// scale(t); each part fixed in the global axes or following the section
// triad T (follower: f = T f'). Generalized force Q = r_q^T f + W^T m with
// the virtual rotation dtheta = W dq, W = 1/2 sum_k [d_k]x d(d_k)/dq.
//
// SpatialPointMass: a mass at a material point with its weight, and a
// rotary inertia J' in the section axes (rigid bodies only: J' adds to the
// body's own through the Euler parameters). The translational part
// m r_q^T (r'' - g), r'' = r_q a + (v^T d2r/dq2 v), assumes d2r/dq2
// independent of q, which holds for rigid bodies with Euler parameters
// (r quadratic in p) and for ANCF beams (r linear).
#pragma once

#include "boomdyn/point_load.hpp"
#include "boomdyn/spatial_body.hpp"
#include "boomdyn/time_function.hpp"
#include "boomdyn/work_item.hpp"

namespace boomdyn {

class SpatialPointLoad : public WorkItem {
public:
  struct Parts {
    Vec3 force = Vec3::Zero(), followerForce = Vec3::Zero();   // global; section axes
    Vec3 moment = Vec3::Zero(), followerMoment = Vec3::Zero(); // global; section axes
  };
  SpatialPointLoad(std::string name, const SpatialBody &body, double s, Parts parts, TimeFunction scale);
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  // The generalized force Q (count entries) at scale 1 and, if K is not
  // null, dQ/dq (count x count, column-major).
  void generalizedForce(const double *q, Eigen::VectorXd &Q, Eigen::MatrixXd *K) const;

private:
  std::string name_;
  const SpatialBody *body_;
  double s_;
  SpatialLocation loc_;
  Parts parts_;
  TimeFunction scale_;
};

class SpatialRigidBody;

class SpatialPointMass : public WorkItem {
public:
  // rotary: J' in the section axes (zero: none); needs a rigid body.
  SpatialPointMass(std::string name, const SpatialBody &body, double s, double mass, const Mat3 &rotary,
                   const Vec3 &gravity, Release release = {});
  std::string name() const override { return name_; }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(const AssemblyContext &ctx, const ItemValues &in, double *residual, double *J) const override;
  void energy(const AssemblyContext &ctx, const ItemValues &in, EnergyParts &e) const override;
  void scales(const ItemValues &in, double &massDiag, double &stiffDiag, int &count) const override;
  void breakpoints(std::vector<double> &out) const override { release_.breakpoints(out); }

private:
  std::string name_;
  const SpatialBody *body_;
  double s_;
  SpatialLocation loc_;
  double mass_;
  Mat3 rotary_;
  bool hasRotary_;
  Vec3 gravity_;
  Release release_;
};

} // namespace boomdyn
