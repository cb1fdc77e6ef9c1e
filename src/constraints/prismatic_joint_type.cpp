// Type `prismatic_joint` (section constraints, spatial scenes): the
// material point of a body slides along an axis fixed in another body or
// the ground without any rotation relative to it. Free: translation along
// the axis. Rows: two offsets across the axis, the optional slide drive,
// two alignment rows and the roll row (spatial_axis_joint.hpp,
// spatial_joint.hpp).
#include "spatial_axis_joint.hpp"

namespace boomdyn {

PhysicsType prismaticJointType()
{
  return axisSliderType("prismatic_joint",
                        "A material point slides along an axis fixed in another body or the ground and the body keeps "
                        "its orientation relative to it: only the translation along the axis stays free (5 rows; 6 "
                        "with 'slide').",
                        true);
}

} // namespace boomdyn
