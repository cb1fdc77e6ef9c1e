// Type `point_force` of spatial scenes (section loads, dimension 3): a force
// at a material point, fixed in the global axes (`force`) or following the
// section (`follower_force`, in section axes), times scale(t)
// (spatial_point_load.hpp; schema and builder shared with point_moment).
#include "spatial_point_load_schema.hpp"

namespace boomdyn {

PhysicsType spatialPointForceType()
{
  return spatialPointLoadType({"point_force", "force", "force", "N", "[Fx, Fy, Fz]",
                               "force in the section axes at the point: it turns with the body (a follower load)"});
}

} // namespace boomdyn
