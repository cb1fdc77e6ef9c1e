// The registration list of physics types: one line per type. Each maker is
// defined in the type's own file (src/constraints/pin_type.cpp, ...). The
// order within a section is the order of its `type:` choices in messages
// and of its tables in docs/scenes.md.
#include "boomdyn/physics_type.hpp"

#include <cmath>
#include <stdexcept>

#define BOOMDYN_PHYSICS_TYPES(X) \
  X(ancfBeamType) \
  X(rigidBodyType) \
  X(clampType) \
  X(pinType) \
  X(angleDriveType) \
  X(slidingJointType) \
  X(extractionDriveType) \
  X(ropeType) \
  X(elasticRopeType) \
  X(distanceType) \
  X(groundContactType) \
  X(hydraulicCylinderType) \
  X(pointForceType) \
  X(pointMassType) \
  X(springType) \
  X(pointSensorType) \
  X(frameSensorType) \
  X(spatialRigidBodyType) \
  X(sphericalJointType) \
  X(revoluteJointType) \
  X(cylindricalJointType) \
  X(prismaticJointType) \
  X(spatialClampType) \
  X(spatialAngleDriveType) \
  X(spatialSlidingJointType) \
  X(spatialExtractionDriveType) \
  X(spatialPointForceType) \
  X(spatialPointMomentType) \
  X(spatialPointMassType) \
  X(spatialAncfBeamType) \
  X(spatialPointSensorType) \
  X(spatialFrameSensorType)

namespace boomdyn {

#define BOOMDYN_DECLARE_TYPE(maker) PhysicsType maker();
BOOMDYN_PHYSICS_TYPES(BOOMDYN_DECLARE_TYPE)
#undef BOOMDYN_DECLARE_TYPE

const std::vector<PhysicsType> &physicsTypes()
{
#define BOOMDYN_MAKE_TYPE(maker) maker(),
  static const std::vector<PhysicsType> types{BOOMDYN_PHYSICS_TYPES(BOOMDYN_MAKE_TYPE)};
#undef BOOMDYN_MAKE_TYPE
  return types;
}

const BodySpec &bodySpec(const Scene &scene, const std::string &name)
{
  for (const BodySpec &b : scene.bodies)
    if (b.name == name) return b;
  throw std::logic_error("scene '" + scene.file + "' has no body '" + name + "'");
}

Vec2d initialPoint(const Scene &scene, const PointRef &point)
{
  const BodySpec &b = bodySpec(scene, point.body);
  return {b.origin[0] + point.s * std::cos(b.angle), b.origin[1] + point.s * std::sin(b.angle)};
}

Vec3d initialPoint3(const Scene &scene, const PointRef &point)
{
  const BodySpec &b = bodySpec(scene, point.body);
  const double n = std::sqrt(b.axis[0] * b.axis[0] + b.axis[1] * b.axis[1] + b.axis[2] * b.axis[2]);
  Vec3d r = b.origin3;
  if (n > 0)
    for (int i = 0; i < 3; ++i) r[i] += point.s * b.axis[i] / n;
  return r;
}

KeySchema bodyKey(const std::string &key, const std::string &help)
{
  return boomdyn::key(key, ValueKind::Body, "", Need::Required, help);
}

KeySchema atKey(const std::string &key, const std::string &body, const std::string &help)
{
  return boomdyn::key(key, ValueKind::MaterialCoordinate, "m", Need::Required, help).onBody(body);
}

std::vector<const PhysicsType *> physicsTypesOf(const std::string &section, int dimension)
{
  std::vector<const PhysicsType *> out;
  for (const PhysicsType &t : physicsTypes())
    if (t.schema.section == section && t.dimension == dimension) out.push_back(&t);
  return out;
}

const PhysicsType *findPhysicsType(const std::string &section, const std::string &type, int dimension)
{
  for (const PhysicsType &t : physicsTypes())
    if (t.schema.section == section && t.schema.type == type && t.dimension == dimension) return &t;
  return nullptr;
}

const PhysicsType &bodyType(BodySpec::Type kind)
{
  for (const PhysicsType &t : physicsTypes())
    if (t.schema.section == "bodies" && t.bodyKind == kind) return t;
  throw std::logic_error("no body type registered for BodySpec::Type " + std::to_string(static_cast<int>(kind)));
}

} // namespace boomdyn
