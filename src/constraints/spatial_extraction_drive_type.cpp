// Type `extraction_drive` of spatial scenes (section constraints, dimension
// 3): the same drive of a sliding joint's contact coordinate as the planar
// type (extraction_drive_type.cpp, slack_drive.hpp); a spatial sliding joint
// keeps its slack coordinate under the same scratch keys.
#include "boomdyn/physics_type.hpp"

namespace boomdyn {

PhysicsType extractionDriveType();

PhysicsType spatialExtractionDriveType()
{
  PhysicsType t = extractionDriveType();
  t.dimension = 3;
  return t;
}

} // namespace boomdyn
