#include "boomdyn/design_numbers.hpp"

#include "boomdyn/angle_drive.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace boomdyn {

namespace {

// The weight of the load an elastic rope lifts (EN 13001-2: phi_2 is the
// peak over the hoist load's weight): m g / n, m the mass of the body at the
// rope's far end (`to`: its rhoA L and every point mass on it at t = 0), n
// the falls that carry it (1 + the rope's sheaves on that body: a rope
// reeved through a sheave on the hook block carries it on two falls).
// Only for a rope on a winch (a hoist rope: the winch lifts the load); 0
// for other ropes (an inextensible rope of the mechanism, or a telescoping
// rope that a static start leaves slack).
double hangingLoadWeight(const Scene &scene, const std::string &group, const std::string &rope)
{
  if (group != "elastic_rope") return 0;
  const auto spec = std::find_if(scene.constraints.begin(), scene.constraints.end(), [&](const ComponentSpec &c) {
    return c.type == "elastic_rope" && c.name == rope;
  });
  if (spec == scene.constraints.end() || !spec->has("winch")) return 0;
  const std::string load = spec->text("to");
  double mass = 0;
  for (const BodySpec &b : scene.bodies)
    if (b.name == load) mass += b.section.rhoA * b.length;
  for (const ComponentSpec &m : scene.masses)
    if (m.text("body") == load) mass += m.number("mass");
  int falls = 1;
  for (const char *pulley : {"pulley", "pulley2"})
    falls += spec->has(pulley) && spec->text(pulley) == load;
  if (spec->has("pulleys"))
    for (std::size_t i = 0; spec->map("pulleys").has(std::to_string(i)); ++i)
      falls += spec->map("pulleys").map(std::to_string(i)).text("body") == load;
  return mass * std::hypot(scene.gravity[0], scene.gravity[1]) / falls;
}

} // namespace

DesignNumbers::DesignNumbers(const Model &model)
{
  const auto &channels = model.outputChannels();
  for (std::size_t k = 0; k < channels.size(); ++k) {
    const OutputChannel &ch = channels[k];
    if ((ch.group == "rope" || ch.group == "elastic_rope") && ch.quantity == "tension") {
      items_.push_back({Kind::Tension, ch.group, ch.name, static_cast<PetscInt>(k)});
      items_.back().loadWeight = hangingLoadWeight(model.scene(), ch.group, ch.name);
    }
    else if (ch.group == "joint_resultants" && ch.quantity == "normal_force")
      items_.push_back({Kind::ContactForce, ch.group, ch.name, static_cast<PetscInt>(k)});
  }
  // Clamps: the angle drive "<name>.angle" beside the pin "<name>.pin".
  // Its constraint C = j(theta) . r'(s) with the constraint force -Cq^T lambda
  // is the moment -lambda |r'| on the body (|r'| = 1 + axial strain, taken
  // as 1: relative error ~1e-5 for steel booms): the reaction moment at the
  // root, counter-clockwise positive, equal and opposite to the bending
  // moment the root section carries.
  std::set<std::string> pins;
  for (const ConstraintItem *c : model.constraints()) pins.insert(c->name());
  for (const ConstraintItem *c : model.constraints()) {
    const std::string n = c->name();
    if (n.size() <= 6 || n.compare(n.size() - 6, 6, ".angle") != 0) continue;
    const std::string clamp = n.substr(0, n.size() - 6);
    if (!pins.count(clamp + ".pin") || !dynamic_cast<const AngleDrive *>(&c->constraint())) continue;
    items_.push_back({Kind::Moment, "clamp", clamp, c->firstRow() - model.numCoordinates()});
  }
}

void DesignNumbers::update(double t, const std::vector<double> &outputs, const std::vector<double> &multipliers)
{
  if (outputs.empty() && multipliers.empty()) return; // not rank 0
  for (Item &it : items_) {
    double value;
    if (it.kind == Kind::Moment) {
      if (it.index >= (PetscInt)multipliers.size()) continue;
      value = -multipliers[it.index];
    } else {
      if (it.index >= (PetscInt)outputs.size()) continue;
      value = outputs[it.index];
    }
    // Tensions: signed extremes; moments and contact forces: magnitudes.
    const double v = it.kind == Kind::Tension ? value : std::abs(value);
    if (!it.seen) {
      it.seen = true;
      it.start = value;
      it.peak = it.low = v;
      it.peakTime = it.lowTime = t;
      continue;
    }
    if (v > it.peak) it.peak = v, it.peakTime = t;
    if (v < it.low) it.low = v, it.lowTime = t;
  }
}

namespace {
// A rope that carries nothing at t = 0 (a payload resting on the ground, the
// rigid rope of a mechanism at rest) reads a tension of round-off size there
// (3e-7 N against a 20 kN peak on the lift-off scene); a ratio to that is
// noise, so a start below a millionth of the largest tension counts as none.
bool hasStaticTension(double start, double peak, double low)
{
  return start > 1e-6 * std::max(std::abs(peak), std::abs(low));
}
} // namespace

