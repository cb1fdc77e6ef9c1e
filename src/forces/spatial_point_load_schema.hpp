// The schema and builder shared by the spatial point loads (point_force and
// point_moment of spatial scenes): a vector fixed in the global axes or a
// follower vector in the section axes at a material point, times scale(t)
// (spatial_point_load.hpp). The types differ only in their words.
#pragma once

#include "boomdyn/physics_type.hpp"

namespace boomdyn {

struct SpatialPointLoadWords {
  const char *type;         // "point_force"
  const char *defaultName;  // "force"
  const char *quantity;     // "force": also the key of the fixed vector, "follower_" + it the follower's
  const char *unit;         // "N"
  const char *components;   // "[Fx, Fy, Fz]"
  const char *followerHelp; // help of the follower key
};

PhysicsType spatialPointLoadType(const SpatialPointLoadWords &words);

} // namespace boomdyn
