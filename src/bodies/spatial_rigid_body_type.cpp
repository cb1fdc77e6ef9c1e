// Type `rigid` of spatial scenes (section bodies, dimension 3): a rigid body
// with an axis along which material coordinates run, placed by the position
// of s = 0 and its body axes (x along `axis`, y along the part of `up`
// normal to it), with mass, full inertia tensor and centre of mass.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_rigid_body.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace boomdyn {

namespace {

Vec3 vec(const Vec3d &a) { return Vec3(a[0], a[1], a[2]); }

Mat3 inertiaTensor(const BodySpec &b)
{
  Mat3 J;
  J << b.inertia[0], b.products[0], b.products[2], b.products[0], b.inertia[1], b.products[1], b.products[2],
      b.products[1], b.inertia[2];
  return J;
}

// The body axes as the columns of a rotation matrix; x along axis, y along
// the part of up normal to x. Empty reason: axis and up are usable.
std::string bodyAxes(const Vec3d &axis, const Vec3d &up, Mat3 &axes)
{
  const Vec3 x = vec(axis), u = vec(up);
  if (!(x.norm() > 0)) return "axis";
  const Vec3 ex = x / x.norm(), y = u - u.dot(ex) * ex;
  if (!(y.norm() > 1e-9 * u.norm()) || !(u.norm() > 0)) return "up";
  axes.col(0) = ex, axes.col(1) = y / y.norm(), axes.col(2) = ex.cross(y / y.norm());
  return "";
}

void describeSpatialRigidBody(const ComponentSpec &spec, BodySpec &b)
{
  b.name = spec.name;
  b.type = BodySpec::Type::SpatialRigid;
  b.mark = spec.mark;
  b.length = spec.number("length");
  b.elements = 1;
  if (spec.has("origin")) b.origin3 = spec.vec3("origin");
  if (spec.has("axis")) b.axis = spec.vec3("axis");
  if (spec.has("up")) b.up = spec.vec3("up");
  b.mass = spec.number("mass");
  b.inertia = spec.vec3("inertia");
  if (spec.has("products")) b.products = spec.vec3("products");
  b.centerOfMass = spec.has("center_of_mass") ? spec.vec3("center_of_mass") : Vec3d{0.5 * b.length, 0, 0};
  if (spec.has("velocity")) b.velocity = spec.vec3("velocity");
  if (spec.has("angular_velocity")) b.angularVelocity = spec.vec3("angular_velocity");
  // The planar view's fields, for what reads every body alike (the total mass).
  b.origin = {b.origin3[0], b.origin3[1]};
  b.section.rhoA = b.mass / b.length;
}

std::optional<SpecIssue> checkSpatialRigidBody(const ComponentSpec &spec, const Scene &)
{
  BodySpec b;
  describeSpatialRigidBody(spec, b);
  Mat3 axes;
  const std::string bad = bodyAxes(b.axis, b.up, axes);
  if (bad == "axis") return SpecIssue{"axis", "must not be the zero vector (it is the direction of the body's x axis)"};
  if (bad == "up")
    return SpecIssue{spec.has("up") ? "up" : "axis",
                     "'up' [" + numberText(b.up[0]) + ", " + numberText(b.up[1]) + ", " + numberText(b.up[2]) +
                         "] is parallel to 'axis': give an 'up' vector across the axis (it sets the body's y axis)"};
  // A physical inertia tensor is positive definite and its principal
  // values obey the triangle inequality J1 <= J2 + J3.
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(inertiaTensor(b));
  const Vec3 J = eig.eigenvalues();
  const std::string key = spec.has("products") ? "products" : "inertia";
  if (!(J.minCoeff() > 0))
    return SpecIssue{key, "the inertia tensor must be positive definite (principal moments " + numberText(J[0]) + ", " +
                              numberText(J[1]) + ", " + numberText(J[2]) + " kg m^2)"};
  if (J[2] > (J[0] + J[1]) * (1 + 1e-12))
    return SpecIssue{key, "no rigid body has these principal moments: " + numberText(J[2]) + " > " + numberText(J[0]) +
                              " + " + numberText(J[1]) + " kg m^2 (each must be at most the sum of the other two)"};
  return std::nullopt;
}

void buildSpatialRigidBody(const BodySpec &b, BodyBuilder &builder)
{
  Mat3 axes;
  if (!bodyAxes(b.axis, b.up, axes).empty())
    throw ModelError(ModelBuilder::where(b.mark) + "body '" + b.name + "': 'axis' and 'up' do not give body axes");
  const PetscInt first = builder.firstCoordinate();
  auto owned = std::make_unique<SpatialRigidBody>(b.name, b.length, b.mass, inertiaTensor(b), vec(b.centerOfMass),
                                                  vec(b.origin3), axes, first);
  owned->setInitialVelocity(vec(b.velocity), vec(b.angularVelocity));
  const SpatialRigidBody &body = builder.addBody(std::move(owned));
  builder.addItem(std::make_unique<SpatialRigidInertia>(body, builder.gravity3()));
  builder.addConstraint(std::make_shared<EulerNormalization>(b.name + ".euler", first + 3), b.mark);
}

} // namespace

