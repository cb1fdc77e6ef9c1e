#include "boomdyn/schema_markdown.hpp"

#include "boomdyn/physics_type.hpp"

#include <sstream>

namespace boomdyn {

namespace {

std::string number(double x)
{
  std::ostringstream out;
  out << x;
  return out.str();
}

std::string code(const std::string &s) { return "`" + s + "`"; }

std::string needText(const KeySchema &k)
{
  switch (k.need) {
  case Need::Required:
    return "yes";
  case Need::RequiredWith:
    return "with " + code(k.other);
  case Need::RequiredWithout:
    return "unless " + code(k.other);
  case Need::InForm:
    return "in its form";
  case Need::Optional:
    break;
  }
  return "no";
}

std::string kindText(const KeySchema &k)
{
  switch (k.kind) {
  case ValueKind::Number:
    return "number";
  case ValueKind::Angle:
    return "number";
  case ValueKind::Integer:
    return "integer";
  case ValueKind::Name:
    return "name";
  case ValueKind::Vec2:
    return "[x, y]";
  case ValueKind::Vec3:
    return "[x, y, z]";
  case ValueKind::TimeFunction:
    return "[time function](#time-functions)";
  case ValueKind::AngleFunction:
    return "[time function](#time-functions)";
  case ValueKind::Body:
    return "body name" + (k.differentFrom.empty() ? "" : " (not " + code(k.differentFrom) + ")");
  case ValueKind::MaterialCoordinate:
    return "material coordinate on " + code(k.bodyKey);
  case ValueKind::Component:
    return "name of a " + code(k.refType) + " listed before";
  case ValueKind::Map:
    return "map (table below)";
  case ValueKind::MapList:
    return "list of maps (table below)";
  }
  return "";
}

std::string limitText(const KeySchema &k)
{
  if (k.kind == ValueKind::Integer) return std::to_string(k.minInt) + " to " + std::to_string(k.maxInt);
  if (k.kind == ValueKind::MapList && k.maxInt > 0) return "1 to " + std::to_string(k.maxInt) + " items";
  std::string text = k.limit == Limit::Positive ? "> 0" : k.limit == Limit::NonNegative ? ">= 0" : "";
  if (k.maxNumber < std::numeric_limits<double>::infinity())
    text += (text.empty() ? "<= " : ", <= ") + number(k.maxNumber) + " (" + k.maxReason + ")";
  return text;
}

std::string defaultText(const KeySchema &k)
{
  if (!k.defaultText.empty()) return k.defaultText;
  return k.hasDefault ? number(k.defaultNumber) : "";
}

std::string sectionNoun(const std::string &section)
{
  return section.substr(section.find('.') == std::string::npos ? 0 : section.find('.') + 1);
}

void table(std::ostream &out, const TypeSchema &s, bool typeKey, bool nameKey, int dimension = 2)
{
  out << "| key | required | kind | unit | default | limits | meaning |\n";
  out << "| --- | --- | --- | --- | --- | --- | --- |\n";
  // Bodies: `type` may be left out (the first body type), `name` may not.
  const bool bodies = s.section == "bodies";
  const PhysicsType *defaultBody = bodies ? physicsTypesOf("bodies", dimension).at(0) : nullptr;
  if (typeKey)
    out << "| `type` | " << (bodies && defaultBody->schema.type != s.type ? "yes" : "no") << " | " << code(s.type)
        << " | | " << (bodies ? code(defaultBody->schema.type) : "") << " | | selects this table |\n";
  if (nameKey && bodies)
    out << "| `name` | yes | name | | | unique among bodies | constraints, loads and sensors refer to it |\n";
  else if (nameKey)
    out << "| `name` | no | name | | " << code(s.defaultName + "<index>") << " | unique among " << sectionNoun(s.section)
        << " | index: position in the list, from 0 |\n";
  for (const KeySchema &k : s.keys)
    out << "| " << code(k.key) << " | " << needText(k) << " | " << kindText(k) << " | " << k.unit << " | "
        << defaultText(k) << " | " << limitText(k) << " | " << k.help << " |\n";
  // Keys of sibling types (Always) need no line: the tables say where they belong.
  bool any = false;
  for (const KeyRule &r : s.rules) {
    if (r.when == KeyRule::When::Always) continue;
    out << (any ? "" : "\n") << "- " << code(r.key) << (r.when == KeyRule::When::IfPresent ? " with " : " without ")
        << code(r.condition) << ": " << r.reason << ".\n";
    any = true;
  }
}

} // namespace

std::string schemaMarkdown(const std::string &section)
{
  std::ostringstream out;
  const bool typeKey = section == "bodies" || section == "constraints" || section == "loads";
  bool first = true;
  // Planar types first, then the spatial ones (scenes with `dimension: 3`).
  std::vector<const PhysicsType *> types = physicsTypesOf(section, 2), spatial = physicsTypesOf(section, 3);
  types.insert(types.end(), spatial.begin(), spatial.end());
  for (const PhysicsType *t : types) {
    const TypeSchema &s = t->schema;
    out << (first ? "" : "\n") << "#### " << code(s.type) << (t->dimension == 3 ? " (spatial scenes)" : "") << "\n\n"
        << s.summary << "\n\n";
    first = false;
    table(out, s, typeKey, true, t->dimension);
    for (const KeySchema &k : s.keys)
      if ((k.kind == ValueKind::Map || k.kind == ValueKind::MapList) && k.nested) {
        out << "\n" << code(s.type) << "." << code(k.key) << ": " << k.nested->summary << "\n\n";
        table(out, *k.nested, false, false);
        if (!k.nested->forms.empty()) out << "\nForms: " << k.nested->formsText << " (exactly one).\n";
      }
  }
  return out.str();
}

std::string regenerateSchemaBlocks(const std::string &doc)
{
  std::string out = doc;
  std::vector<std::string> sections{"bodies"};
  for (const std::string &section : Scene::componentSections()) sections.push_back(section);
  for (const std::string &section : sections) {
    const std::string begin = "<!-- BEGIN generated: " + section + " -->\n", end = "<!-- END generated: " + section + " -->";
    const std::size_t a = out.find(begin);
    if (a == std::string::npos) throw std::runtime_error("no line '" + begin.substr(0, begin.size() - 1) + "'");
    const std::size_t b = out.find(end, a);
    if (b == std::string::npos) throw std::runtime_error("no line '" + end + "' after '" + begin.substr(0, begin.size() - 1) + "'");
    out.replace(a + begin.size(), b - a - begin.size(), schemaMarkdown(section));
  }
  return out;
}

} // namespace boomdyn
