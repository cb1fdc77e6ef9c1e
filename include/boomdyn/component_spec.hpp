// One component of a scene (a constraint, load, mass, spring or sensor) as
// validated plain data: its type, name, and the values of its keys in SI
// units (angles in radians), as its TypeSchema describes them. The scene
// reader fills it; the type's builder reads it. Scenes built in code (tests)
// fill it with set().
#pragma once

#include "boomdyn/time_function.hpp"

#include <array>
#include <map>
#include <memory>
#include <string>
#include <variant>

namespace boomdyn {

using Vec2d = std::array<double, 2>;
using Vec3d = std::array<double, 3>;

// Where a value came from, for messages raised after parsing.
struct SourceMark {
  std::string file;
  int line = 0; // 1-based, 0 = unknown
  std::string key;
};

// A material point: body name and material coordinate s in [0, length].
struct PointRef {
  std::string body;
  double s = 0;
};

struct ComponentSpec;
// Numbers and integers are doubles; body and component names are strings;
// nested maps (friction) are components of their own.
using SpecValue = std::variant<double, std::string, Vec2d, TimeFunction, std::shared_ptr<const ComponentSpec>, Vec3d>;

struct ComponentSpec {
  ComponentSpec() = default;
  ComponentSpec(std::string type_, std::string name_) : type(std::move(type_)), name(std::move(name_)) {}

  std::string type; // e.g. "sliding_joint"
  std::string name;
  SourceMark mark;  // the list item
  std::map<std::string, SpecValue> values;

  bool has(const std::string &key) const { return values.count(key) > 0; }
  ComponentSpec &set(const std::string &key, SpecValue value)
  {
    values[key] = std::move(value);
    return *this;
  }
  ComponentSpec &set(const std::string &key, const ComponentSpec &nested)
  {
    return set(key, SpecValue(std::make_shared<const ComponentSpec>(nested)));
  }

  // Typed access; a missing key or a value of another kind is a program
  // error (the schema guarantees both) and throws std::logic_error.
  double number(const std::string &key) const;
  int integer(const std::string &key) const;
  const std::string &text(const std::string &key) const;
  Vec2d vec2(const std::string &key) const;
  Vec3d vec3(const std::string &key) const;
  const TimeFunction &function(const std::string &key) const;
  const ComponentSpec &map(const std::string &key) const;
  // The material point named by a body key and a material coordinate key.
  PointRef point(const std::string &bodyKey = "body", const std::string &atKey = "at") const;

  // The value of an optional key, or fallback.
  double numberOr(const std::string &key, double fallback) const { return has(key) ? number(key) : fallback; }
};

} // namespace boomdyn
