// The section of the spatial beam element (docs/model.md §1.7) at a point
// that is itself a variable: the axis point r, the section triad (d1, d2,
// d3) and the projections d_k . r as functions of the element's 14
// coordinates and of the arc length x along the element, with their first
// and second derivatives in these 15 variables (entries 0..13: the element
// vector, entry 14: x). A sliding joint's slack coordinate is x: its rows
// and their Jacobian and Hessian in both the beam's coordinates and the
// slack come from here (spatial_sliding_joint.hpp).
#pragma once

#include "boomdyn/spatial_beam_kinematics.hpp"

namespace boomdyn::spatial_beam {

constexpr int kSlackVariables = kCoordinates + 1; // the element vector, then x
constexpr int kSlackIndex = kCoordinates;
using Vec15 = Eigen::Matrix<double, kSlackVariables, 1>;
using Mat15 = Eigen::Matrix<double, kSlackVariables, kSlackVariables>;

// A scalar with its gradient and Hessian in the 15 variables.
struct SlackScalar {
  double value = 0;
  Vec15 grad;
  Mat15 hess;
};

struct SlackFrame {
  SlackScalar r[3];        // components of the axis point
  SlackScalar d[3][3];     // d[k][c]: component c of director d_{k+1}
  SlackScalar rd[3];       // d_{k+1} . r
  Vec3 position() const { return {r[0].value, r[1].value, r[2].value}; }
  Vec3 director(int k) const { return {d[k][0].value, d[k][1].value, d[k][2].value}; }
};

// The section at xi = x / l of the element (x measured from its node 0;
// xi may lie a little outside [0, 1]: the cubic axis continues smoothly).
SlackFrame slackFrame(const Geometry &geo, const Vec14 &e, double xi);

} // namespace boomdyn::spatial_beam
