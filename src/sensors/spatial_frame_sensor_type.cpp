// Type `frame_sensor` of spatial scenes (section output.frames, no `type:`
// key): the section of a body at a material point, written at every step:
// its triad, twist and angular velocity, and a beam's axial strain, torsion
// and curvatures (section_reading.hpp, docs/output.md `/frames`).
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

namespace boomdyn {

namespace {

void buildSpatialFrameSensor(const ComponentSpec &spec, ModelBuilder &b)
{
  FrameSensor frame{spec.name, nullptr, spec.number("at"), ""};
  frame.spatialBody = &b.spatialBody(spec.text("body"));
  b.addFrameSensor(std::move(frame));
}

} // namespace

PhysicsType spatialFrameSensorType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "output.frames";
  t.schema.type = "frame_sensor";
  t.schema.defaultName = "frame";
  t.schema.summary = "The section at a material point at every step (/frames/<name>): its triad, twist about the "
                     "axis and angular velocity, and a beam's axial strain, torsion and curvatures.";
  t.schema.keys = {
      bodyKey("body", "the observed body"),
      atKey("at", "body", "the observed section"),
  };
  t.build = buildSpatialFrameSensor;
  return t;
}

} // namespace boomdyn
