// The components of a scene (constraints, loads, masses, springs, sensors)
// read against the schemas of the registered physics types: the keys of
// every type of the section are known (keys of a sibling type get "only
// allowed for ..."), `type:` selects the type, then the type's rules and
// keys are checked in schema order, its derived defaults filled and its
// cross-checks run, all with the file:line:column: key messages of the
// checked-YAML layer.
#include "checked_yaml.hpp"

#include "boomdyn/physics_type.hpp"

#include <algorithm>

namespace boomdyn::scene_io {

namespace {

// Sections whose items name their type with `type:`; the others hold one type.
bool hasTypeKey(const std::string &section)
{
  return section == "bodies" || section == "constraints" || section == "loads";
}
// Bodies: `type` may be left out (the first registered body type) and
// `name` is required, since constraints and loads refer to bodies by name.
bool isBodies(const std::string &section) { return section == "bodies"; }

// The noun in "duplicate <noun> name".
std::string itemNoun(const std::string &section)
{
  if (section == "bodies") return "body";
  if (section == "constraints") return "constraint";
  if (section == "loads") return "load";
  if (section == "masses") return "mass";
  if (section == "springs") return "spring";
  if (section == "output.sensors") return "sensor";
  return "frame";
}

std::string withArticle(const std::string &word)
{
  return (std::string("aeiou").find(word.empty() ? 'x' : word[0]) != std::string::npos ? "an " : "a ") + word;
}

// Reads one component against its type's schema (physics_type.hpp).
class ComponentReader : public CheckedYaml {
public:
  using CheckedYaml::CheckedYaml;
  ComponentSpec parseComponent(const Field &f, std::size_t index, const std::string &section, const Scene &scene,
                               std::map<std::string, std::string> &taken) const;

private:
  void readKeys(const MapView &m, const TypeSchema &schema, const std::vector<const PhysicsType *> &siblings,
                const std::string &section, const Scene &scene, const std::string &prefix, ComponentSpec &spec,
                std::map<std::string, Field> &fields) const;
  void readValue(const Field &f, const KeySchema &k, const std::string &section, const Scene &scene,
                 const std::string &prefix, ComponentSpec &spec, std::map<std::string, Field> &fields) const;
  // The index of the form (TypeSchema::forms) the map is written in;
  // forms.size() when the schema has none. Rejects a mix and no form.
  std::size_t chooseForm(const MapView &m, const TypeSchema &schema) const;
};

} // namespace

void readComponents(const Reporter &report, const MapView &parent, const std::string &key, const std::string &section,
                    Scene &scene)
{
  const ComponentReader reader(report);
  const auto field = parent.get(key);
  if (!field) return;
  if (physicsTypesOf(section, scene.dimension).empty())
    report.fail(*field, std::string("not available in a ") + (scene.dimension == 3 ? "spatial" : "planar") +
                            " scene (dimension: " + std::to_string(scene.dimension) + "): no type of section " +
                            section + " is registered for it");
  std::map<std::string, std::string> taken;
  const auto items = reader.list(*field);
  for (std::size_t i = 0; i < items.size(); ++i) {
    // Push before the next item is read: later items may refer to earlier ones.
    ComponentSpec spec = reader.parseComponent(items[i], i, section, scene, taken);
    scene.components(section).push_back(std::move(spec));
  }
}

void readBodies(const Reporter &report, const std::vector<Field> &items, Scene &scene)
{
  const ComponentReader reader(report);
  std::map<std::string, std::string> taken;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const ComponentSpec spec = reader.parseComponent(items[i], i, "bodies", scene, taken);
    BodySpec body;
    findPhysicsType("bodies", spec.type, scene.dimension)->describeBody(spec, body);
    scene.bodies.push_back(std::move(body));
  }
}

std::size_t ComponentReader::chooseForm(const MapView &m, const TypeSchema &schema) const
{
  std::size_t chosen = schema.forms.size(), used = 0;
  for (std::size_t i = 0; i < schema.forms.size(); ++i)
    for (const std::string &key : schema.forms[i])
      if (m.has(key)) {
        ++used, chosen = i;
        break;
      }
  if (schema.forms.empty()) return chosen;
  if (used > 1) report_.fail(m.self(), "give either " + schema.formsText + " (not a mix of the two forms)");
  if (used == 0) report_.fail(m.self(), "needs " + schema.formsText);
  return chosen;
}

