// The checked-YAML layer of the scene reader (private to src/io): values
// are pulled out of yaml-cpp's node tree through accessors that know each
// value's key path and source position, so that every rejection can say
// "<file>:<line>:<column>: key '<path>': <reason>". Used by the scene reader
// (scene_reader.cpp: top level, bodies, analysis settings) and the component
// reader (component_reader.cpp: components of registered physics types).
//
// Nothing here uses yaml-cpp's as<T>(): its conversions accept things we do
// not want (".nan", quoted numbers, overflow to inf) and throw exceptions
// without our key path. Scalars are converted by hand instead.
#pragma once

#include "boomdyn/schema.hpp"
#include "boomdyn/scene.hpp"
#include "boomdyn/scene_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace boomdyn::scene_io {

constexpr double kPi = 3.14159265358979323846264338327950288;
constexpr double kRadPerDeg = kPi / 180.0;
constexpr int kMaxModes = 1000;
constexpr int kMaxLoadSteps = 1000000;
constexpr int kMaxNewton = 1000;
const char *const kTopLevel = "(top level)"; // path shown for the document itself

std::string join(const std::vector<std::string> &items);
// Edit distance, for "did you mean" hints on misspelt keys.
std::size_t editDistance(const std::string &a, const std::string &b);
// A short description of what a node holds, for "expected X, got Y".
std::string describeNode(const YAML::Node &node);

enum class NumberText { Ok, NotANumber, NotFinite, OutOfRange };

// Parses a YAML plain scalar as a finite double (see checked_yaml.cpp).
NumberText parseNumber(const std::string &text, double &value);

// A value in the document: the node, its key path for messages, the
// position to report for errors in the value, and the position of its key
// (or list item), reported for keys missing inside it: "dynamic:" is where
// a reader looks for the dynamic section, not the first key below it.
struct Field {
  YAML::Node node;
  std::string path;
  YAML::Mark mark;
  YAML::Mark key_mark;
};

std::string childPath(const std::string &parent, const std::string &key);

// Error reporting for one file.
class Reporter {
public:
  explicit Reporter(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Mark &mark, const std::string &path, const std::string &reason) const
  {
    // yaml-cpp marks are 0-based, and -1 when unknown.
    const int line = std::max(mark.line, 0) + 1;
    const int column = std::max(mark.column, 0) + 1;
    throw SceneError(file_ + ":" + std::to_string(line) + ":" + std::to_string(column) + ": key '" +
                     (path.empty() ? kTopLevel : path) + "': " + reason);
  }
  [[noreturn]] void fail(const Field &field, const std::string &reason) const
  {
    fail(field.mark, field.path, reason);
  }

  SourceMark sourceMark(const Field &field) const
  {
    return SourceMark{file_, std::max(field.mark.line, 0) + 1, field.path};
  }

private:
  std::string file_;
};

// The entries of a YAML map, checked once for unknown, duplicate and
// non-string keys. An empty value (null) counts as an empty map, so that
// "output:" with everything commented out below means "all defaults".
class MapView {
public:
  MapView(const Reporter &report, const Field &field, const std::vector<std::string> &allowed);


  bool has(const std::string &key) const { return entries_.count(key) > 0; }

  std::optional<Field> get(const std::string &key) const
  {
    const auto it = entries_.find(key);
    if (it == entries_.end())
      return std::nullopt;
    return it->second.field;
  }

  // Missing keys are reported at the map that lacks them.
  Field require(const std::string &key, const std::string &hint = "") const
  {
    const auto it = entries_.find(key);
    if (it == entries_.end())
      report_.fail(self_.key_mark, childPath(self_.path, key), "missing required key" + hint);
    return it->second.field;
  }

  // Rejects a key that the schema knows but that makes no sense here.
  void forbid(const std::string &key, const std::string &reason) const
  {
    const auto it = entries_.find(key);
    if (it != entries_.end())
      report_.fail(it->second.key_mark, it->second.field.path, reason);
  }

  const Field &self() const { return self_; }

  YAML::Mark keyMark(const std::string &key) const { return entries_.at(key).key_mark; }

private:
  struct Entry {
    YAML::Mark key_mark;
    Field field;
  };

  static std::string unknownKeyReason(const std::string &name, const std::vector<std::string> &allowed);


  const Reporter &report_;
  Field self_;
  std::map<std::string, Entry> entries_;
};
// The checked accessors for scalars, lists, time functions and references.
class CheckedYaml {
public:
  explicit CheckedYaml(const Reporter &report) : report_(report) {}

  // --- scalars ---------------------------------------------------------
  const std::string &scalarText(const Field &f, const std::string &expected) const;
  double number(const Field &f) const;
  double positive(const Field &f) const;
  double nonNegative(const Field &f) const;
  // Integers may be written as 8, 8.0 or 1e6, but must be whole numbers.
  int integer(const Field &f, int lo, int hi, const std::string &too_large = "") const;
  std::string text(const Field &f) const;
  // Names end up in output files and plot legends; keep them to a
  // character set that is safe in file names, HDF5 paths and CSV headers.
  std::string name(const Field &f) const;
  // One of a fixed set of words; returns its index.
  std::size_t choice(const Field &f, const std::vector<std::string> &options) const;
  std::vector<Field> list(const Field &f) const;
  std::vector<double> numbers(const Field &f) const;
  Vec2d vec2(const Field &f) const;
  Vec3d vec3(const Field &f) const;
  // --- time functions --------------------------------------------------
  // A plain number is a constant; otherwise a map with a 'type'.
  TimeFunction timeFunction(const Field &f) const;
  // Angles are written in degrees; the Scene holds radians.
  TimeFunction angleFunction(const Field &f) const { return timeFunction(f).scaled(kRadPerDeg); }

  // --- references --------------------------------------------------------
  const BodySpec &body(const Field &f, const Scene &scene) const;
  // A material coordinate: start, end or s in [0, length] in metres.
  double materialCoordinate(const Field &f, const BodySpec &b) const;
  PointRef point(const MapView &m, const Scene &scene, const std::string &body_key = "body",
                 const std::string &at_key = "at") const;
  static const BodySpec &bodyNamed(const Scene &scene, const std::string &name);
  // Names are unique within each list; `what` is e.g. "body".
  void claimName(std::map<std::string, std::string> &taken, const std::string &name, const Field &where,
                 const std::string &what, const std::string &item_path) const;
  // Name from an optional 'name' key, or "<prefix><index>".
  std::string itemName(const MapView &m, std::map<std::string, std::string> &taken, const std::string &what,
                       const std::string &default_name) const;

protected:
  const Reporter &report_;
};

// Reads the list under parent's `key` as components of `section` into the
// scene, each checked against its type's schema (component_reader.cpp).
void readComponents(const Reporter &report, const MapView &parent, const std::string &key, const std::string &section,
                    Scene &scene);
// Reads the items of `bodies` against the schemas of the body types and
// appends their typed views (BodySpec) to scene.bodies (component_reader.cpp).
void readBodies(const Reporter &report, const std::vector<Field> &items, Scene &scene);

} // namespace boomdyn::scene_io
