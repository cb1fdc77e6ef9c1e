// Type `hydraulic_cylinder` (section constraints, beside the ropes: a force
// element that joins two points): a double-acting cylinder from a base
// point (a body's material point or a ground point) to its rod end on a
// body, with its chamber pressures as first-order states, fed by a 4/3
// proportional valve, a flow source, or closed (hydraulic_cylinder.hpp,
// hydraulic_cylinder_item.hpp, docs/model.md §2.6). Outputs per cylinder and
// step: force, piston_pressure, rod_pressure, stroke, stroke_rate,
// flow_piston, flow_rod, hydraulic_power, compression_power,
// friction_power (and spool with a spool lag).
#include "boomdyn/hydraulic_cylinder_item.hpp"
#include "boomdyn/model_builder.hpp"
#include "boomdyn/physics_type.hpp"

#include <cmath>
#include <memory>

namespace boomdyn {

namespace {

constexpr double kPi = 3.14159265358979323846;

double pistonArea(const ComponentSpec &spec)
{
  const double D = spec.number("piston_diameter");
  return 0.25 * kPi * D * D;
}

double rodSideArea(const ComponentSpec &spec)
{
  const double D = spec.number("piston_diameter"), d = spec.number("rod_diameter");
  return 0.25 * kPi * (D * D - d * d);
}

ValveData::Mode valveMode(const ComponentSpec &spec)
{
  const std::string v = spec.has("valve") ? spec.text("valve") : "closed";
  if (v == "proportional") return ValveData::Mode::Proportional;
  if (v == "flow_source") return ValveData::Mode::FlowSource;
  return ValveData::Mode::Closed;
}

std::optional<SpecIssue> checkCylinder(const ComponentSpec &spec, const Scene &)
{
  const std::string valve = spec.has("valve") ? spec.text("valve") : "closed";
  if (valve != "proportional" && valve != "closed" && valve != "flow_source")
    return SpecIssue{"valve", "must be proportional, closed or flow_source (got '" + valve + "')"};
  if (!(spec.number("rod_diameter") < spec.number("piston_diameter")))
    return SpecIssue{"rod_diameter", "must be smaller than piston_diameter (" + numberText(spec.number("piston_diameter")) +
                                         " m): the rod-side annulus would have no area"};
  for (const char *side : {"piston", "rod"}) {
    const std::string dead = std::string("dead_volume_") + side, hose = std::string("hose_volume_") + side;
    if (!(spec.number(dead) + spec.number(hose) > 0))
      return SpecIssue{dead, std::string("the ") + side + " chamber has no volume at its end of the stroke (" + dead +
                                 " + " + hose + " = 0): its pressure would be infinitely stiff there; give the "
                                 "cylinder's dead volume or the hose volume"};
  }
  const bool proportional = valve == "proportional", source = valve == "flow_source";
  for (const char *k : {"command", "rated_flow", "rated_pressure_drop", "supply_pressure"})
    if (proportional != spec.has(k))
      return SpecIssue{k, proportional ? std::string("'") + k + "' is required with valve: proportional"
                                       : "only allowed with valve: proportional (valve is " + valve + ")"};
  if (spec.has("spool_time_constant") && !proportional)
    return SpecIssue{"spool_time_constant", "only allowed with valve: proportional (valve is " + valve + ")"};
  if (source != spec.has("flow"))
    return SpecIssue{"flow", source ? "'flow' is required with valve: flow_source"
                                    : "only allowed with valve: flow_source (valve is " + valve + ")"};
  if (proportional && !(spec.number("supply_pressure") > spec.number("tank_pressure")))
    return SpecIssue{"supply_pressure", "must be above tank_pressure (" + numberText(spec.number("tank_pressure")) +
                                            " Pa): the valve would feed no chamber"};
  return std::nullopt;
}

void addStates(const ComponentSpec &spec, ModelBuilder &b)
{
  // Initial stroke from the bodies as placed (the stroke memory's start).
  auto point = [&](const std::string &bodyKey, const std::string &atKey) {
    return initialPoint(b.scene(), PointRef{spec.text(bodyKey), spec.number(atKey)});
  };
  const Vec2d rod = point("body", "at");
  const Vec2d base = spec.has("base") ? point("base", "base_at") : spec.vec2("base_point");
  const double l = std::hypot(rod[0] - base[0], rod[1] - base[1]), s0 = l - spec.number("closed_length");
  const double L = spec.number("stroke");
  if (!(s0 >= 0 && s0 <= L))
    throw ModelError(ModelBuilder::where(spec.mark) + "hydraulic_cylinder '" + spec.name +
                     "': key 'closed_length': the cylinder's initial stroke is " + numberText(s0) +
                     " m (pin-to-pin length " + numberText(l) + " m less closed_length " +
                     numberText(spec.number("closed_length")) + " m), outside its stroke [0, " + numberText(L) +
                     "] m; place the bodies or change closed_length so that the piston starts inside the cylinder");
  const double pt = spec.number("tank_pressure");
  const double p1 = spec.numberOr("initial_pressure_piston", pt), p2 = spec.numberOr("initial_pressure_rod", pt);
  const double pressureFloor = std::max({1e5, std::abs(pt), std::abs(spec.numberOr("supply_pressure", 0.0))});
  auto &scratch = b.scratch(spec.type, spec.name);
  const std::string of = " of hydraulic_cylinder '" + spec.name + "'";
  scratch["p1"] = static_cast<double>(b.addFirstOrderState("piston pressure" + of, p1, pressureFloor));
  scratch["p2"] = static_cast<double>(b.addFirstOrderState("rod-side pressure" + of, p2, pressureFloor));
  scratch["stroke"] = static_cast<double>(b.addFirstOrderState("stroke memory" + of, s0, L));
  scratch["s0"] = s0;
  if (valveMode(spec) == ValveData::Mode::Proportional && spec.numberOr("spool_time_constant", 0.0) > 0)
    scratch["spool"] = static_cast<double>(b.addFirstOrderState("spool position" + of, spec.function("command").value(0.0), 1.0));
}

void buildCylinder(const ComponentSpec &spec, ModelBuilder &b)
{
  HydraulicCylinderData c;
  c.pistonArea = pistonArea(spec);
  c.rodSideArea = rodSideArea(spec);
  c.strokeLength = spec.number("stroke");
  c.deadVolume[0] = spec.number("dead_volume_piston"), c.deadVolume[1] = spec.number("dead_volume_rod");
  c.hoseVolume[0] = spec.number("hose_volume_piston"), c.hoseVolume[1] = spec.number("hose_volume_rod");
  c.bulkOil = spec.number("bulk_modulus_oil");
  c.bulkHose = spec.numberOr("bulk_modulus_hose", 0.0);
  c.bulkWall = spec.numberOr("bulk_modulus_wall", 0.0);
  c.coulomb = spec.number("friction_coulomb");
  c.coulombVelocity = spec.number("friction_velocity");
  c.viscous = spec.number("friction_viscous");
  c.stopStiffness = spec.number("stop_stiffness");
  c.stopDamping = spec.number("stop_damping");
  c.stopDampingDepth = spec.number("stop_damping_depth");

  ValveData v;
  v.mode = valveMode(spec);
  v.tankPressure = spec.number("tank_pressure");
  v.laminarPressureDrop = spec.number("laminar_pressure_drop");
  if (v.mode == ValveData::Mode::Proportional) {
    v.command = spec.function("command");
    v.spoolTimeConstant = spec.numberOr("spool_time_constant", 0.0);
    v.flowCoefficient = spec.number("rated_flow") / std::sqrt(spec.number("rated_pressure_drop"));
    v.supplyPressure = spec.number("supply_pressure");
    // The spool travels in [-1, 1]: a command beyond opens no further.
    const Scene &scene = b.scene();
    const double tEnd = std::max({scene.dynamic.t_end, scene.statics.time, v.command.endTime(), 0.0});
    double lo, hi;
    v.command.bounds(0.0, tEnd, &lo, &hi);
    if (!(lo >= -1 && hi <= 1))
      throw ModelError(ModelBuilder::where(spec.mark) + "hydraulic_cylinder '" + spec.name +
                       "': key 'command': the spool command ranges over [" + numberText(lo) + ", " + numberText(hi) +
                       "] for t in [0, " + numberText(tEnd) + "] s; the spool position is a fraction of its travel, in "
                       "[-1, 1] (+1: supply to the piston side)");
  } else if (v.mode == ValveData::Mode::FlowSource)
    v.flow = spec.function("flow");

  HydraulicCylinderItem::End rod{&b.body(spec.text("body")), spec.number("at"), Vec2::Zero()}, base;
  if (spec.has("base")) base = {&b.body(spec.text("base")), spec.number("base_at"), Vec2::Zero()};
  else {
    const Vec2d p = spec.vec2("base_point");
    base.ground = Vec2(p[0], p[1]);
  }
  auto &scratch = b.scratch(spec.type, spec.name);
  HydraulicCylinderItem::States states;
  states.p1 = static_cast<PetscInt>(scratch.at("p1"));
  states.p2 = static_cast<PetscInt>(scratch.at("p2"));
  states.stroke = static_cast<PetscInt>(scratch.at("stroke"));
  if (scratch.count("spool")) states.spool = static_cast<PetscInt>(scratch.at("spool"));
  const double p2Initial = spec.numberOr("initial_pressure_rod", v.tankPressure);
  auto item = std::make_unique<HydraulicCylinderItem>(spec.name, base, rod, spec.number("closed_length"), c, v, states,
                                                      scratch.at("s0"), p2Initial);
  const HydraulicCylinderItem *cyl = item.get(); // owned by the Model, which also holds the channels
  std::vector<PetscInt> dofs;
  cyl->coordinates(dofs);
  b.addItem(std::move(item));
  auto channel = [&](const char *quantity, const char *unit, double (*pick)(const HydraulicCylinderItem::State &)) {
    b.addOutputChannel(OutputChannel::ofTimedState(
        "hydraulic_cylinder", spec.name, quantity, unit, dofs,
        [cyl, pick](double t, const double *q, const double *v) { return pick(cyl->state(t, q, v)); }));
  };
  using S = HydraulicCylinderItem::State;
  channel("force", "N", [](const S &s) { return s.force; });
  channel("piston_pressure", "Pa", [](const S &s) { return s.p1; });
  channel("rod_pressure", "Pa", [](const S &s) { return s.p2; });
  channel("stroke", "m", [](const S &s) { return s.stroke; });
  channel("stroke_rate", "m/s", [](const S &s) { return s.strokeRate; });
  channel("flow_piston", "m^3/s", [](const S &s) { return s.Q1; });
  channel("flow_rod", "m^3/s", [](const S &s) { return s.Q2; });
  channel("hydraulic_power", "W", [](const S &s) { return s.hydraulicPower; });
  channel("compression_power", "W", [](const S &s) { return s.compressionPower; });
  channel("friction_power", "W", [](const S &s) { return s.frictionPower; });
  if (states.spool >= 0) channel("spool", "", [](const S &s) { return s.spool; });
}

} // namespace

PhysicsType hydraulicCylinderType()
{
  PhysicsType t;
  t.schema.section = "constraints";
  t.schema.type = t.schema.defaultName = "hydraulic_cylinder";
  t.schema.summary =
      "A double-acting hydraulic cylinder from a base point to its rod end: chamber pressures as first-order states "
      "(oil, hose and wall compliance), Coulomb and viscous friction, compliant end stops, fed by a 4/3 proportional "
      "valve (square-root orifices with a laminar region, optional spool lag), by a flow source, or closed.";
  t.schema.keys = {
      bodyKey("body", "body of the rod end (the luffed body)"),
      atKey("at", "body", "material point of the rod end"),
      key("base", ValueKind::Body, "", Need::Optional, "body of the cylinder's base (leave out for a ground point)"),
      atKey("base_at", "base", "material point of the base").requiredWith("base"),
      key("base_point", ValueKind::Vec2, "m", Need::Optional, "ground point [x, y] of the base").requiredWithout("base"),
      key("piston_diameter", ValueKind::Number, "m", Need::Required, "bore D: piston area A1 = pi D^2 / 4").positive(),
      key("rod_diameter", ValueKind::Number, "m", Need::Required,
          "rod diameter d < D: rod-side area A2 = pi (D^2 - d^2) / 4")
          .positive(),
      key("stroke", ValueKind::Number, "m", Need::Required, "stroke length L (end stops at 0 and L)").positive(),
      key("closed_length", ValueKind::Number, "m", Need::Required,
          "pin-to-pin length fully retracted (stroke 0); the initial stroke (initial pin-to-pin length less this) "
          "must lie in [0, L]")
          .positive(),
      key("dead_volume_piston", ValueKind::Number, "m^3", Need::Optional, "piston chamber volume at stroke 0")
          .nonNegative()
          .byDefault(0.0),
      key("dead_volume_rod", ValueKind::Number, "m^3", Need::Optional, "rod chamber volume at stroke L")
          .nonNegative()
          .byDefault(0.0),
      key("hose_volume_piston", ValueKind::Number, "m^3", Need::Optional,
          "oil volume of the hoses and lines to the piston chamber; dead + hose volume > 0 on each side")
          .nonNegative()
          .byDefault(0.0),
      key("hose_volume_rod", ValueKind::Number, "m^3", Need::Optional, "oil volume of the hoses to the rod chamber")
          .nonNegative()
          .byDefault(0.0),
      key("bulk_modulus_oil", ValueKind::Number, "Pa", Need::Optional, "bulk modulus of the oil")
          .positive()
          .byDefault(1.5e9),
      key("bulk_modulus_hose", ValueKind::Number, "Pa", Need::Optional,
          "effective bulk modulus of the hoses' expansion, in series with the oil over the hose volume")
          .positive()
          .derived("rigid hoses"),
      key("bulk_modulus_wall", ValueKind::Number, "Pa", Need::Optional,
          "effective bulk modulus of the cylinder wall's expansion, in series with the oil over the chamber volume "
          "outside the hoses")
          .positive()
          .derived("rigid wall"),
      key("friction_coulomb", ValueKind::Number, "N", Need::Optional, "Coulomb friction F_c (smoothed: F_c tanh(v / "
                                                                      "friction_velocity))")
          .nonNegative()
          .byDefault(0.0),
      key("friction_velocity", ValueKind::Number, "m/s", Need::Optional, "velocity scale of the smoothed Coulomb law")
          .positive()
          .byDefault(1e-3),
      key("friction_viscous", ValueKind::Number, "N s/m", Need::Optional, "viscous friction c").nonNegative().byDefault(0.0),
      key("stop_stiffness", ValueKind::Number, "N/m", Need::Optional, "stiffness of the end stops at 0 and L")
          .positive()
          .byDefault(1e8),
      key("stop_damping", ValueKind::Number, "N s/m", Need::Optional, "damping of the end stops").nonNegative().byDefault(0.0),
      key("stop_damping_depth", ValueKind::Number, "m", Need::Optional,
          "penetration over which the stops' damping grows from 0 to stop_damping")
          .positive()
          .byDefault(1e-3),
      key("valve", ValueKind::Name, "", Need::Optional,
          "proportional (4/3 valve: command, rated_flow, rated_pressure_drop, supply_pressure), closed (the cylinder a "
          "nonlinear spring) or flow_source (prescribed flow into the piston chamber, rod chamber at tank pressure)")
          .derived("closed"),
      key("command", ValueKind::TimeFunction, "", Need::Optional,
          "spool position in [-1, 1] (+1: supply to the piston side, rod side to tank; -1 the reverse)"),
      key("spool_time_constant", ValueKind::Number, "s", Need::Optional,
          "first-order lag of the spool behind its command (1/(2 pi f_-45deg))")
          .positive()
          .derived("none: the spool is at its command"),
      key("rated_flow", ValueKind::Number, "m^3/s", Need::Optional,
          "flow of one metering edge fully open at rated_pressure_drop")
          .positive(),
      key("rated_pressure_drop", ValueKind::Number, "Pa", Need::Optional, "pressure drop of the rated flow").positive(),
      key("laminar_pressure_drop", ValueKind::Number, "Pa", Need::Optional,
          "below this drop the orifice law is laminar (linear at small drops, C1 with the square-root law)")
          .positive()
          .byDefault(2e5),
      key("supply_pressure", ValueKind::Number, "Pa", Need::Optional, "pump pressure at the valve's P port"),
      key("tank_pressure", ValueKind::Number, "Pa", Need::Optional, "pressure at the T port").byDefault(0.0),
      key("flow", ValueKind::TimeFunction, "m^3/s", Need::Optional, "flow source: flow into the piston chamber"),
      key("initial_pressure_piston", ValueKind::Number, "Pa", Need::Optional,
          "piston chamber pressure at t = 0 (with dynamic.initial: static, solved for instead)")
          .derived("tank_pressure"),
      key("initial_pressure_rod", ValueKind::Number, "Pa", Need::Optional,
          "rod chamber pressure at t = 0, kept by the static start")
          .derived("tank_pressure"),
  };
  t.schema.rules = {
      forbidIfPresent("base", "base_point", "not allowed together with 'base' (the base is on that body)"),
      forbidIfAbsent("base", "base_at", "only allowed together with 'base'"),
  };
  const std::string reason = "not allowed for a hydraulic_cylinder (it names its points with body/at and "
                             "base/base_at or base_point)";
  for (const char *k : {"point", "angle", "other", "other_at"}) t.schema.rules.push_back(forbid(k, reason));
  t.check = checkCylinder;
  t.addStates = addStates;
  t.build = buildCylinder;
  return t;
}

} // namespace boomdyn
