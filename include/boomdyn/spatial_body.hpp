// The spatial body interface: what joints, loads, masses and outputs of a
// spatial scene (dimension 3) see of a body. At a material coordinate s a
// spatial body gives the position r(s) of its axis point and the section
// triad (d1 along the axis, d2, d3 across it), both with their first
// derivatives with respect to the coordinates they depend on, and second
// derivatives contracted with a vector (curvatureTerm), the spatial
// counterpart of the planar Body's curvatureTerm. Rigid bodies (Euler
// parameters) and spatial beams (position, slope and twist per node) both
// implement it, so a spherical joint or a follower force is written once.
//
// A vector fixed in the section at s is u = sum_k u'_k d_k; a rotation rate
// follows from the triad as omega = 1/2 sum_k d_k x d_k' (spatial_frame.hpp).
#pragma once

#include "boomdyn/body.hpp"

namespace boomdyn {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// The most coordinates one spatial sample depends on (a beam element: 14).
constexpr int kSpatialMaxDofs = 16;
using SpatialJacobian = Eigen::Matrix<double, 3, kSpatialMaxDofs>;
using SpatialHessian = Eigen::Matrix<double, kSpatialMaxDofs, kSpatialMaxDofs>;

// The coordinates a point of a spatial body depends on.
struct SpatialLocation {
  int count = 0;
  std::array<PetscInt, kSpatialMaxDofs> dofs{}; // global coordinate indices
  int element = 0;                              // element index (beams), 0 for rigid bodies
  double xi = 0;                                // local parameter in the element
  double s = 0;                                 // material coordinate
  double begin = 0, end = 0;                    // material span of the element
};

// Position and section triad at s and their derivatives with respect to the
// location's coordinates (3 x count, stored 3 x kSpatialMaxDofs).
struct SpatialSample {
  Vec3 r;                             // position of the axis point
  Mat3 triad;                         // columns d1 (along the axis), d2, d3
  SpatialJacobian r_q;                // dr/dq
  std::array<SpatialJacobian, 3> d_q; // d(d_k)/dq
};

// The strains of a beam's section: Green axial strain (|r'|^2 - 1)/2, the
// torsion K1 and the curvatures K2, K3 about the section axes d2, d3 (rad
// per m of reference length; docs/model.md §1.7).
struct SpatialStrains {
  double axial = 0, torsion = 0, curvature2 = 0, curvature3 = 0;
};

// What curvatureTerm differentiates twice.
enum class SpatialField { Position = 0, Director1 = 1, Director2 = 2, Director3 = 3 };

class SpatialBody : public BodyBase {
public:
  int dimension() const override { return 3; }
  // Which coordinates the point at s depends on. s must lie in [0, length].
  virtual SpatialLocation locate(double s) const = 0;
  // Evaluate at s (inside the location's element), given the values of loc.dofs in order.
  virtual void sample(const SpatialLocation &loc, double s, const double *values, SpatialSample &out) const = 0;
  // d2(w . x)/dq2 (count x count, stored kSpatialMaxDofs square) for x = r
  // (Position) or the director d_k. Zero for a field linear in q.
  virtual void curvatureTerm(const SpatialLocation &loc, double s, const double *values, SpatialField field,
                             const Vec3 &w, SpatialHessian &H) const = 0;
  // The initial position of the axis point at s and the initial triad (the
  // placement in the scene), for derived defaults and body-fixed vectors.
  virtual Vec3 initialPosition(double s) const = 0;
  virtual Mat3 initialTriad(double s) const = 0;
  // The strains of the section at a location (SpatialStrains; all 0 for a
  // rigid body), for sensors and the output.
  virtual SpatialStrains sectionStrains(const SpatialLocation &loc, const double *values) const
  {
    (void)loc, (void)values;
    return {};
  }

protected:
  SpatialBody(std::string name, double length, PetscInt first) : BodyBase(std::move(name), length, first) {}
};

} // namespace boomdyn
