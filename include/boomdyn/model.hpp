// The Model: bodies, constraints, loads and masses built from a Scene, and
// the layout of the unknowns x = [q | lambda]. Every rank builds the whole
// Model (it is metadata and small kernels); the Assembler decides which rank
// evaluates which work item.
#pragma once

#include "boomdyn/body.hpp"
#include "boomdyn/constraint_item.hpp"
#include "boomdyn/output_channel.hpp"
#include "boomdyn/post_step_hook.hpp"
#include "boomdyn/scene.hpp"
#include "boomdyn/sliding_joint.hpp"
#include "boomdyn/spatial_body.hpp"
#include "boomdyn/type_event.hpp"
#include "boomdyn/work_item.hpp"

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace boomdyn {

class ModelError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// A point sensor: a planar scene's on `body`, a spatial scene's on
// `spatialBody` (the other is null).
struct Sensor {
  std::string name;
  const Body *body = nullptr;
  double s = 0;
  const SpatialBody *spatialBody = nullptr;
};

// Deflection of a material point in a body's moving frame (paper Fig. 9):
// origin at the body's start (s = 0), x-axis through the contact point of
// sliding joint `axisJoint` on that body; the output is the point's
// coordinate normal to the axis (m).
// In a spatial scene a frame sensor reads the section at s of `spatialBody`
// instead (body null, no axis joint): its triad, twist, angular velocity
// and strains (section_reading.hpp).
struct FrameSensor {
  std::string name;
  const Body *body = nullptr;
  double s = 0;
  std::string axisJoint; // a sliding joint whose track is `body`
  const SpatialBody *spatialBody = nullptr;
};

class LuGreFriction;
class PadContact;

class Model {
public:
  // Throws ModelError (message names the scene file, line and key) when the
  // scene is consistent as data but not as a mechanism, e.g. a constraint
  // violated by the initial configuration.
  explicit Model(const Scene &scene);

  PetscInt numCoordinates() const { return nq_; }
  PetscInt numMultipliers() const { return nlambda_; }
  PetscInt size() const { return nq_ + nlambda_; }

  // Planar scenes hold planar bodies (Body), spatial scenes spatial ones
  // (SpatialBody); BodyBase::dimension() tells which.
  const std::vector<std::unique_ptr<BodyBase>> &bodies() const { return bodies_; }
  const BodyBase *findBody(const std::string &name) const;
  const std::vector<std::unique_ptr<WorkItem>> &items() const { return items_; }
  const std::vector<const ConstraintItem *> &constraints() const { return constraints_; }
  // Some item damps the motion physically (WorkItem::physicalDamping): the
  // eigen-analysis takes the damped (PEP) path and the energy balance counts
  // the damping work.
  bool hasPhysicalDamping() const
  {
    for (const auto &item : items_)
      if (item->physicalDamping()) return true;
    return false;
  }
  const std::vector<Sensor> &sensors() const { return sensors_; }
  const std::vector<FrameSensor> &frameSensors() const { return frameSensors_; }
  // Per-type outputs (rope tensions, ...), in the order the types added them.
  const std::vector<OutputChannel> &outputChannels() const { return outputChannels_; }
  // Work after each converged step (sliding joints follow their tracks).
  const std::vector<PostStepHook> &postStepHooks() const { return postStepHooks_; }
  // Per-type event sources (elastic ropes: slack/taut), in the order the types added them.
  const std::vector<EventSource> &eventSources() const { return eventSources_; }
  // Sliding joints, mutable through a const Model: which track element holds
  // the contact point is topology state that follows the solution.
  const std::vector<std::shared_ptr<SlidingJoint>> &slidingJoints() const { return slidingJoints_; }
  // Coordinates that are first-order states (LuGre z, a hydraulic
  // cylinder's pressures, stroke memory and spool).
  const std::vector<PetscInt> &firstOrderCoordinates() const { return firstOrder_; }
  // Per first-order state, the size below which Newton judges its
  // increments absolutely (0 for LuGre z: its floor comes from
  // the friction law, BlockConvergence).
  const std::vector<double> &firstOrderFloors() const { return firstOrderFloor_; }
  // Per first-order state, what it is, as messages name it (its owner gave
  // it: "LuGre z of sliding_joint 'j2'", "piston pressure of
  // hydraulic_cylinder 'luffing'").
  const std::vector<std::string> &firstOrderNames() const { return firstOrderNames_; }
  // The sliding joints with LuGre friction (one z each), in the order of frictions().
  const std::vector<std::string> &frictionJointNames() const { return frictionJoints_; }
  // The friction elements, in the order of frictionJointNames().
  const std::vector<const LuGreFriction *> &frictions() const { return frictions_; }
  // The compliant pads of sliding joints (sliding_joint's `pad`), in scene order.
  const std::vector<const PadContact *> &pads() const { return pads_; }
  const Scene &scene() const { return scene_; }
  // Initial coordinates (undeformed bodies as placed in the scene), size nq.
  std::vector<double> initialCoordinates() const;
  // Initial velocities, size nq (zero but for spatial bodies given a velocity).
  std::vector<double> initialVelocities() const;

  // Conditioning of the Newton iteration matrix M/(beta h^2) + K of a dynamic
  // run, estimated per flexible body (its type's elementOmegaMax2) from its
  // element data: (omega_max h)^2 beta,
  // with omega_max^2 the largest eigenvalue of one straight element's
  // stiffness against its mass (it grows like EI / (rhoA l^4) with the
  // element length l). Above kIllConditioned double precision no longer
  // resolves the Newton residual (measured: docs/extreme-cases.md). One
  // message per beam beyond it, naming the scene, the body, the element
  // length, and the largest element count at this h and the largest h at
  // this mesh that stay below it; empty for static and modal scenes.
  static constexpr double kIllConditioned = 1e15;
  struct Conditioning {
    std::string body;
    double elementLength = 0, omegaMax = 0, estimate = 0, maxStep = 0;
    int elements = 0, maxElements = 0;
  };
  std::vector<Conditioning> iterationConditioning() const;

  // An energy the model's own data make [J]: M (|g| L + (L / T)^2), with M
  // the bodies' and point masses' total mass, L the size of the initial
  // configuration (the span of the bodies' ends, at least the longest body)
  // and T the run's end time: the potential energy of lifting the model by
  // its size and the kinetic energy of moving it by its size over the run.
  // The energy balance takes its round-off floor from it (a model whose
  // energies are all zero has no other scale). 0 for a model without mass.
  double energyScale() const;
  // The bodies' and point masses' total mass as the scene gives it [kg].
  double totalMass() const;
  std::vector<std::string> conditioningWarnings() const;

private:
  friend class ModelBuilder; // the physics types build the Model through it
  friend class BodyBuilder;  // and the body types
  void checkInitialConfiguration() const;
  double spatialEnergyScale(double mass) const;

  Scene scene_;
  PetscInt nq_ = 0, nlambda_ = 0;
  std::vector<std::unique_ptr<BodyBase>> bodies_;
  // Constraints that bodies bring along (the normalization row of a spatial
  // rigid body's Euler parameters), added before the components' constraints.
  std::vector<std::pair<std::shared_ptr<Constraint>, SourceMark>> bodyConstraints_;
  std::vector<std::unique_ptr<WorkItem>> items_;
  std::vector<const ConstraintItem *> constraints_;
  std::vector<SourceMark> constraintMarks_;
  std::vector<Sensor> sensors_;
  std::vector<FrameSensor> frameSensors_;
  std::vector<OutputChannel> outputChannels_;
  std::vector<PostStepHook> postStepHooks_;
  std::vector<EventSource> eventSources_;
  std::vector<std::shared_ptr<SlidingJoint>> slidingJoints_;
  std::vector<std::pair<PetscInt, double>> slackInitial_; // (slack coordinate or first-order state, initial value)
  std::vector<PetscInt> firstOrder_;
  std::vector<double> firstOrderFloor_;
  std::vector<std::string> firstOrderNames_;
  std::vector<std::string> frictionJoints_;
  std::vector<const LuGreFriction *> frictions_;
  std::vector<const PadContact *> pads_;
};

} // namespace boomdyn
