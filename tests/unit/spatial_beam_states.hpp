// Random states of the spatial beam element (docs/model.md §1.7) for the
// central-difference, rigid-motion and objectivity tests: deformed and
// twisted elements at random places and orientations, node reference triads
// near (not equal to) the tangents, and the rigid velocities of a state.
#pragma once

#include "boomdyn/spatial_beam_element.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <random>

namespace boomdyn::spatial_beam::states {

inline Mat3 randomRotation(std::mt19937 &rng, double maxAngle)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 axis(u(rng), u(rng), u(rng));
  return Eigen::AngleAxisd(maxAngle * u(rng), axis.normalized()).toRotationMatrix();
}

// Size of coordinate k: positions scale with l, slopes and angles are ~1.
inline double coordinateScale(int k, double l) { return (k % kNodeCoordinates) < 3 ? l : 1.0; }

struct State {
  Geometry geo;
  Vec14 e;
};

// A straight element along a random triad, perturbed by amp (relative), the
// nodes twisted by up to twist rad, the node references turned by up to
// 0.3 rad from the element's triad.
inline State deformedState(std::mt19937 &rng, double l, double amp, double twist)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Mat3 triad = randomRotation(rng, 3.0);
  State s;
  s.geo = straightGeometry(triad, l);
  for (auto &node : s.geo.node) {
    const Mat3 R = randomRotation(rng, 0.3);
    node.tangent = R * node.tangent, node.normal = R * node.normal;
  }
  s.e = straightElement(Vec3(u(rng), u(rng), u(rng)), triad, l);
  for (int k = 0; k < kCoordinates; ++k) s.e[k] += amp * u(rng) * coordinateScale(k, l);
  s.e[twistIndex(0)] = twist * u(rng);
  s.e[twistIndex(1)] = twist * u(rng);
  return s;
}

inline Vec14 randomVelocity(std::mt19937 &rng, double l, double speed)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec14 v;
  for (int k = 0; k < kCoordinates; ++k) v[k] = speed * u(rng) * coordinateScale(k, l);
  return v;
}

// The state rotated as a whole by R about the origin with the node
// references held fixed: positions and slopes rotate, the twists change so
// that each node's section triad is the rotated one. The section triads fix
// the twists only modulo 2 pi; the element's total twist (theta_1 + beta -
// theta_0, beta the principal angle between the node references carried to
// node 1) counts the turns, so theta_1 is chosen to keep the torsion.
inline Vec14 rotatedWithFixedReferences(const State &s, const Mat3 &R)
{
  Vec14 e = s.e;
  for (int a = 0; a < 2; ++a) {
    const Mat3 d = nodeTriad(s.geo.node[a], s.e.segment<3>(slopeIndex(a)), s.e[twistIndex(a)]);
    e.segment<3>(positionIndex(a)) = R * s.e.segment<3>(positionIndex(a));
    e.segment<3>(slopeIndex(a)) = R * s.e.segment<3>(slopeIndex(a));
    e[twistIndex(a)] = twistFor(s.geo.node[a], e.segment<3>(slopeIndex(a)), R * d.col(1));
  }
  const double turns =
      (strainsAt(s.geo, s.e, 0.5).torsion - strainsAt(s.geo, e, 0.5).torsion) * s.geo.l / (2.0 * M_PI);
  e[twistIndex(1)] += 2.0 * M_PI * std::round(turns);
  return e;
}

// blockdiag(R, R, 1, R, R, 1): how a force or a velocity of the element
// transforms under a rotation of the state with its references.
inline Mat14 rotationOfCoordinates(const Mat3 &R)
{
  Mat14 T = Mat14::Identity();
  for (int a = 0; a < 2; ++a) {
    T.block<3, 3>(positionIndex(a), positionIndex(a)) = R;
    T.block<3, 3>(slopeIndex(a), slopeIndex(a)) = R;
  }
  return T;
}

// The rate of the coordinates in the rigid motion with angular velocity w and
// velocity v of the origin: rdot = v + w x r, r'dot = w x r', and the twist
// rates that turn each node's section triad with w (from the triad's
// derivatives: d2dot = w x d2, d d2/d theta = d3).
inline Vec14 rigidVelocity(const State &s, const Vec3 &w, const Vec3 &v)
{
  Vec14 edot = Vec14::Zero();
  for (int a = 0; a < 2; ++a) {
    edot.segment<3>(positionIndex(a)) = v + w.cross(s.e.segment<3>(positionIndex(a)));
    edot.segment<3>(slopeIndex(a)) = w.cross(s.e.segment<3>(slopeIndex(a)));
  }
  for (int a = 0; a < 2; ++a) {
    const SectionFrame f = sectionFrame(s.geo, s.e, a);
    Vec14 partial = edot;
    partial[twistIndex(0)] = partial[twistIndex(1)] = 0;
    const Vec3 d2dot = f.dGrad[1] * partial;
    edot[twistIndex(a)] = (w.cross(f.d.col(1)) - d2dot).dot(f.d.col(2)) / f.dGrad[1].col(twistIndex(a)).dot(f.d.col(2));
  }
  return edot;
}

inline double relErr(const Eigen::MatrixXd &a, const Eigen::MatrixXd &b) { return (a - b).norm() / b.norm(); }

// A steel box 0.3 m x 0.4 m, wall 10 mm, with retardation times giving a few
// per cent damping in the low modes.
inline Section steelBox(AxialIntegration axial)
{
  Section s = boxSection(2.1e11, 8.1e10, 7850, 0.3, 0.4, 0.01);
  s.etaA = 2.0e-4, s.etaB = 3.0e-3, s.etaT = 1.0e-3;
  s.axialIntegration = axial;
  s.length = 100.0; // Assumed: pointwise weight gamma ~ 0.02, the projection carries the axial energy
  return s;
}

} // namespace boomdyn::spatial_beam::states
