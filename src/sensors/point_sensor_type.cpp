// Type `point_sensor` (section output.sensors, no `type:` key): the
// position and velocity of a material point, written at every step.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

namespace boomdyn {

namespace {

void buildPointSensor(const ComponentSpec &spec, ModelBuilder &b)
{
  b.addSensor(Sensor{spec.name, &b.body(spec.text("body")), spec.number("at")});
}

} // namespace

PhysicsType pointSensorType()
{
  PhysicsType t;
  t.schema.section = "output.sensors";
  t.schema.type = "point_sensor";
  t.schema.defaultName = "sensor";
  t.schema.summary = "Position and velocity of a material point at every step (/steps/sensors).";
  t.schema.keys = {
      bodyKey("body", "the observed body"),
      atKey("at", "body", "the observed material point"),
  };
  t.build = buildPointSensor;
  return t;
}

} // namespace boomdyn
