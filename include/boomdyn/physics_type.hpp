// The registry of physics types. A type (pin, rope, point_mass, ...) is one
// file that fills a PhysicsType: its scene schema, derived defaults and
// cross-checks, and its builder into the Model, in three stages so that all
// coordinates are numbered before the first-order states and those before
// the multiplier rows. The list of all types is src/model/physics_types.cpp
// (one registration line per type).
//
// A plain C++ registry, not PetscFunctionList: the scene reader, the schema
// printer and the fuzzer run without PETSc initialized, and the registry is
// a constant table built on first use.
#pragma once

#include "boomdyn/scene.hpp"
#include "boomdyn/schema.hpp"

#include <optional>
#include <string>
#include <vector>

namespace boomdyn {

class BodyBuilder;
class ModelBuilder;

// A problem found by a type's cross-check: the key (relative to the
// component, "friction.mu_c" for nested ones) and the reason.
struct SpecIssue {
  std::string key;
  std::string reason;
};

struct PhysicsType {
  TypeSchema schema;
  // The scenes the type belongs to: 2 planar, 3 spatial (the scene's
  // `dimension`). A type name may exist in both (a planar and a spatial
  // `clamp`): the registry is looked up by (section, type, dimension).
  int dimension = 2;
  // Derived defaults that need the rest of the scene (a clamp's ground point
  // is where its body starts). Fills only absent keys.
  void (*complete)(ComponentSpec &spec, const Scene &scene) = nullptr;
  // Checks the schema cannot express, on the completed spec; scene holds the
  // components listed before this one.
  std::optional<SpecIssue> (*check)(const ComponentSpec &spec, const Scene &scene) = nullptr;
  // Model construction: extra coordinates, then first-order states, then
  // constraints, work items, sensors, outputs and hooks.
  void (*addCoordinates)(const ComponentSpec &spec, ModelBuilder &builder) = nullptr;
  void (*addStates)(const ComponentSpec &spec, ModelBuilder &builder) = nullptr;
  void (*build)(const ComponentSpec &spec, ModelBuilder &builder) = nullptr;

  // Body types only (section "bodies"). Bodies are built from the typed
  // view BodySpec, which command-line options (-boom_elements) and tests
  // change after reading: describeBody fills it from the read component,
  // buildBody adds the body and its work items to the Model. bodyKind is
  // the BodySpec::type that selects this type.
  BodySpec::Type bodyKind = BodySpec::Type::AncfBeam;
  void (*describeBody)(const ComponentSpec &spec, BodySpec &body) = nullptr;
  void (*buildBody)(const BodySpec &body, BodyBuilder &builder) = nullptr;
  // Flexible bodies: the largest omega^2 (rad^2/s^2) of one straight,
  // unstrained element of length elementLength, for the Model's estimate of
  // the Newton matrix's conditioning (Model::iterationConditioning); nullptr
  // for bodies without elastic modes.
  double (*elementOmegaMax2)(const BodySpec &body, double elementLength) = nullptr;
};

// Helpers for derived defaults: the body of that name (the reader has
// checked that it exists), and where a material point starts.
const BodySpec &bodySpec(const Scene &scene, const std::string &name);
Vec2d initialPoint(const Scene &scene, const PointRef &point);
// The same in a spatial scene: origin + s axis/|axis|.
Vec3d initialPoint3(const Scene &scene, const PointRef &point);

// Keys shared by many types: a material point named by a body and a
// material coordinate on it.
KeySchema bodyKey(const std::string &key, const std::string &help);
KeySchema atKey(const std::string &key, const std::string &body, const std::string &help);

// Every registered type, in registration order (the order of `type:`
// choices in messages and of the tables in docs/scenes.md).
const std::vector<PhysicsType> &physicsTypes();
// The types of one section and dimension, in registration order.
std::vector<const PhysicsType *> physicsTypesOf(const std::string &section, int dimension = 2);
// nullptr if the section has no such type in that dimension.
const PhysicsType *findPhysicsType(const std::string &section, const std::string &type, int dimension = 2);
// The body type of a body (section "bodies"); every BodySpec::Type has one.
const PhysicsType &bodyType(BodySpec::Type kind);

} // namespace boomdyn