ComponentSpec ComponentReader::parseComponent(const Field &f, std::size_t index, const std::string &section,
                                          const Scene &scene, std::map<std::string, std::string> &taken) const
{
  const std::vector<const PhysicsType *> types = physicsTypesOf(section, scene.dimension);
  // The types of the section in the other dimension: their keys and names
  // get "only allowed in a spatial scene" rather than "unknown".
  const int otherDimension = scene.dimension == 3 ? 2 : 3;
  const std::vector<const PhysicsType *> others = physicsTypesOf(section, otherDimension);
  // Every key of every type of the section is known here, so that a key of
  // a sibling type gets "only allowed for ..." rather than "unknown key".
  std::vector<std::string> allowed{"name"}, typeNames;
  if (hasTypeKey(section)) allowed.insert(isBodies(section) ? allowed.end() : allowed.begin(), "type");
  for (const PhysicsType *t : types) typeNames.push_back(t->schema.type);
  for (const auto *group : {&types, &others})
    for (const PhysicsType *t : *group)
      for (const KeySchema &k : t->schema.keys)
        if (std::find(allowed.begin(), allowed.end(), k.key) == allowed.end()) allowed.push_back(k.key);
  const MapView m(report_, f, allowed);
  if (isBodies(section)) m.require("name");
  const std::string inOther = otherDimension == 3 ? "only allowed in a spatial scene (top-level key 'dimension: 3')"
                                                  : "not allowed in a spatial scene (dimension: 3)";
  // A planar scene's key that only spatial types take is still an unknown
  // key here (the user may have meant something else), with the hint.
  const std::string keyInOther =
      otherDimension == 3 ? "unknown key in a planar scene (spatial scenes, top-level key 'dimension: 3', take it)"
                          : inOther;
  auto chooseType = [&](const Field &t) {
    if (t.node.IsScalar() && std::find(typeNames.begin(), typeNames.end(), t.node.Scalar()) == typeNames.end())
      for (const PhysicsType *o : others)
        if (o->schema.type == t.node.Scalar())
          report_.fail(t, "type '" + o->schema.type + "' is " + inOther + "; here use one of " + join(typeNames));
    return types[choice(t, typeNames)];
  };
  const PhysicsType *type = types.at(0);
  if (isBodies(section)) {
    if (const auto t = m.get("type")) type = chooseType(*t);
  } else if (hasTypeKey(section)) {
    type = chooseType(m.require("type", " (one of " + join(typeNames) + ")"));
  }
  // Keys that only types of the other dimension take (a spatial body's
  // 'axis' in a planar scene), unless a sibling or a rule of the type
  // itself says more.
  for (const PhysicsType *o : others)
    for (const KeySchema &k : o->schema.keys) {
      if (!m.has(k.key) || type->schema.find(k.key)) continue;
      bool explained = false;
      for (const PhysicsType *t : types) explained = explained || t->schema.find(k.key);
      for (const KeyRule &rule : type->schema.rules)
        explained = explained || (rule.key == k.key && rule.when == KeyRule::When::Always);
      if (!explained) m.forbid(k.key, keyInOther);
    }
  ComponentSpec spec;
  spec.type = type->schema.type;
  spec.mark = report_.sourceMark(f);
  spec.name = itemName(m, taken, itemNoun(section), type->schema.defaultName + std::to_string(index));
  std::map<std::string, Field> fields;
  readKeys(m, type->schema, types, section, scene, "", spec, fields);
  if (type->complete) type->complete(spec, scene);
  if (type->check)
    if (const auto issue = type->check(spec, scene)) {
      const auto it = fields.find(issue->key);
      report_.fail(it == fields.end() ? f : it->second, issue->reason);
    }
  return spec;
}

// Keys of one map against its schema: first the keys that do not belong
// here (so that the message names the real mistake), then the values in
// schema order.
void ComponentReader::readKeys(const MapView &m, const TypeSchema &schema, const std::vector<const PhysicsType *> &siblings,
                           const std::string &section, const Scene &scene, const std::string &prefix,
                           ComponentSpec &spec, std::map<std::string, Field> &fields) const
{
  for (const PhysicsType *sibling : siblings)
    for (const KeySchema &k : sibling->schema.keys) {
      if (schema.find(k.key) || !m.has(k.key)) continue;
      std::string reason;
      for (const KeyRule &rule : schema.rules)
        if (rule.key == k.key && rule.when == KeyRule::When::Always) reason = rule.reason;
      if (reason.empty()) {
        std::vector<std::string> owners;
        for (const PhysicsType *t : siblings)
          if (t->schema.find(k.key)) owners.push_back(withArticle(t->schema.type));
        for (std::size_t i = 0; i < owners.size(); ++i) reason += (i ? " or " : "") + owners[i];
        reason = "only allowed for " + reason;
      }
      m.forbid(k.key, reason);
    }
  for (const KeyRule &rule : schema.rules) {
    const bool given = !rule.condition.empty() && m.has(rule.condition);
    // Always: keys no sibling owns (a rigid section's stiffnesses); the others were rejected above.
    if (rule.when == KeyRule::When::Always || (rule.when == KeyRule::When::IfPresent && given) ||
        (rule.when == KeyRule::When::IfAbsent && !given))
      m.forbid(rule.key, rule.reason);
  }
  const std::size_t form = chooseForm(m, schema);
  for (const KeySchema &k : schema.keys) {
    const std::optional<Field> given = m.get(k.key);
    if (!given) {
      const bool inForm = form < schema.forms.size() && std::find(schema.forms[form].begin(), schema.forms[form].end(),
                                                                  k.key) != schema.forms[form].end();
      const bool needed = k.need == Need::Required || (k.need == Need::RequiredWith && m.has(k.other)) ||
                          (k.need == Need::RequiredWithout && !m.has(k.other)) || (k.need == Need::InForm && inForm);
      if (needed) m.require(k.key);
      if (k.hasDefault) spec.set(k.key, k.defaultNumber);
      continue;
    }
    readValue(*given, k, section, scene, prefix, spec, fields);
  }
}

