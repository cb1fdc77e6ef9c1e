// Type `ancf_beam` (section bodies): a flexible planar beam, meshed with
// equal ANCF elements (Euler-Bernoulli), starting undeformed and at rest.
#include "body_section.hpp"

#include "boomdyn/ancf_beam.hpp"
#include "boomdyn/beam_element_item.hpp"
#include "boomdyn/model_builder.hpp"

#include <Eigen/Eigenvalues>

namespace boomdyn {

namespace {

// Beyond this the Jacobian alone is many GB.
constexpr int kMaxElements = 10000000;

void describeAncfBeam(const ComponentSpec &spec, BodySpec &b)
{
  body_section::describeBody(spec, BodySpec::Type::AncfBeam, b);
  b.elements = spec.integer("elements");
}

std::optional<SpecIssue> checkAncfBeam(const ComponentSpec &spec, const Scene &)
{
  return body_section::checkProducts(spec, true);
}

void buildAncfBeam(const BodySpec &b, BodyBuilder &builder)
{
  ancf::Section sec{b.section.EA, b.section.EI, b.section.rhoA, b.section.etaAxial, b.section.etaBending};
  sec.length = b.length;
  switch (b.section.axialIntegration) {
  case SectionSpec::AxialIntegration::Full: sec.axialIntegration = ancf::AxialIntegration::Full; break;
  case SectionSpec::AxialIntegration::Reduced: sec.axialIntegration = ancf::AxialIntegration::Reduced; break;
  case SectionSpec::AxialIntegration::Assumed: sec.axialIntegration = ancf::AxialIntegration::Assumed; break;
  }
  auto owned = std::make_unique<AncfBeam>(b.name, b.length, b.elements, sec, Vec2(b.origin[0], b.origin[1]), b.angle,
                                          builder.firstCoordinate());
  const AncfBeam &beam = *owned;
  builder.addBody(std::move(owned));
  // All elements are equal: one mass matrix, shared.
  auto mass = std::make_shared<const ancf::Mat8>(ancf::massMatrix(sec.rhoA, beam.elementLength()));
  for (int el = 0; el < beam.numElements(); ++el)
    builder.addItem(std::make_unique<BeamElementItem>(beam, el, mass, builder.gravity()));
}

// Largest omega^2 of one straight, unstrained element: K v = omega^2 M v.
double elementOmegaMax2(const BodySpec &b, double l)
{
  const ancf::Section sec{b.section.EA, b.section.EI, b.section.rhoA};
  const ancf::Vec8 e = ancf::straightElement(Vec2::Zero(), Vec2(1, 0), l);
  ancf::Vec8 f;
  ancf::Mat8 K;
  ancf::internalForce(sec, l, e, f, &K);
  const Eigen::GeneralizedSelfAdjointEigenSolver<ancf::Mat8> eig(0.5 * (K + K.transpose()), ancf::massMatrix(sec.rhoA, l),
                                                                  Eigen::EigenvaluesOnly);
  return eig.eigenvalues().maxCoeff();
}

} // namespace

PhysicsType ancfBeamType()
{
  static const TypeSchema section = body_section::schema("ancf_beam", true);
  PhysicsType t;
  t.schema.section = "bodies";
  t.schema.type = t.schema.defaultName = "ancf_beam";
  t.schema.summary = "A flexible planar beam (Euler-Bernoulli) meshed with equal ANCF elements; the default type.";
  t.schema.keys = {
      key("length", ValueKind::Number, "m", Need::Required, "undeformed length").positive(),
      key("elements", ValueKind::Integer, "", Need::Required, "number of equal beam elements")
          .between(1, kMaxElements)
          .tooLargeMeans("mesh too large"),
      key("origin", ValueKind::Vec2, "m", Need::Optional, "initial position of the start (s = 0)").derived("[0, 0]"),
      key("angle", ValueKind::Angle, "deg", Need::Optional, "initial direction of the axis, counter-clockwise from x")
          .byDefault(0),
      key("section", ValueKind::Map, "", Need::Required, "cross-section properties").holding(section),
  };
  t.check = checkAncfBeam;
  t.bodyKind = BodySpec::Type::AncfBeam;
  t.describeBody = describeAncfBeam;
  t.buildBody = buildAncfBeam;
  t.elementOmegaMax2 = elementOmegaMax2;
  return t;
}

} // namespace boomdyn
