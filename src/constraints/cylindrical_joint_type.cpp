// Type `cylindrical_joint` (section constraints, spatial scenes): the
// material point of a body slides along an axis fixed in another body or
// the ground and turns about it; the axis fixed in the body stays along it.
// Free: translation along and rotation about the axis. Rows: two offsets
// across the axis, the optional slide drive, two alignment rows
// (spatial_axis_joint.hpp, spatial_joint.hpp).
#include "spatial_axis_joint.hpp"

namespace boomdyn {

PhysicsType cylindricalJointType()
{
  return axisSliderType("cylindrical_joint",
                        "A material point slides along an axis fixed in another body or the ground and the body turns "
                        "about it: translation along and rotation about the axis stay free (4 rows; 5 with 'slide').",
                        false);
}

} // namespace boomdyn