// The tension the dynamic factors are relative to: the static tension (at
// t = 0), or for an elastic rope that carries nothing at t = 0 (a load
// resting on the ground: lift-off) the weight of the load it lifts; NaN for
// other ropes without a static tension.
double DesignNumbers::reference(const Item &it)
{
  if (hasStaticTension(it.start, it.peak, it.low)) return it.start;
  return it.loadWeight > 0 ? it.loadWeight : std::nan("");
}

std::vector<std::pair<std::string, double>> DesignNumbers::attributes() const
{
  std::vector<std::pair<std::string, double>> out;
  for (const Item &it : items_) {
    if (!it.seen) continue;
    const std::string p = "design." + it.group + "." + it.name + ".";
    switch (it.kind) {
    case Kind::Tension:
      out.push_back({p + "static_tension_N", it.start});
      out.push_back({p + "peak_tension_N", it.peak});
      out.push_back({p + "peak_tension_time_s", it.peakTime});
      out.push_back({p + "min_tension_N", it.low});
      out.push_back({p + "min_tension_time_s", it.lowTime});
      // A slack start: the factors are relative to the lifted load's weight (stored as such).
      if (!hasStaticTension(it.start, it.peak, it.low) && it.loadWeight > 0)
        out.push_back({p + "load_weight_N", it.loadWeight});
      out.push_back({p + "dynamic_factor", it.peak / reference(it)});
      out.push_back({p + "min_factor", it.low / reference(it)});
      break;
    case Kind::Moment:
      out.push_back({p + "peak_root_moment_Nm", it.peak});
      out.push_back({p + "peak_root_moment_time_s", it.peakTime});
      out.push_back({p + "static_root_moment_Nm", std::abs(it.start)});
      break;
    case Kind::ContactForce:
      out.push_back({p + "peak_normal_force_N", it.peak});
      out.push_back({p + "peak_normal_force_time_s", it.peakTime});
      break;
    }
  }
  return out;
}

std::string DesignNumbers::report() const
{
  std::string text;
  char line[400];
  for (const Item &it : items_) {
    if (!it.seen) continue;
    switch (it.kind) {
    case Kind::Tension:
      if (hasStaticTension(it.start, it.peak, it.low))
        std::snprintf(line, sizeof line,
                      "  %s '%s': static tension %.6g N (t = 0), peak %.6g N at t = %.4g s (dynamic factor %.4f), "
                      "minimum %.6g N at t = %.4g s (%.4f)\n",
                      it.group.c_str(), it.name.c_str(), it.start, it.peak, it.peakTime, it.peak / it.start, it.low,
                      it.lowTime, it.low / it.start);
      else if (it.loadWeight > 0)
        std::snprintf(line, sizeof line,
                      "  %s '%s': tension %.6g N at t = 0 (slack start: factors over the lifted load's weight %.6g N), "
                      "peak %.6g N at t = %.4g s (dynamic factor %.4f), minimum %.6g N at t = %.4g s (%.4f)\n",
                      it.group.c_str(), it.name.c_str(), it.start, it.loadWeight, it.peak, it.peakTime,
                      it.peak / it.loadWeight, it.low, it.lowTime, it.low / it.loadWeight);
      else
        std::snprintf(line, sizeof line,
                      "  %s '%s': tension %.6g N at t = 0 (no static tension: no dynamic factor), peak %.6g N at "
                      "t = %.4g s, minimum %.6g N at t = %.4g s\n",
                      it.group.c_str(), it.name.c_str(), it.start, it.peak, it.peakTime, it.low, it.lowTime);
      break;
    case Kind::Moment:
      std::snprintf(line, sizeof line, "  clamp '%s': peak root moment %.6g N m at t = %.4g s (%.6g N m at t = 0)\n",
                    it.name.c_str(), it.peak, it.peakTime, std::abs(it.start));
      break;
    case Kind::ContactForce:
      std::snprintf(line, sizeof line, "  joint '%s': peak normal force %.6g N at t = %.4g s\n", it.name.c_str(),
                    it.peak, it.peakTime);
      break;
    }
    text += line;
  }
  return text.empty() ? text : "design numbers (docs/output.md):\n" + text;
}

std::vector<double> DesignNumbers::state() const
{
  std::vector<double> out;
  for (const Item &it : items_)
    out.insert(out.end(), {it.seen ? 1.0 : 0.0, it.start, it.peak, it.peakTime, it.low, it.lowTime});
  return out;
}

void DesignNumbers::restore(const std::vector<double> &values)
{
  if (values.size() != 6 * items_.size()) return; // another model or an older checkpoint: start afresh
  for (std::size_t k = 0; k < items_.size(); ++k) {
    const double *v = &values[6 * k];
    Item &it = items_[k];
    it.seen = v[0] != 0, it.start = v[1], it.peak = v[2], it.peakTime = v[3], it.low = v[4], it.lowTime = v[5];
  }
}

} // namespace boomdyn
