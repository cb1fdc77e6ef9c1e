// Type `frame_sensor` (section output.frames, no `type:` key): deflection
// of a material point in its body's moving frame (paper Fig. 9): origin at
// the body's start, x-axis through the contact point of a sliding joint
// whose track is that body; the output is the coordinate normal to the axis.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

namespace boomdyn {

namespace {

std::optional<SpecIssue> checkFrameSensor(const ComponentSpec &spec, const Scene &scene)
{
  const std::string &body = spec.text("body"), &joint = spec.text("axis_joint");
  for (const ComponentSpec &c : scene.constraints)
    if (c.type == "sliding_joint" && c.name == joint && c.text("track") == body) return std::nullopt;
  return SpecIssue{"axis_joint", "must name a sliding_joint whose track is '" + body + "' (got '" + joint + "')"};
}

void buildFrameSensor(const ComponentSpec &spec, ModelBuilder &b)
{
  b.addFrameSensor(FrameSensor{spec.name, &b.body(spec.text("body")), spec.number("at"), spec.text("axis_joint")});
}

} // namespace

PhysicsType frameSensorType()
{
  PhysicsType t;
  t.schema.section = "output.frames";
  t.schema.type = "frame_sensor";
  t.schema.defaultName = "frame";
  t.schema.summary = "Deflection of a material point normal to its body's moving axis (origin at the body's start, "
                     "axis through a sliding joint's contact point).";
  t.schema.keys = {
      bodyKey("body", "the body whose deflection is measured"),
      atKey("at", "body", "the measured material point"),
      key("axis_joint", ValueKind::Name, "", Need::Required,
          "a sliding joint whose track is `body`; its contact point fixes the frame's x-axis"),
  };
  t.check = checkFrameSensor;
  t.build = buildFrameSensor;
  return t;
}

} // namespace boomdyn
