#include "body_section.hpp"

#include <cmath>
#include <sstream>

namespace boomdyn::body_section {

namespace {

KeySchema sectionKey(const std::string &name, const std::string &unit, const std::string &help)
{
  return key(name, ValueKind::Number, unit, Need::InForm, help).positive();
}

} // namespace

TypeSchema schema(const std::string &bodyType, bool stiffness)
{
  TypeSchema s;
  s.section = "bodies";
  s.type = bodyType + ".section";
  if (stiffness) {
    s.summary = "exactly one of two forms: the stiffnesses (`EA`, `EI`, `rhoA`), or the material and geometry "
                "(`E`, `A`, `I`, `rho`; then EA = E·A, EI = E·I, rhoA = rho·A).";
    // Schema order is the order of checks and of "allowed keys here" in messages.
    s.keys = {sectionKey("EA", "N", "axial stiffness"), sectionKey("EI", "N m^2", "bending stiffness"),
              sectionKey("rhoA", "kg/m", "mass per length"), sectionKey("E", "Pa", "Young's modulus"),
              sectionKey("A", "m^2", "cross-section area"),
              sectionKey("I", "m^4", "second moment of area about the axis normal to the plane (bending axis)"),
              sectionKey("rho", "kg/m^3", "density")};
    // Kelvin-Voigt material damping (docs/model.md §1.1), in either form.
    s.keys.push_back(key("eta_axial", ValueKind::Number, "s", Need::Optional,
                         "retardation time of the axial strain: N = EA (eps + eta_axial deps/dt)")
                         .nonNegative()
                         .byDefault(0.0, "0 (undamped)"));
    s.keys.push_back(key("eta_bending", ValueKind::Number, "s", Need::Optional,
                         "retardation time of the curvature: M = EI (K + eta_bending dK/dt)")
                         .nonNegative()
                         .byDefault(0.0, "0 (undamped)"));
    s.keys.push_back(key("damping_ratio", ValueKind::Number, "", Need::Optional,
                         "instead of the eta keys: damping ratio zeta of the mode at `damping_frequency`; sets "
                         "eta_axial = eta_bending = zeta / (pi f) (stiffness-proportional damping)")
                         .nonNegative()
                         .requiredWith("damping_frequency"));
    s.keys.push_back(key("damping_frequency", ValueKind::Number, "Hz", Need::Optional,
                         "the frequency f at which `damping_ratio` holds (the mode to be damped, e.g. the first)")
                         .positive()
                         .requiredWith("damping_ratio"));
    for (const char *eta : {"eta_axial", "eta_bending"})
      s.rules.push_back(forbidIfPresent("damping_ratio", eta,
                                        "give the damping either as eta_axial/eta_bending or as damping_ratio at "
                                        "damping_frequency, not both"));
    s.forms = {{"EA", "EI", "rhoA"}, {"E", "A", "I", "rho"}};
    s.formsText = "EA, EI, rhoA, or E, A, I, rho";
    return s;
  }
  s.summary = "the mass per length only: `rhoA`, or `rho` and `A` (then rhoA = rho·A).";
  s.keys = {sectionKey("rhoA", "kg/m", "mass per length"), sectionKey("A", "m^2", "cross-section area"),
            sectionKey("rho", "kg/m^3", "density")};
  for (const char *k : {"EA", "EI", "E", "I"})
    s.rules.push_back(forbid(k, "a rigid body has no stiffness; give its mass per length: rhoA, or rho and A"));
  for (const char *k : {"eta_axial", "eta_bending", "damping_ratio", "damping_frequency"})
    s.rules.push_back(forbid(k, "a rigid body does not deform, so it has no material damping"));
  s.forms = {{"rhoA"}, {"A", "rho"}};
  s.formsText = "rhoA, or rho and A";
  return s;
}

std::optional<SpecIssue> checkProducts(const ComponentSpec &body, bool stiffness)
{
  const ComponentSpec &s = body.map("section");
  if (!s.has("rho")) return std::nullopt;
  // Products of large or small inputs can overflow or underflow.
  const auto bad = [](double a, double b) {
    const double p = a * b;
    return !std::isfinite(p) || !(p > 0);
  };
  const auto issue = [&](const char *at, const char *what, const char *a, const char *b) {
    return SpecIssue{std::string("section.") + at,
                     std::string(what) + " = " + numberText(s.number(a)) + " * " + numberText(s.number(b)) + " is out of range"};
  };
  if (bad(s.number("rho"), s.number("A"))) return issue("rho", "rhoA", "rho", "A");
  if (!stiffness) return std::nullopt;
  if (bad(s.number("E"), s.number("A"))) return issue("E", "EA", "E", "A");
  if (bad(s.number("E"), s.number("I"))) return issue("E", "EI", "E", "I");
  return std::nullopt;
}

namespace {

// The Kelvin-Voigt retardation times: given, or from a damping ratio zeta at
// f: zeta_n = eta omega_n / 2 for stiffness-proportional damping, so
// eta = 2 zeta / (2 pi f) for both strains.
void readDamping(const ComponentSpec &s, SectionSpec &out)
{
  if (s.has("damping_ratio")) {
    out.etaAxial = out.etaBending = s.number("damping_ratio") / (M_PI * s.number("damping_frequency"));
    return;
  }
  out.etaAxial = s.number("eta_axial");
  out.etaBending = s.number("eta_bending");
}

} // namespace

SectionSpec fromSpec(const ComponentSpec &s, bool stiffness)
{
  SectionSpec out;
  if (stiffness) readDamping(s, out);
  if (!s.has("rho")) {
    if (stiffness) out.EA = s.number("EA"), out.EI = s.number("EI");
    out.rhoA = s.number("rhoA");
    return out;
  }
  out.rhoA = s.number("rho") * s.number("A");
  if (stiffness) out.EA = s.number("E") * s.number("A"), out.EI = s.number("E") * s.number("I");
  return out;
}

void describeBody(const ComponentSpec &spec, BodySpec::Type type, BodySpec &b)
{
  b.name = spec.name;
  b.type = type;
  b.mark = spec.mark;
  b.length = spec.number("length");
  if (spec.has("origin")) b.origin = spec.vec2("origin");
  b.angle = spec.number("angle");
  b.section = fromSpec(spec.map("section"), type == BodySpec::Type::AncfBeam);
}

} // namespace boomdyn::body_section
