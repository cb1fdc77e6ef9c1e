// A body owns a contiguous block of the global coordinate vector (BodyBase,
// the same in planar and spatial scenes). A planar body (Body) offers a
// "centerline" view: position r(s) and its s-derivatives at a material
// coordinate s, with their derivatives with respect to the coordinates they
// depend on. Joints, loads and sensors only use this view, so they do not
// care whether they touch an ANCF beam or a rigid body. Spatial bodies offer
// the spatial view of spatial_body.hpp instead.
#pragma once

#include <Eigen/Dense>
#include <petscsys.h>

#include <array>
#include <string>
#include <vector>

namespace boomdyn {

using Vec2 = Eigen::Vector2d;

// The coordinates a centerline point depends on (at most 8).
struct CenterlineLocation {
  int count = 0;
  std::array<PetscInt, 8> dofs{}; // global coordinate indices
  int element = 0;                // element index (beams), 0 for rigid bodies
  double xi = 0;                  // local parameter in the element
  double s = 0;                   // material coordinate
  double begin = 0, end = 0;      // material span of the element
};

// r, r_s, r_ss, r_sss at s and their (linear) derivatives with respect to
// the location's coordinates: d r / dq = Rq etc. (2 x count, stored 2 x 8).
struct CenterlineSample {
  std::array<Vec2, 4> r;                              // r, r', r'', r'''
  std::array<Eigen::Matrix<double, 2, 8>, 4> r_q;     // d(r^(k))/dq
  // True when r^(k) is linear in q (ANCF): second q-derivatives vanish.
  bool linear = true;
};

// What every body is, whatever the dimension of its scene: a name, a length
// along which material coordinates s run, and its block of coordinates.
class BodyBase {
public:
  virtual ~BodyBase() = default;
  const std::string &name() const { return name_; }
  double length() const { return length_; }
  PetscInt firstCoordinate() const { return first_; }
  virtual PetscInt numCoordinates() const = 0;
  // Coordinates of the initial (undeformed) configuration, numCoordinates() values.
  virtual void initialCoordinates(double *q) const = 0;
  // Velocities of the initial state, numCoordinates() values; the caller
  // zeroes them first (bodies that start at rest leave them).
  virtual void initialVelocities(double *v) const { (void)v; }
  // 2: a planar body (Body, below); 3: a spatial body (SpatialBody).
  virtual int dimension() const = 0;
  // For the output (ParaView polylines, docs/output.md): the number of
  // straight segments the body's axis is drawn with, between equally spaced
  // material points from s = 0 to the length. A rigid body is one segment
  // between its ends; a beam samples each element at kOutputSegmentsPerElement
  // points, which shows its cubic interpolation and not only the nodes.
  virtual int outputSegments() const { return 1; }
  static constexpr int kOutputSegmentsPerElement = 4;

protected:
  BodyBase(std::string name, double length, PetscInt first) : name_(std::move(name)), length_(length), first_(first) {}
  std::string name_;
  double length_;
  PetscInt first_;
};

// A planar body and its centerline view.
class Body : public BodyBase {
public:
  int dimension() const override { return 2; }
  // Which coordinates the point at s depends on. s must lie in [0, length].
  virtual CenterlineLocation locate(double s) const = 0;
  // Evaluate at s (inside the location's element: s may differ from loc.s as
  // long as it stays within that element, which sliding joints use), given
  // the values of loc.dofs in order.
  virtual void sample(const CenterlineLocation &loc, double s, const double *values, CenterlineSample &out) const = 0;
  // Second derivative of w . r^(k)(q) with respect to q (count x count), for
  // bodies whose centerline is nonlinear in q. Zero for ANCF beams.
  virtual void curvatureTerm(const CenterlineLocation &loc, double s, const double *values, int k, const Vec2 &w,
                             Eigen::Matrix<double, 8, 8> &H) const
  {
    (void)loc, (void)s, (void)values, (void)k, (void)w;
    H.setZero();
  }

protected:
  Body(std::string name, double length, PetscInt first) : BodyBase(std::move(name), length, first) {}
};

} // namespace boomdyn
