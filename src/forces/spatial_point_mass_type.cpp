// Type `point_mass` of spatial scenes (section masses, dimension 3): a
// concentrated mass at a material point with its weight, optionally with a
// rotary inertia in the section axes (on rigid bodies) and a quick release
// (spatial_point_load.hpp).
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_point_load.hpp"
#include "boomdyn/spatial_rigid_body.hpp"

namespace boomdyn {

namespace {

void buildSpatialPointMass(const ComponentSpec &spec, ModelBuilder &b)
{
  const SpatialBody &body = b.spatialBody(spec.text("body"));
  Release release;
  if (spec.has("release_at")) release.at = spec.number("release_at");
  Mat3 J = Mat3::Zero();
  if (spec.has("inertia")) {
    const Vec3d d = spec.vec3("inertia");
    J.diagonal() = Vec3(d[0], d[1], d[2]);
    if (!dynamic_cast<const SpatialRigidBody *>(&body))
      throw ModelError(ModelBuilder::where(spec.mark) + "point mass '" + spec.name +
                       "': a rotary inertia is available on rigid bodies only");
  }
  b.addItem(std::make_unique<SpatialPointMass>(spec.name, body, spec.number("at"), spec.number("mass"), J,
                                               b.gravity3(), release));
}

std::optional<SpecIssue> checkSpatialPointMass(const ComponentSpec &spec, const Scene &)
{
  if (!spec.has("inertia")) return std::nullopt;
  const Vec3d J = spec.vec3("inertia");
  for (double x : J)
    if (!(x >= 0)) return SpecIssue{"inertia", "moments of inertia must be >= 0"};
  if (J[0] > J[1] + J[2] || J[1] > J[0] + J[2] || J[2] > J[0] + J[1])
    return SpecIssue{"inertia", "no rigid body has these moments (each must be at most the sum of the other two)"};
  return std::nullopt;
}

} // namespace

PhysicsType spatialPointMassType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "masses";
  t.schema.type = "point_mass";
  t.schema.defaultName = "mass";
  t.schema.summary = "A concentrated mass at a material point (with its weight), optionally with a rotary inertia, "
                     "optionally released at a given time.";
  t.schema.keys = {
      bodyKey("body", "the body that carries the mass"),
      atKey("at", "body", "material point of the mass"),
      key("mass", ValueKind::Number, "kg", Need::Required, "the mass").positive(),
      key("inertia", ValueKind::Vec3, "kg m^2", Need::Optional,
          "principal moments of inertia [Jxx, Jyy, Jzz] about the point in the section axes (rigid bodies only)")
          .derived("[0, 0, 0]"),
      key("release_at", ValueKind::Number, "s", Need::Optional,
          "quick release: from this time on the mass and its weight are gone (velocities unchanged)")
          .positive()
          .derived("never"),
  };
  t.check = checkSpatialPointMass;
  t.build = buildSpatialPointMass;
  return t;
}

} // namespace boomdyn
