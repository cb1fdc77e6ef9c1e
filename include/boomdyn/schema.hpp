// The scene schema of a physics type as plain data: which keys a component
// of the type takes, what kind of value each holds, its unit, limits,
// default and help text. The type file (src/constraints/pin_type.cpp, ...)
// writes it; the io layer interprets it (io/component_reader.cpp checks the
// YAML against it, io/schema_markdown.cpp prints docs/scenes.md's tables).
// Nothing here knows YAML, so physics types do not depend on io.
#pragma once

#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace boomdyn {

enum class ValueKind {
  Number,             // a finite number
  Angle,              // a finite number in degrees (stored in radians)
  Integer,            // a whole number (8, 8.0 or 1e6)
  Name,               // letters, digits, '_', '-', '.'
  Vec2,               // [x, y]
  Vec3,               // [x, y, z] (spatial scenes)
  TimeFunction,       // a number or a time function map {type: ...}
  AngleFunction,      // a TimeFunction in degrees (stored in radians)
  Body,               // the name of a body
  MaterialCoordinate, // start, end or s in [0, length] of the body named by KeySchema::bodyKey
  Component,          // the name of a component of type KeySchema::refType listed before this one
  Map,                // a nested map checked against KeySchema::nested
  MapList,            // a list of such maps; in the spec a map of the items by index "0", "1", ...
};

enum class Limit { None, Positive, NonNegative };

// When a key must be given.
enum class Need {
  Optional,        // may be left out (default: KeySchema::defaultText)
  Required,        // always
  RequiredWith,    // when KeySchema::other is given
  RequiredWithout, // when KeySchema::other is not given
  InForm,          // when the map is written in the form (TypeSchema::forms) that lists this key
};

struct TypeSchema;

struct KeySchema {
  std::string key;
  ValueKind kind = ValueKind::Number;
  std::string unit; // "m", "N", "deg", "" for dimensionless or names
  Need need = Need::Optional;
  std::string other;       // the key that Need::RequiredWith/RequiredWithout refers to
  Limit limit = Limit::None;
  int minInt = 0, maxInt = 0; // Integer: allowed range; MapList: at most maxInt items (0: any number)
  std::string tooLarge;       // Integer, MapList: why the upper limit exists ("mesh too large"), for the message
  // Number: the largest plausible value (infinite: none) and why, for the
  // message and the docs ("a steel bar of 5 m^2").
  double maxNumber = std::numeric_limits<double>::infinity();
  std::string maxReason;
  // Optional keys: the value used when the key is absent (Number only;
  // hasDefault false: the key stays absent and the builder derives it).
  bool hasDefault = false;
  double defaultNumber = 0;
  std::string defaultText; // for the docs: "0", "initial distance", ...
  std::string bodyKey;       // MaterialCoordinate: the key naming the body
  std::string differentFrom; // Body: must name another body than this key's
  std::string refType;       // Component: the type it must name ("sliding_joint")
  const TypeSchema *nested = nullptr; // Map: the schema of the nested map
  std::string help;

  // Chainable refinements, so that a type file reads as a table:
  //   key("at", ValueKind::MaterialCoordinate, "m", Need::Required, "...").onBody("body")
  KeySchema positive() const { return with([](KeySchema &k) { k.limit = Limit::Positive; }); }
  KeySchema nonNegative() const { return with([](KeySchema &k) { k.limit = Limit::NonNegative; }); }
  KeySchema between(int lo, int hi) const { return with([&](KeySchema &k) { k.minInt = lo, k.maxInt = hi; }); }
  KeySchema tooLargeMeans(std::string why) const { return with([&](KeySchema &k) { k.tooLarge = why; }); }
  KeySchema atMost(double most, std::string why) const
  {
    return with([&](KeySchema &k) { k.maxNumber = most, k.maxReason = why; });
  }
  KeySchema byDefault(double value, std::string text = "") const
  {
    return with([&](KeySchema &k) { k.hasDefault = true, k.defaultNumber = value, k.defaultText = text; });
  }
  KeySchema derived(std::string text) const { return with([&](KeySchema &k) { k.defaultText = text; }); }
  KeySchema onBody(std::string key) const { return with([&](KeySchema &k) { k.bodyKey = key; }); }
  KeySchema unlike(std::string key) const { return with([&](KeySchema &k) { k.differentFrom = key; }); }
  KeySchema naming(std::string type) const { return with([&](KeySchema &k) { k.refType = type; }); }
  KeySchema holding(const TypeSchema &schema) const { return with([&](KeySchema &k) { k.nested = &schema; }); }
  KeySchema requiredWith(std::string key) const { return with([&](KeySchema &k) { k.need = Need::RequiredWith, k.other = key; }); }
  KeySchema requiredWithout(std::string key) const
  {
    return with([&](KeySchema &k) { k.need = Need::RequiredWithout, k.other = key; });
  }

private:
  template <typename F> KeySchema with(F change) const
  {
    KeySchema k = *this;
    change(k);
    return k;
  }
};

// A number as scene messages print it (10 significant digits), for limits
// and values in the reader's and the types' messages.
inline std::string numberText(double x)
{
  std::ostringstream out;
  out.precision(10);
  out << x;
  return out.str();
}

inline KeySchema key(std::string name, ValueKind kind, std::string unit, Need need, std::string help)
{
  KeySchema k;
  k.key = std::move(name);
  k.kind = kind;
  k.unit = std::move(unit);
  k.need = need;
  k.help = std::move(help);
  return k;
}

// A key that this type does not take although a sibling type in the same
// section does, or that clashes with another key: the reason is the message.
struct KeyRule {
  enum class When { Always, IfPresent, IfAbsent };
  std::string key;
  When when = When::Always;
  std::string condition; // the key tested by IfPresent/IfAbsent
  std::string reason;
};

// A rule that forbids `key` whatever else is given.
inline KeyRule forbid(std::string key, std::string reason)
{
  return KeyRule{std::move(key), KeyRule::When::Always, "", std::move(reason)};
}
inline KeyRule forbidIfPresent(std::string condition, std::string key, std::string reason)
{
  return KeyRule{std::move(key), KeyRule::When::IfPresent, std::move(condition), std::move(reason)};
}
inline KeyRule forbidIfAbsent(std::string condition, std::string key, std::string reason)
{
  return KeyRule{std::move(key), KeyRule::When::IfAbsent, std::move(condition), std::move(reason)};
}

struct TypeSchema {
  std::string section; // "bodies", "constraints", "loads", "masses", "springs", "output.sensors", "output.frames"
  std::string type;    // the value of `type:` ("pin"); sections without a type key have one type
  std::string summary; // one line for the docs
  std::string defaultName; // name prefix when `name` is absent: prefix + index in the section
  std::vector<KeySchema> keys;
  std::vector<KeyRule> rules;
  // Alternative ways to write the map (a body's section: stiffnesses, or
  // material and geometry): each form lists its keys; a map must use
  // exactly one form, whose Need::InForm keys are then required.
  // formsText names them in messages ("rhoA, or rho and A").
  std::vector<std::vector<std::string>> forms;
  std::string formsText;

  const KeySchema *find(const std::string &key) const
  {
    for (const KeySchema &k : keys)
      if (k.key == key) return &k;
    return nullptr;
  }
};

} // namespace boomdyn
