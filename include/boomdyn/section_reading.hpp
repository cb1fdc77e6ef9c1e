// What a sensor and the ParaView output read at a material point of a
// spatial body (docs/output.md): position and velocity of the axis point,
// the section triad, its angular velocity, the twist and the strains.
#pragma once

#include "boomdyn/spatial_body.hpp"

namespace boomdyn {

struct SectionReading {
  Vec3 position = Vec3::Zero(), velocity = Vec3::Zero();
  // Columns d1 (along the axis), d2, d3 in global axes: the rotation from
  // section to global axes.
  Mat3 triad = Mat3::Identity();
  // omega = 1/2 sum_k d_k x d_k' (global axes, rad/s).
  Vec3 angularVelocity = Vec3::Zero();
  // The angle (rad, in (-pi, pi]) about d1 from the initial d2, carried onto
  // the current axis d1 by the smallest rotation from the initial d1, to the
  // current d2: the twist of the section, whatever chart of reference
  // triads the body uses. Undefined when d1 has turned by half a turn.
  double twist = 0;
  SpatialStrains strains; // 0 for a rigid body
};

// The reading at s (inside loc's element), from the values q and velocities
// v of loc.dofs, in that order.
SectionReading readSection(const SpatialBody &body, const SpatialLocation &loc, double s, const double *q,
                           const double *v);

// The twist (as SectionReading::twist) of the triad `current` against the
// section's initial triad.
double sectionTwist(const Mat3 &initial, const Mat3 &current);

} // namespace boomdyn
