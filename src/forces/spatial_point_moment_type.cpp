// Type `point_moment` (section loads, spatial scenes): a moment at a
// material point, fixed in the global axes (`moment`) or following the
// section (`follower_moment`, in section axes), times scale(t)
// (spatial_point_load.hpp; schema and builder shared with point_force).
#include "spatial_point_load_schema.hpp"

namespace boomdyn {

PhysicsType spatialPointMomentType()
{
  return spatialPointLoadType({"point_moment", "moment", "moment", "N m", "[Mx, My, Mz]",
                               "moment in the section axes at the point: it turns with the body"});
}

} // namespace boomdyn
