#include "boomdyn/spatial_embedding.hpp"

#include "boomdyn/physics_type.hpp"

#include <cmath>

namespace boomdyn {

namespace {

[[noreturn]] void refuse(const SourceMark &mark, const std::string &what)
{
  throw SpatialEmbeddingError(mark.file + ":" + std::to_string(mark.line) + ": key '" + mark.key + "': " + what +
                              " cannot run as a spatial model yet (-boom_spatial takes rigid bodies, ANCF beams, pins, clamps, "
                              "angle drives, sliding joints on beams without friction or pad, extraction drives, "
                              "point forces, point masses and point sensors)");
}

Vec3d inPlane(const Vec2d &v) { return {v[0], v[1], 0.0}; }

bool constantAngle(const ComponentSpec &c, double angle)
{
  const TimeFunction &f = c.function("angle");
  std::vector<double> kinks;
  f.velocityBreakpoints(kinks);
  f.accelerationBreakpoints(kinks);
  // A constant function: the same value and no rate anywhere we can see.
  return kinks.empty() && f.value(0.0) == angle && f.rate(0.0) == 0.0 && f.value(1e9) == angle;
}

ComponentSpec aboutZ(const ComponentSpec &c, const std::string &type, const std::string &name)
{
  ComponentSpec s(type, name);
  s.mark = c.mark;
  s.set("body", c.text("body")).set("at", c.number("at"));
  s.set("axis", Vec3d{0, 0, 1});
  return s;
}

} // namespace

Scene spatialEmbedding(const Scene &planar)
{
  if (planar.dimension != 2) return planar;
  Scene s = planar;
  s.dimension = 3;
  s.gravity3 = inPlane(planar.gravity);
  s.constraints.clear(), s.forces.clear(), s.masses.clear();
  if (!planar.springs.empty()) refuse(planar.springs[0].mark, "spring '" + planar.springs[0].name + "'");
  // Point sensors carry over as they are (body and at); frame sensors do not.
  if (!planar.output.frames.empty()) refuse(planar.output.frames[0].mark, "a frame sensor");
  // Modal analysis and tracking carry over: the in-plane modes are the
  // planar ones, the out-of-plane modes come in addition (docs/model.md §5).
  for (BodySpec &b : s.bodies) {
    if (b.type == BodySpec::Type::AncfBeam) {
      // A spatial beam with its section's z axis normal to the plane: the
      // in-plane bending is about z (EI_z = EI). Out of the plane nothing
      // loads it; it gets the same bending stiffness, GJ = EI and the rotary
      // inertia of a section with polar radius of gyration 2 I/A = 2 EI/EA.
      b.type = BodySpec::Type::SpatialAncfBeam;
      b.origin3 = inPlane(b.origin);
      b.axis = {std::cos(b.angle), std::sin(b.angle), 0.0};
      b.up = {-std::sin(b.angle), std::cos(b.angle), 0.0};
      b.section.EIz = b.section.EIy = b.section.GJ = b.section.EI;
      b.section.rhoIp = b.section.rhoA * 2.0 * b.section.EI / b.section.EA;
      b.section.etaTorsion = b.section.etaBending;
      continue;
    }
    if (b.type != BodySpec::Type::Rigid) refuse(b.mark, "body '" + b.name + "'");
    const double m = b.section.rhoA * b.length, J = m * b.length * b.length / 12.0;
    b.type = BodySpec::Type::SpatialRigid;
    b.origin3 = inPlane(b.origin);
    b.axis = {std::cos(b.angle), std::sin(b.angle), 0.0};
    b.up = {-std::sin(b.angle), std::cos(b.angle), 0.0};
    b.mass = m;
    b.inertia = {J, J, J};
    b.products = {0, 0, 0};
    b.centerOfMass = {0.5 * b.length, 0, 0};
  }
  for (const ComponentSpec &c : planar.constraints) {
    if (c.type == "pin") {
      ComponentSpec r = aboutZ(c, "revolute_joint", c.name);
      if (c.has("other")) r.set("other", c.text("other")).set("other_at", c.number("other_at"));
      else r.set("point", inPlane(c.vec2("point")));
      s.constraints.push_back(r);
    } else if (c.type == "clamp") {
      const double angle = bodySpec(planar, c.text("body")).angle;
      if (constantAngle(c, angle)) {
        ComponentSpec r("clamp", c.name);
        r.mark = c.mark;
        r.set("body", c.text("body")).set("at", c.number("at")).set("point", inPlane(c.vec2("point")));
        s.constraints.push_back(r);
      } else {
        ComponentSpec r = aboutZ(c, "revolute_joint", c.name + ".pin");
        r.set("point", inPlane(c.vec2("point")));
        ComponentSpec d = aboutZ(c, "angle_drive", c.name + ".angle");
        d.set("zero", Vec3d{1, 0, 0}).set("angle", c.function("angle"));
        s.constraints.push_back(r), s.constraints.push_back(d);
      }
    } else if (c.type == "angle_drive") {
      ComponentSpec d = aboutZ(c, "angle_drive", c.name);
      d.set("zero", Vec3d{1, 0, 0}).set("angle", c.function("angle"));
      s.constraints.push_back(d);
    } else if (c.type == "sliding_joint" && !c.has("friction") && !c.has("pad") &&
               bodySpec(planar, c.text("track")).type == BodySpec::Type::AncfBeam) {
      // The spatial joint's rows d1 . d and d2 . d are the planar rows i . d
      // and j . d (the beam's d2 is the in-plane normal j); d3 . d holds the
      // slider point in the plane of the track's axis.
      ComponentSpec r("sliding_joint", c.name);
      r.mark = c.mark;
      r.set("body", c.text("body")).set("at", c.number("at")).set("track", c.text("track"));
      s.constraints.push_back(r);
    } else if (c.type == "extraction_drive") {
      s.constraints.push_back(c);
    } else {
      refuse(c.mark, "constraint '" + c.name + "' (" + c.type + ")");
    }
  }
  for (const ComponentSpec &c : planar.forces) {
    if (c.type != "point_force") refuse(c.mark, "load '" + c.name + "' (" + c.type + ")");
    ComponentSpec f = c;
    f.values.erase("force");
    f.set("force", inPlane(c.vec2("force")));
    s.forces.push_back(f);
  }
  for (const ComponentSpec &c : planar.masses) s.masses.push_back(c);
  return s;
}

} // namespace boomdyn
