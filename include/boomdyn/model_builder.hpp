// What a physics type's builder may do to the Model under construction
// (physics_type.hpp): look up bodies and the initial coordinates, number
// new coordinates and first-order states, add constraints, work items,
// sensors, output channels and post-step hooks. The Model creates one
// ModelBuilder after its bodies and hands it to every type, stage by stage.
#pragma once

#include "boomdyn/model.hpp"
#include "boomdyn/spatial_body.hpp"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace boomdyn {

// What a body type's builder may do (physics_type.hpp: buildBody): add its
// body, whose coordinates follow those of the bodies before it, and the
// body's work items. The Model hands one BodyBuilder to the body types, in
// scene order, before any other type is built.
class BodyBuilder {
public:
  explicit BodyBuilder(Model &model) : model_(model) {}

  Vec2 gravity() const { return Vec2(model_.scene_.gravity[0], model_.scene_.gravity[1]); }
  // Spatial scenes: gravity [gx, gy, gz].
  Vec3 gravity3() const { return Vec3(model_.scene_.gravity3[0], model_.scene_.gravity3[1], model_.scene_.gravity3[2]); }
  // The index of the new body's first coordinate.
  PetscInt firstCoordinate() const { return model_.nq_; }
  // Takes the body built on firstCoordinate() and numbers its coordinates.
  template <typename B> B &addBody(std::unique_ptr<B> body)
  {
    model_.nq_ += body->numCoordinates();
    B &added = *body;
    model_.bodies_.push_back(std::move(body));
    return added;
  }
  void addItem(std::unique_ptr<WorkItem> item) { model_.items_.push_back(std::move(item)); }
  // A constraint the body brings along (a spatial rigid body's Euler
  // parameter normalization); its rows precede those of the components.
  void addConstraint(std::shared_ptr<Constraint> c, const SourceMark &mark)
  {
    model_.bodyConstraints_.emplace_back(std::move(c), mark);
  }
  // A hook the body brings along (a spatial beam rebasing its node
  // references); it runs before the components' hooks.
  void addPostStepHook(PostStepHook hook) { model_.postStepHooks_.push_back(std::move(hook)); }

private:
  Model &model_;
};

class ModelBuilder {
public:
  explicit ModelBuilder(Model &model) : model_(model), q0_(model.initialCoordinates()) {}

  // "<file>:<line>: key '<key>': ", the start of a ModelError message about a component.
  static std::string where(const SourceMark &mark)
  {
    return mark.file + ":" + std::to_string(mark.line) + ": key '" + mark.key + "': ";
  }

  const Scene &scene() const { return model_.scene_; }
  Vec2 gravity() const { return Vec2(model_.scene_.gravity[0], model_.scene_.gravity[1]); }
  Vec3 gravity3() const { return Vec3(model_.scene_.gravity3[0], model_.scene_.gravity3[1], model_.scene_.gravity3[2]); }
  double totalMass() const { return model_.totalMass(); } // Model::totalMass
  // Throws ModelError for an unknown name (the reader has checked names)
  // and for a body of the other dimension (types are registered per
  // dimension, so the reader never lets that happen).
  const Body &body(const std::string &name) const { return ofDimension<Body>(name, 2); }
  const SpatialBody &spatialBody(const std::string &name) const { return ofDimension<SpatialBody>(name, 3); }
  // Initial coordinates of the bodies (undeformed, as placed).
  const std::vector<double> &bodyCoordinates() const { return q0_; }

  // Coordinates numbered so far (final in the build stage).
  PetscInt numCoordinates() const { return model_.nq_; }
  // A new second-order coordinate (after the bodies'), starting at initial.
  PetscInt addCoordinate(double initial);
  // A new first-order state (LuGre z) of the friction at joint `joint`.
  PetscInt addFirstOrderState(const std::string &joint);
  // A new first-order state of a component that is not a LuGre friction
  // (a hydraulic cylinder's chamber pressure), starting at `initial`; Newton
  // judges its increments against max(|value|, floor) (BlockConvergence).
  // what: the state as the messages name it, e.g. "piston pressure of
  // hydraulic_cylinder 'luffing'".
  PetscInt addFirstOrderState(const std::string &what, double initial, double floor);
  // Multiplier rows follow all coordinates: call in the build stage only.
  const ConstraintItem &addConstraint(std::shared_ptr<Constraint> c, const SourceMark &mark);
  void addItem(std::unique_ptr<WorkItem> item) { model_.items_.push_back(std::move(item)); }
  void addSlidingJoint(std::shared_ptr<SlidingJoint> joint) { model_.slidingJoints_.push_back(std::move(joint)); }
  void addFriction(std::unique_ptr<LuGreFriction> friction);
  // A compliant pad; the Model owns it (the pointer stays valid).
  const PadContact *addPad(std::unique_ptr<PadContact> pad);
  void addSensor(Sensor sensor) { model_.sensors_.push_back(std::move(sensor)); }
  void addFrameSensor(FrameSensor frame) { model_.frameSensors_.push_back(std::move(frame)); }
  void addOutputChannel(OutputChannel channel) { model_.outputChannels_.push_back(std::move(channel)); }
  void addPostStepHook(PostStepHook hook) { model_.postStepHooks_.push_back(std::move(hook)); }
  void addEventSource(EventSource source) { model_.eventSources_.push_back(std::move(source)); }

  // Numbers a type keeps between its stages, or hands to a later component
  // (an extraction drive reads its sliding joint's slack coordinate), keyed
  // by the component's type and name (unique together).
  std::map<std::string, double> &scratch(const std::string &type, const std::string &name)
  {
    return scratch_[type + "/" + name];
  }

private:
  template <typename B> const B &ofDimension(const std::string &name, int dimension) const
  {
    const BodyBase *b = model_.findBody(name);
    if (b->dimension() != dimension)
      throw ModelError("body '" + name + "' is " + (dimension == 2 ? "spatial" : "planar") + " but a " +
                       (dimension == 2 ? "planar" : "spatial") + " type refers to it");
    return static_cast<const B &>(*b);
  }

  Model &model_;
  std::vector<double> q0_;
  std::map<std::string, std::map<std::string, double>> scratch_;
};

} // namespace boomdyn
