// Type `clamp` of spatial scenes (section constraints, dimension 3): a weld
// to the ground. The material point stays at a ground point (3 rows) and the
// section triad keeps its initial orientation (3 rows: d1 . g2 = d1 . g3 =
// d2 . g3 = 0 with g_k the initial triad; spatial_joint.hpp).
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_joint.hpp"

namespace boomdyn {

namespace {

void completeSpatialClamp(ComponentSpec &spec, const Scene &scene)
{
  if (!spec.has("point")) spec.set("point", initialPoint3(scene, spec.point()));
}

void buildSpatialClamp(const ComponentSpec &spec, ModelBuilder &b)
{
  const SpatialBody &body = b.spatialBody(spec.text("body"));
  const double s = spec.number("at");
  const Vec3d p = spec.vec3("point");
  const Mat3 g = body.initialTriad(s);
  std::vector<SpatialDotRow> rows(3);
  const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int k = 0; k < 3; ++k) {
    rows[k].u = Vec3::Unit(pairs[k][0]);
    rows[k].n1 = Vec3::Zero();
    rows[k].n2 = g.col(pairs[k][1]);
  }
  b.addConstraint(std::make_shared<SpatialJoint>(spec.name, SpatialEnd::onBody(body, s),
                                                 SpatialEnd::ground(Vec3(p[0], p[1], p[2])), true, rows),
                  spec.mark);
}

} // namespace

PhysicsType spatialClampType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "clamp";
  t.schema.summary = "Holds a material point at a ground point with the section's initial orientation (a weld: "
                     "position and all three rotations).";
  t.schema.keys = {
      bodyKey("body", "the clamped body"),
      atKey("at", "body", "material point of the body that is held"),
      key("point", ValueKind::Vec3, "m", Need::Optional, "ground point [x, y, z]").derived("where the point starts"),
  };
  t.schema.rules = {
      forbid("angle", "not allowed for a spatial clamp (it keeps the initial orientation; turn a body with a "
                      "revolute_joint and an angle_drive)"),
      forbid("other", "not allowed for a clamp (a clamp holds a body to the ground)"),
      forbid("other_at", "not allowed for a clamp (a clamp holds a body to the ground)"),
  };
  t.complete = completeSpatialClamp;
  t.build = buildSpatialClamp;
  return t;
}

} // namespace boomdyn
