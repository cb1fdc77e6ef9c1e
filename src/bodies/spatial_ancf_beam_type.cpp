// Type `ancf_beam` of spatial scenes (section bodies, dimension 3): a
// flexible beam with twist meshed with equal ANCF14 elements
// (docs/model.md §1.7), straight, unstrained and at rest at the start,
// along `axis` from `origin`, with the section's principal axis y along the
// part of `up` normal to the axis.
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_ancf_beam.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace boomdyn {

namespace {

namespace sb = spatial_beam;

// Beyond this the Jacobian alone is many GB.
constexpr int kMaxElements = 1000000;

Vec3 vec(const Vec3d &a) { return Vec3(a[0], a[1], a[2]); }

// The section triad: d1 along axis, d2 along the part of up normal to it.
// Empty reason: axis and up are usable.
std::string sectionTriad(const Vec3d &axis, const Vec3d &up, Mat3 &triad)
{
  const Vec3 x = vec(axis), u = vec(up);
  if (!(x.norm() > 0)) return "axis";
  const Vec3 ex = x / x.norm(), y = u - u.dot(ex) * ex;
  if (!(u.norm() > 0) || !(y.norm() > 1e-9 * u.norm())) return "up";
  triad.col(0) = ex, triad.col(1) = y / y.norm(), triad.col(2) = ex.cross(y / y.norm());
  return "";
}

KeySchema sectionKey(const std::string &name, const std::string &unit, const std::string &help)
{
  return key(name, ValueKind::Number, unit, Need::InForm, help).positive();
}

const TypeSchema &sectionSchema()
{
  static const TypeSchema s = [] {
    TypeSchema t;
    t.section = "bodies";
    t.type = "ancf_beam.section (dimension 3)";
    t.summary = "exactly one of two forms: the section resultants (`EA`, `EI_y`, `EI_z`, `GJ`, `rhoA`, `rho_Ip`), "
                "or a closed thin-walled rectangular box (`E`, `G`, `rho`, `width`, `height`, `thickness`; "
                "midline dimensions, Bredt's J for the torsion).";
    t.keys = {sectionKey("EA", "N", "axial stiffness"),
              sectionKey("EI_y", "N m^2", "bending stiffness about the section axis y (d2)"),
              sectionKey("EI_z", "N m^2", "bending stiffness about the section axis z (d3)"),
              sectionKey("GJ", "N m^2", "torsional stiffness (a closed box: Bredt's J, not the polar moment)"),
              sectionKey("rhoA", "kg/m", "mass per length"),
              sectionKey("rho_Ip", "kg m", "rotary inertia of the section about the axis per length, rho (Iy + Iz)"),
              sectionKey("E", "Pa", "Young's modulus (box form)"),
              sectionKey("G", "Pa", "shear modulus (box form)"),
              sectionKey("rho", "kg/m^3", "density (box form)"),
              sectionKey("width", "m", "midline width of the box along y (d2)"),
              sectionKey("height", "m", "midline height of the box along z (d3)"),
              sectionKey("thickness", "m", "wall thickness of the box (thin-walled: well below width and height)")};
    t.keys.push_back(key("eta_axial", ValueKind::Number, "s", Need::Optional,
                         "retardation time of the axial strain: N = EA (eps + eta_axial deps/dt)")
                         .nonNegative()
                         .byDefault(0.0, "0 (undamped)"));
    t.keys.push_back(key("eta_bending", ValueKind::Number, "s", Need::Optional,
                         "retardation time of both curvatures: M_i = EI_i (K_i + eta_bending dK_i/dt)")
                         .nonNegative()
                         .byDefault(0.0, "0 (undamped)"));
    t.keys.push_back(key("eta_torsion", ValueKind::Number, "s", Need::Optional,
                         "retardation time of the torsion: T = GJ (K1 + eta_torsion dK1/dt)")
                         .nonNegative()
                         .byDefault(0.0, "0 (undamped)"));
    t.forms = {{"EA", "EI_y", "EI_z", "GJ", "rhoA", "rho_Ip"}, {"E", "G", "rho", "width", "height", "thickness"}};
    t.formsText = "EA, EI_y, EI_z, GJ, rhoA, rho_Ip, or E, G, rho, width, height, thickness";
    for (const char *k : {"EI", "I", "A"})
      t.rules.push_back(forbid(k, "not a key of a spatial beam's section: give EA, EI_y, EI_z, GJ, rhoA and rho_Ip, or "
                                  "a box (E, G, rho, width, height, thickness)"));
    return t;
  }();
  return s;
}

sb::Section sectionOf(const ComponentSpec &s)
{
  sb::Section sec;
  if (s.has("EA")) {
    sec.EA = s.number("EA"), sec.EIy = s.number("EI_y"), sec.EIz = s.number("EI_z"), sec.GJ = s.number("GJ");
    sec.rhoA = s.number("rhoA"), sec.rhoIp = s.number("rho_Ip");
  } else {
    sec = sb::boxSection(s.number("E"), s.number("G"), s.number("rho"), s.number("width"), s.number("height"),
                         s.number("thickness"));
  }
  if (s.has("eta_axial")) sec.etaA = s.number("eta_axial");
  if (s.has("eta_bending")) sec.etaB = s.number("eta_bending");
  if (s.has("eta_torsion")) sec.etaT = s.number("eta_torsion");
  return sec;
}

void describeSpatialAncfBeam(const ComponentSpec &spec, BodySpec &b)
{
  b.name = spec.name;
  b.type = BodySpec::Type::SpatialAncfBeam;
  b.mark = spec.mark;
  b.length = spec.number("length");
  b.elements = spec.integer("elements");
  if (spec.has("origin")) b.origin3 = spec.vec3("origin");
  if (spec.has("axis")) b.axis = spec.vec3("axis");
  if (spec.has("up")) b.up = spec.vec3("up");
  const sb::Section sec = sectionOf(spec.map("section"));
  b.section.EA = sec.EA, b.section.EIy = sec.EIy, b.section.EIz = sec.EIz, b.section.GJ = sec.GJ;
  b.section.EI = std::min(sec.EIy, sec.EIz);
  b.section.rhoA = sec.rhoA, b.section.rhoIp = sec.rhoIp;
  b.section.etaAxial = sec.etaA, b.section.etaBending = sec.etaB, b.section.etaTorsion = sec.etaT;
  b.origin = {b.origin3[0], b.origin3[1]};
}

sb::Section sectionOf(const BodySpec &b)
{
  sb::Section sec;
  sec.EA = b.section.EA, sec.EIy = b.section.EIy, sec.EIz = b.section.EIz, sec.GJ = b.section.GJ;
  sec.rhoA = b.section.rhoA, sec.rhoIp = b.section.rhoIp;
  sec.etaA = b.section.etaAxial, sec.etaB = b.section.etaBending, sec.etaT = b.section.etaTorsion;
  sec.length = b.length;
  switch (b.section.axialIntegration) {
  case SectionSpec::AxialIntegration::Full: sec.axialIntegration = sb::AxialIntegration::Full; break;
  case SectionSpec::AxialIntegration::Reduced: sec.axialIntegration = sb::AxialIntegration::Reduced; break;
  case SectionSpec::AxialIntegration::Assumed: sec.axialIntegration = sb::AxialIntegration::Assumed; break;
  }
  return sec;
}

std::optional<SpecIssue> checkSpatialAncfBeam(const ComponentSpec &spec, const Scene &)
{
  BodySpec b;
  Mat3 triad;
  const Vec3d axis = spec.has("axis") ? spec.vec3("axis") : b.axis, up = spec.has("up") ? spec.vec3("up") : b.up;
  const std::string bad = sectionTriad(axis, up, triad);
  if (bad == "axis") return SpecIssue{"axis", "must not be the zero vector (it is the direction of the beam's axis)"};
  if (bad == "up")
    return SpecIssue{spec.has("up") ? "up" : "axis",
                     "'up' [" + numberText(up[0]) + ", " + numberText(up[1]) + ", " + numberText(up[2]) +
                         "] is parallel to 'axis': give an 'up' vector across the axis (it sets the section's y axis)"};
  const ComponentSpec &s = spec.map("section");
  if (s.has("thickness")) {
    const double t = s.number("thickness"), w = s.number("width"), h = s.number("height");
    if (!(2 * t < std::min(w, h)))
      return SpecIssue{"section.thickness", "the wall thickness " + numberText(t) +
                                                " m must be less than half the smaller midline dimension (" +
                                                numberText(std::min(w, h)) + " m) of a closed box"};
  }
  const sb::Section sec = sectionOf(s);
  for (double x : {sec.EA, sec.EIy, sec.EIz, sec.GJ, sec.rhoA, sec.rhoIp})
    if (!std::isfinite(x) || !(x > 0))
      return SpecIssue{"section", "the section's resultants (EA, EI_y, EI_z, GJ, rhoA, rho_Ip) must be finite and "
                                  "positive; these inputs give one out of range"};
  return std::nullopt;
}

// Rebasing of the node references (docs/model.md §1.7) at accepted steps
// and converged load steps, from the node slopes every rank receives: the
// same decision on every rank. The Model owns the beam and the hook.
PostStepHook rebaseHook(SpatialAncfBeam &beam)
{
  PostStepHook hook;
  hook.name = beam.name();
  hook.watched = beam.slopeDofs();
  hook.changesChartOnly = true;
  SpatialAncfBeam *b = &beam;
  hook.afterStep = [b](const double *slopes, double t, bool *, std::string *) -> PetscErrorCode {
    PetscFunctionBeginUser;
    if (b->rebase(slopes))
      PetscCall(PetscInfo(nullptr, "t = %g: beam '%s' rebases its node references\n", t, b->name().c_str()));
    PetscFunctionReturn(0);
  };
  hook.state = [b] { return b->references(); };
  hook.setState = [b](const double *values) { b->setReferences(values); };
  return hook;
}

void buildSpatialAncfBeam(const BodySpec &b, BodyBuilder &builder)
{
  Mat3 triad;
  if (!sectionTriad(b.axis, b.up, triad).empty())
    throw ModelError(ModelBuilder::where(b.mark) + "body '" + b.name + "': 'axis' and 'up' do not give a section triad");
  const sb::Section sec = sectionOf(b);
  auto owned = std::make_unique<SpatialAncfBeam>(b.name, b.length, b.elements, sec, vec(b.origin3), triad,
                                                 builder.firstCoordinate());
  SpatialAncfBeam &beam = builder.addBody(std::move(owned));
  // All elements are equal: one mass matrix, shared.
  auto mass = std::make_shared<const sb::Mat14>(sb::massMatrix(sec, beam.elementLength()));
  for (int el = 0; el < beam.numElements(); ++el)
    builder.addItem(std::make_unique<SpatialBeamElementItem>(beam, el, mass, builder.gravity3()));
  builder.addPostStepHook(rebaseHook(beam));
}

// Largest omega^2 of one straight, unstrained element: K v = omega^2 M v.
double elementOmegaMax2(const BodySpec &b, double l)
{
  sb::Section sec = sectionOf(b);
  sec.etaA = sec.etaB = sec.etaT = 0;
  const sb::Geometry geo = sb::straightGeometry(Mat3::Identity(), l);
  const sb::Vec14 e = sb::straightElement(Vec3::Zero(), Mat3::Identity(), l);
  sb::Vec14 f;
  sb::Mat14 K;
  sb::internalForce(sec, geo, e, f, &K);
  const Eigen::GeneralizedSelfAdjointEigenSolver<sb::Mat14> eig(0.5 * (K + K.transpose()), sb::massMatrix(sec, l),
                                                                 Eigen::EigenvaluesOnly);
  return eig.eigenvalues().maxCoeff();
}

} // namespace

PhysicsType spatialAncfBeamType()
{
  PhysicsType t;
  t.dimension = 3;
  t.schema.section = "bodies";
  t.schema.type = t.schema.defaultName = "ancf_beam";
  t.schema.summary = "A flexible spatial beam with twist (`dimension: 3`): equal ANCF14 elements (position, slope "
                     "and twist angle per node), two bending stiffnesses, torsion and Kelvin-Voigt damping.";
  t.schema.keys = {
      key("length", ValueKind::Number, "m", Need::Required, "undeformed length").positive(),
      key("elements", ValueKind::Integer, "", Need::Required, "number of equal beam elements")
          .between(1, kMaxElements)
          .tooLargeMeans("mesh too large"),
      key("origin", ValueKind::Vec3, "m", Need::Optional, "initial position of the start (s = 0)").derived("[0, 0, 0]"),
      key("axis", ValueKind::Vec3, "", Need::Optional, "initial direction of the beam's axis (any length)")
          .derived("[1, 0, 0]"),
      key("up", ValueKind::Vec3, "", Need::Optional,
          "the section's axis y (d2, the axis of EI_y) is the part of this vector normal to the beam's axis; z = x "
          "cross y")
          .derived("[0, 1, 0]"),
      key("section", ValueKind::Map, "", Need::Required, "cross-section properties").holding(sectionSchema()),
  };
  t.schema.rules = {
      forbid("angle", "not allowed in a spatial scene (dimension: 3): orient the beam with 'axis' and 'up'"),
  };
  t.check = checkSpatialAncfBeam;
  t.bodyKind = BodySpec::Type::SpatialAncfBeam;
  t.describeBody = describeSpatialAncfBeam;
  t.buildBody = buildSpatialAncfBeam;
  t.elementOmegaMax2 = elementOmegaMax2;
  return t;
}

} // namespace boomdyn