void ComponentReader::readValue(const Field &f, const KeySchema &k, const std::string &section, const Scene &scene,
                            const std::string &prefix, ComponentSpec &spec, std::map<std::string, Field> &fields) const
{
  fields.emplace(prefix + k.key, f);
  switch (k.kind) {
  case ValueKind::Number: {
    const double x =
      k.limit == Limit::Positive ? positive(f) : k.limit == Limit::NonNegative ? nonNegative(f) : number(f);
    if (x > k.maxNumber)
      report_.fail(f, "must be <= " + numberText(k.maxNumber) + " (" + k.maxReason + "; got " + f.node.Scalar() + ")");
    spec.set(k.key, x);
    return;
  }
  case ValueKind::Angle:
    spec.set(k.key, number(f) * kRadPerDeg);
    return;
  case ValueKind::Integer:
    spec.set(k.key, static_cast<double>(integer(f, k.minInt, k.maxInt, k.tooLarge)));
    return;
  case ValueKind::Name:
    spec.set(k.key, name(f));
    return;
  case ValueKind::Vec2:
    if (scene.dimension == 2 && f.node.IsSequence() && f.node.size() == 3)
      report_.fail(f, "expected a list of two numbers [x, y], got a list of 3 (a spatial scene needs the top-level "
                      "key 'dimension: 3')");
    spec.set(k.key, vec2(f));
    return;
  case ValueKind::Vec3:
    spec.set(k.key, vec3(f));
    return;
  case ValueKind::TimeFunction:
    spec.set(k.key, timeFunction(f));
    return;
  case ValueKind::AngleFunction:
    spec.set(k.key, angleFunction(f));
    return;
  case ValueKind::Body: {
    const std::string named = body(f, scene).name;
    if (!k.differentFrom.empty() && spec.has(k.differentFrom) && spec.text(k.differentFrom) == named)
      report_.fail(f, "must name another body than '" + k.differentFrom + "' ('" + named + "')");
    spec.set(k.key, named);
    return;
  }
  case ValueKind::MaterialCoordinate:
    spec.set(k.key, materialCoordinate(f, bodyNamed(scene, spec.text(k.bodyKey))));
    return;
  case ValueKind::Component: {
    const std::string named = name(f);
    bool found = false;
    for (const ComponentSpec &other : scene.components(section))
      found = found || (other.type == k.refType && other.name == named);
    if (!found) report_.fail(f, "names no " + k.refType + " listed before it ('" + named + "')");
    spec.set(k.key, named);
    return;
  }
  case ValueKind::Map:
  case ValueKind::MapList: {
    // Keys its rules forbid are known here too (their reason beats "unknown key").
    std::vector<std::string> keys;
    for (const KeySchema &nested : k.nested->keys) keys.push_back(nested.key);
    for (const KeyRule &rule : k.nested->rules)
      if (std::find(keys.begin(), keys.end(), rule.key) == keys.end()) keys.push_back(rule.key);
    auto readMap = [&](const Field &item, const std::string &path) {
      const MapView m(report_, item, keys);
      ComponentSpec nested(k.nested->type, spec.name + "." + path);
      nested.mark = report_.sourceMark(item);
      readKeys(m, *k.nested, {}, section, scene, prefix + path + ".", nested, fields);
      return nested;
    };
    if (k.kind == ValueKind::Map) {
      spec.set(k.key, readMap(f, k.key));
      return;
    }
    if (!f.node.IsSequence() || f.node.size() == 0)
      report_.fail(f, "must be a non-empty list of maps [{...}, ...]");
    if (k.maxInt > 0 && f.node.size() > static_cast<std::size_t>(k.maxInt))
      report_.fail(f, "has " + std::to_string(f.node.size()) + " items, more than the limit of " +
                          std::to_string(k.maxInt) + (k.tooLarge.empty() ? "" : ": " + k.tooLarge));
    ComponentSpec list(k.nested->type, spec.name + "." + k.key);
    list.mark = report_.sourceMark(f);
    for (std::size_t i = 0; i < f.node.size(); ++i) {
      const std::string index = "[" + std::to_string(i) + "]";
      const Field item{f.node[i], f.path + index, f.node[i].Mark(), f.node[i].Mark()};
      list.set(std::to_string(i), readMap(item, k.key + index));
    }
    spec.set(k.key, list);
    return;
  }
  }
}

} // namespace boomdyn::scene_io
