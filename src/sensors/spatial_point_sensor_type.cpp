// Type `point_sensor` of spatial scenes (section output.sensors, no `type:`
// key): the position and velocity (x, y, z) of a material point, written
// at every step.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

namespace boomdyn {

namespace {

void buildSpatialPointSensor(const ComponentSpec &spec, ModelBuilder &b)
{
  Sensor sensor{spec.name, nullptr, spec.number("at")};
  sensor.spatialBody = &b.spatialBody(spec.text("body"));
  b.addSensor(std::move(sensor));
}

} // namespace

PhysicsType spatialPointSensorType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "output.sensors";
  t.schema.type = "point_sensor";
  t.schema.defaultName = "sensor";
  t.schema.summary = "Position and velocity (x, y, z) of a material point at every step (/sensors/<name>).";
  t.schema.keys = {
      bodyKey("body", "the observed body"),
      atKey("at", "body", "the observed material point"),
  };
  t.build = buildSpatialPointSensor;
  return t;
}

} // namespace boomdyn
