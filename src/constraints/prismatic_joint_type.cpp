// Type `prismatic_joint` (section constraints, spatial scenes): the
// material point of a body slides along an axis fixed in another body or
// the ground without any rotation relative to it. Free: translation along
// the axis. Rows: two offsets across the axis, the optional slide drive,
// two alignment rows and the roll row (spatial_axis_joint.hpp,
// spatial_joint.hpp).
#include "boomdyn/physics_type.hpp"
#include "spatial_axis_joint.hpp"

namespace boomdyn {

namespace {
void buildPrismatic(const ComponentSpec &spec, ModelBuilder &b) { buildAxisSlider(spec, b, true); }
} // namespace

PhysicsType prismaticJointType()
{
  PhysicsType t;
  t.dimension = 3;
  axisSliderSchema(t.schema, "prismatic_joint",
                   "A material point slides along an axis fixed in another body or the ground and the body keeps "
                   "its orientation relative to it: only the translation along the axis stays free (5 rows; 6 with "
                   "'slide').");
  t.complete = completeAxisSlider;
  t.check = checkJointAxis;
  t.build = buildPrismatic;
  return t;
}

} // namespace boomdyn
