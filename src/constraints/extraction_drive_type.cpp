// Type `extraction_drive` (section constraints): the slack coordinate of a
// sliding joint listed before it follows s(t) = s(0) + displacement(t).
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/slack_drive.hpp"

namespace boomdyn {

namespace {

void buildExtractionDrive(const ComponentSpec &spec, ModelBuilder &b)
{
  const std::string &joint = spec.text("joint");
  const auto &slack = b.scratch("sliding_joint", joint);
  if (!slack.count("slack"))
    throw ModelError(ModelBuilder::where(spec.mark) + "extraction drive '" + spec.name + "': no sliding joint named '" +
                     joint + "'");
  b.addConstraint(std::make_shared<SlackDrive>(spec.name, static_cast<PetscInt>(slack.at("slack")), slack.at("s0"),
                                               spec.function("displacement")),
                  spec.mark);
}

} // namespace

PhysicsType extractionDriveType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "extraction_drive";
  t.schema.summary = "Drives the contact coordinate of a sliding joint: s(t) = s(0) + displacement(t).";
  t.schema.keys = {
      key("joint", ValueKind::Component, "", Need::Required, "the sliding joint whose contact coordinate is driven")
          .naming("sliding_joint"),
      key("displacement", ValueKind::TimeFunction, "m", Need::Required,
          "displacement d(t) of the contact coordinate; a number or a time function"),
  };
  const std::string reason = "not allowed for an extraction_drive (it names a sliding joint with 'joint')";
  for (const char *k : {"body", "at", "point", "angle", "other", "other_at"}) t.schema.rules.push_back(forbid(k, reason));
  t.build = buildExtractionDrive;
  return t;
}

} // namespace boomdyn
