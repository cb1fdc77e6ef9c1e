// Kinematics of the spatial ANCF beam element with twist ("ANCF14",
// docs/model.md §1.7): pure kernels, no PETSc.
//
// Element vector e = [r_0, r'_0, theta_0, r_1, r'_1, theta_1] (14 entries):
// per node the position r (3), the slope r' = dr/dx (3) and the twist angle
// theta (1) of the section about the tangent. The centreline is the cubic
// Hermite interpolation of the planar element (ancf::shapeValues) in each
// direction. Each node carries a fixed reference triad (NodeFrame); the
// node's section triad is that triad carried onto the current tangent by the
// smallest rotation and then turned by theta about the tangent. Inside the
// element the triad is node 0's section triad carried along the centreline by
// smallest rotations, turned by an angle interpolated linearly between the two
// nodes' values; curvatures and torsion are the components of its rotation
// rate, so they do not change when the whole element is rotated (objective).
#pragma once

#include <Eigen/Dense>

namespace boomdyn::spatial_beam {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
constexpr int kCoordinates = 14;     // per element
constexpr int kNodeCoordinates = 7;  // per node: r (3), r' (3), theta (1)
using Vec14 = Eigen::Matrix<double, kCoordinates, 1>;
using Mat14 = Eigen::Matrix<double, kCoordinates, kCoordinates>;
using Mat3x14 = Eigen::Matrix<double, 3, kCoordinates>;

// Offsets of a node's entries in the element vector (node a = 0, 1).
constexpr int positionIndex(int a) { return kNodeCoordinates * a; }
constexpr int slopeIndex(int a) { return kNodeCoordinates * a + 3; }
constexpr int twistIndex(int a) { return kNodeCoordinates * a + 6; }

// Reference triad of a node: unit tangent and unit normal (normal ⊥ tangent);
// the third axis is tangent x normal. The node's section triad at twist theta
// is R_t(theta) SR(tangent -> t) applied to this triad, t = r'/|r'|. The
// smallest rotation SR(a -> t) is singular at t = -a: a body keeps the
// reference near the current tangent by rebasing (rebasedNodeFrame).
struct NodeFrame {
  Vec3 tangent = Vec3::UnitX();
  Vec3 normal = Vec3::UnitY();
};

// An element: its length l (the reference arc length, x in [0, l], xi = x/l)
// and the reference triads of its two nodes (shared with the neighbouring
// elements at those nodes, so that the section triad is continuous).
struct Geometry {
  double l = 1.0;
  NodeFrame node[2];
};

// The four strains at xi: axial (Green) strain eps = (|r'|^2 - 1)/2, torsion
// K1 and the curvatures K2, K3 about the section axes d2, d3; rotation rates
// per unit reference length x (rad/m).
struct Strains {
  double axial = 0, torsion = 0, curvature2 = 0, curvature3 = 0;
};
Strains strainsAt(const Geometry &geo, const Vec14 &e, double xi);

// Position r and section triad (d1 = tangent, d2, d3 as columns of d) at xi,
// with their derivatives with respect to the 14 coordinates (rows: the
// vector's components). r is linear in e (zero second derivatives).
struct SectionFrame {
  Vec3 r;
  Mat3 d;
  Mat3x14 rGrad;
  Mat3x14 dGrad[3];
};
SectionFrame sectionFrame(const Geometry &geo, const Vec14 &e, double xi);
// sum_c w_c d^2 (d_i)_c / de^2 for director i = 0 (d1), 1 (d2), 2 (d3): the
// second derivative of the triad contracted with a 3-vector (a joint row
// w . d_i, or a moment's virtual work, differentiated twice).
Mat14 sectionFrameHessian(const Geometry &geo, const Vec14 &e, double xi, int director, const Vec3 &w);

// The generalized force of a moment M (N m, fixed in space) on the section at
// xi, work-conjugate to the section's virtual rotation
// delta psi = 1/2 sum_i d_i x delta d_i:  Q = 1/2 sum_i (dd_i/de)^T (M x d_i),
// and, if dQ != nullptr, dQ/de (not symmetric: a moment of fixed axis is not
// conservative in space). The sign is that of an applied force (added to
// the right-hand side).
void sectionMomentForce(const Geometry &geo, const Vec14 &e, double xi, const Vec3 &M, Vec14 &Q, Mat14 *dQ);

// The node's section triad (columns d1, d2, d3) from its slope and twist.
Mat3 nodeTriad(const NodeFrame &ref, const Vec3 &slope, double theta);
// The twist theta at which the node's section axis d2 points along d2 (the
// component of d2 normal to the tangent): the inverse of nodeTriad.
double twistFor(const NodeFrame &ref, const Vec3 &slope, const Vec3 &d2);
// A reference triad equal to the node's current zero-twist triad
// SR(ref.tangent -> t) ref: with it, the same theta gives the same section
// triad (a change of chart, not of state) and the smallest rotation is the
// identity again, far from its singularity.
NodeFrame rebasedNodeFrame(const NodeFrame &ref, const Vec3 &slope);

// A straight, unstrained, untwisted element from p0 along triad's first
// column, with both node references equal to triad (columns d1, d2, d3).
Vec14 straightElement(const Vec3 &p0, const Mat3 &triad, double l);
Geometry straightGeometry(const Mat3 &triad, double l);

} // namespace boomdyn::spatial_beam
