// A planar scene as a spatial scene in its plane (option -boom_spatial), so
// that every planar reference also checks the spatial code. The plane is
// z = 0; every vector gets z = 0. Per component:
//
//   rigid body (planar)   -> spatial rigid body: mass rhoA L, inertia
//                            m L^2/12 about all three body axes (the axial
//                            moment does not enter a motion in the plane;
//                            any positive value gives the same results),
//                            axis (cos a, sin a, 0), up (-sin a, cos a, 0)
//   pin                   -> revolute_joint about z (rows 0, 1 = the pin's)
//   clamp, fixed angle    -> spatial clamp (rows 0, 1 = pin; row 3 = angle)
//   clamp, angle(t)       -> revolute_joint about z + angle_drive "<name>.angle"
//   angle_drive           -> angle_drive about z, zero [1, 0, 0] (row 0 = the planar row)
//   point_force           -> point_force [Fx, Fy, 0]
//   point_mass            -> point_mass (no rotary inertia)
//   point_sensor          -> point_sensor (x, y of the planar run, and z)
//
// Anything else (sliding joints, ropes, frame sensors, tracking) is refused
// with SpatialEmbeddingError naming the component.
#pragma once

#include "boomdyn/scene.hpp"

#include <stdexcept>

namespace boomdyn {

class SpatialEmbeddingError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

Scene spatialEmbedding(const Scene &planar);

} // namespace boomdyn