PhysicsType spatialRigidBodyType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "bodies";
  t.schema.type = t.schema.defaultName = "rigid";
  t.schema.summary = "A spatial rigid body (`dimension: 3`): centre of mass and Euler parameters, full inertia "
                     "tensor; material coordinates run along its body x axis.";
  t.schema.keys = {
      key("length", ValueKind::Number, "m", Need::Required, "length of the axis (material coordinates 0 to length)")
          .positive(),
      key("origin", ValueKind::Vec3, "m", Need::Optional, "initial position of the start (s = 0)").derived("[0, 0, 0]"),
      key("axis", ValueKind::Vec3, "", Need::Optional, "initial direction of the body x axis (any length)")
          .derived("[1, 0, 0]"),
      key("up", ValueKind::Vec3, "", Need::Optional,
          "the body y axis is the part of this vector normal to the axis; z = x cross y")
          .derived("[0, 1, 0]"),
      key("mass", ValueKind::Number, "kg", Need::Required, "mass").positive(),
      key("inertia", ValueKind::Vec3, "kg m^2", Need::Required,
          "moments of inertia [Jxx, Jyy, Jzz] about the centre of mass in body axes"),
      key("products", ValueKind::Vec3, "kg m^2", Need::Optional,
          "products of inertia [Jxy, Jyz, Jzx] (tensor entries, not their negatives) in body axes")
          .derived("[0, 0, 0]"),
      key("center_of_mass", ValueKind::Vec3, "m", Need::Optional,
          "centre of mass in body axes, from the point s = 0")
          .derived("[length/2, 0, 0]"),
      key("velocity", ValueKind::Vec3, "m/s", Need::Optional,
          "initial velocity of the point s = 0 (dynamic runs; the joints must allow it)")
          .derived("[0, 0, 0]"),
      key("angular_velocity", ValueKind::Vec3, "rad/s", Need::Optional,
          "initial angular velocity in the global axes (dynamic runs; the joints must allow it)")
          .derived("[0, 0, 0]"),
  };
  t.schema.rules = {
      forbid("angle", "not allowed in a spatial scene (dimension: 3): orient the body with 'axis' and 'up'"),
      forbid("section", "not allowed for a spatial rigid body: give 'mass' and 'inertia'"),
      forbid("elements", "not allowed for a rigid body (it has no mesh)"),
  };
  t.check = checkSpatialRigidBody;
  t.bodyKind = BodySpec::Type::SpatialRigid;
  t.describeBody = describeSpatialRigidBody;
  t.buildBody = buildSpatialRigidBody;
  return t;
}

} // namespace boomdyn
