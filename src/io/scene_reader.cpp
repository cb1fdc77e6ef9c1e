// Scene file reader: YAML text -> validated Scene (format: docs/scenes.md).
//
// Design: yaml-cpp only builds the node tree. Every value is then pulled out
// through a few checked accessors (MapView, number, integer, ...) that know
// the value's key path and source position, so any rejection can say
// "<file>:<line>:<column>: key '<path>': <reason>". The reader stops at the
// first error: later errors are often consequences of the first one.
//
// Nothing here uses yaml-cpp's as<T>(): its conversions accept things we do
// not want (".nan", quoted numbers, overflow to inf) and throw exceptions
// without our key path. Scalars are converted by hand instead.
#include "boomdyn/scene_reader.hpp"

#include "boomdyn/physics_type.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <system_error>

namespace boomdyn {

namespace {

constexpr double kPi = 3.14159265358979323846264338327950288;
constexpr double kRadPerDeg = kPi / 180.0;
constexpr int kMaxElements = 10000000; // beyond this the Jacobian alone is many GB
constexpr int kMaxModes = 1000;
constexpr int kMaxLoadSteps = 1000000;
constexpr int kMaxNewton = 1000;
const char *const kTopLevel = "(top level)"; // path shown for the document itself

std::string join(const std::vector<std::string> &items)
{
  std::string out;
  for (const auto &item : items)
    out += (out.empty() ? "" : ", ") + item;
  return out;
}

std::string fmt(double x)
{
  std::ostringstream out;
  out.precision(10);
  out << x;
  return out.str();
}

// Edit distance, for "did you mean" hints on misspelt keys.
std::size_t editDistance(const std::string &a, const std::string &b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// A short description of what a node holds, for "expected X, got Y".
std::string describeNode(const YAML::Node &node)
{
  switch (node.Type()) {
  case YAML::NodeType::Null:
  case YAML::NodeType::Undefined:
    return "nothing";
  case YAML::NodeType::Sequence:
    return "a list";
  case YAML::NodeType::Map:
    return "a map";
  case YAML::NodeType::Scalar:
    break;
  }
  std::string text = node.Scalar();
  if (text.size() > 40)
    text = text.substr(0, 37) + "...";
  return (node.Tag() == "!" ? "the quoted string '" : "'") + text + "'";
}

enum class NumberText { Ok, NotANumber, NotFinite, OutOfRange };

// Parses a YAML plain scalar as a finite double. Locale-independent
// (from_chars); YAML's .nan/.inf spellings and C's nan/inf are all refused,
// as are values that overflow a double (1e999).
NumberText parseNumber(const std::string &text, double &value)
{
  // [+-][.](nan|inf|infinity), any case: YAML's and C's spellings.
  std::string word = text;
  std::transform(word.begin(), word.end(), word.begin(), [](unsigned char c) { return std::tolower(c); });
  word.erase(0, word.find_first_not_of("+-"));
  word.erase(0, word.find_first_not_of('.'));
  if (word == "nan" || word == "inf" || word == "infinity")
    return NumberText::NotFinite;
  const char *begin = text.data();
  const char *end = text.data() + text.size();
  if (begin != end && *begin == '+') // YAML allows an explicit plus sign
    ++begin;
  const auto [stop, error] = std::from_chars(begin, end, value);
  if (error == std::errc::result_out_of_range)
    return NumberText::OutOfRange;
  if (error != std::errc() || stop != end || begin == end)
    return NumberText::NotANumber;
  return std::isfinite(value) ? NumberText::Ok : NumberText::NotFinite;
}

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

std::string childPath(const std::string &parent, const std::string &key)
{
  return parent.empty() ? key : parent + "." + key;
}

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
  MapView(const Reporter &report, const Field &field, const std::vector<std::string> &allowed)
    : report_(report), self_(field)
  {
    if (!field.node.IsMap() && !field.node.IsNull())
      report.fail(field, "expected a map of keys (" + join(allowed) + "), got " + describeNode(field.node));
    if (field.node.IsNull())
      return;
    for (auto it = field.node.begin(); it != field.node.end(); ++it) {
      // Copies, not references: the iterator hands out a temporary pair.
      const YAML::Node key = it->first;
      const YAML::Node value = it->second;
      if (!key.IsScalar())
        report.fail(key.Mark(), field.path, "keys must be plain names, got " + describeNode(key) + " as a key");
      const std::string name = key.Scalar();
      const std::string path = childPath(field.path, name);
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
        report.fail(key.Mark(), path, unknownKeyReason(name, allowed));
      if (entries_.count(name))
        report.fail(key.Mark(), path,
                    "duplicate key (first given on line " + std::to_string(entries_.at(name).key_mark.line + 1) +
                        ")");
      // An empty value has no position of its own (yaml-cpp reports the
      // next token), so point at its key instead.
      const YAML::Mark mark = value.IsNull() ? key.Mark() : value.Mark();
      entries_.emplace(name, Entry{key.Mark(), Field{value, path, mark, key.Mark()}});
    }
  }

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

  static std::string unknownKeyReason(const std::string &name, const std::vector<std::string> &allowed)
  {
    std::string reason = "unknown key";
    // Suggest only close matches that share at least one character
    // position, so that "G" does not suggest "E".
    std::size_t best = std::min<std::size_t>(3, name.size());
    std::string suggestion;
    for (const auto &candidate : allowed) {
      const std::size_t d = editDistance(name, candidate);
      if (d < best) {
        best = d;
        suggestion = candidate;
      }
    }
    if (!suggestion.empty())
      reason += " (did you mean '" + suggestion + "'?)";
    return reason + "; allowed keys here: " + join(allowed);
  }

  const Reporter &report_;
  Field self_;
  std::map<std::string, Entry> entries_;
};

// Converts the scene document into a Scene, one section at a time.
class SceneParser {
public:
  explicit SceneParser(const Reporter &report) : report_(report) {}

  void parse(const Field &root, Scene &scene);

private:
  // --- scalars ---------------------------------------------------------
  const std::string &scalarText(const Field &f, const std::string &expected) const
  {
    if (!f.node.IsScalar())
      report_.fail(f, "expected " + expected + ", got " + describeNode(f.node));
    return f.node.Scalar();
  }

  double number(const Field &f) const
  {
    const std::string &text = scalarText(f, "a number");
    // A quoted "2.0" is a string in YAML; accepting it would hide typos
    // such as a misplaced quote swallowing the rest of the line.
    if (f.node.Tag() == "!")
      report_.fail(f, "expected a number, got " + describeNode(f.node));
    double value = 0;
    switch (parseNumber(text, value)) {
    case NumberText::Ok:
      return value;
    case NumberText::NotFinite:
      report_.fail(f, "must be a finite number (got " + text + ")");
    case NumberText::OutOfRange:
      report_.fail(f, "number out of range (got " + text + ")");
    case NumberText::NotANumber:
      break;
    }
    report_.fail(f, "expected a number, got " + describeNode(f.node));
  }

  double positive(const Field &f) const
  {
    const double x = number(f);
    if (!(x > 0))
      report_.fail(f, "must be > 0 (got " + f.node.Scalar() + ")");
    return x;
  }

  double nonNegative(const Field &f) const
  {
    const double x = number(f);
    if (!(x >= 0))
      report_.fail(f, "must be >= 0 (got " + f.node.Scalar() + ")");
    return x;
  }

  // Integers may be written as 8, 8.0 or 1e6, but must be whole numbers.
  int integer(const Field &f, int lo, int hi, const std::string &too_large = "") const
  {
    const double x = number(f);
    if (std::floor(x) != x)
      report_.fail(f, "must be a whole number (got " + f.node.Scalar() + ")");
    if (x < lo)
      report_.fail(f, "must be >= " + std::to_string(lo) + " (got " + f.node.Scalar() + ")");
    if (x > hi)
      report_.fail(f, (too_large.empty() ? "" : too_large + ": ") + "must be <= " + std::to_string(hi) +
                          " (got " + f.node.Scalar() + ")");
    return static_cast<int>(x);
  }

  std::string text(const Field &f) const
  {
    const std::string &s = scalarText(f, "a text");
    if (s.empty())
      report_.fail(f, "must not be empty");
    return s;
  }

  // Names end up in output files and plot legends; keep them to a
  // character set that is safe in file names, HDF5 paths and CSV headers.
  std::string name(const Field &f) const
  {
    const std::string s = text(f);
    const bool safe = std::all_of(s.begin(), s.end(), [](unsigned char c) {
      return std::isalnum(c) || c == '_' || c == '-' || c == '.';
    });
    if (!safe)
      report_.fail(f, "names may contain only letters, digits, '_', '-' and '.' (got '" + s + "')");
    return s;
  }

  // One of a fixed set of words; returns its index.
  std::size_t choice(const Field &f, const std::vector<std::string> &options) const
  {
    const std::string expected = "one of " + join(options);
    const std::string &s = scalarText(f, expected);
    const auto it = std::find(options.begin(), options.end(), s);
    if (it == options.end())
      report_.fail(f, "must be " + expected + " (got '" + s + "')");
    return static_cast<std::size_t>(it - options.begin());
  }

  std::vector<Field> list(const Field &f) const
  {
    if (f.node.IsNull())
      return {};
    if (!f.node.IsSequence())
      report_.fail(f, "expected a list, got " + describeNode(f.node));
    std::vector<Field> items;
    for (std::size_t i = 0; i < f.node.size(); ++i) {
      const YAML::Node item = f.node[i];
      const YAML::Mark mark = item.IsNull() ? f.mark : item.Mark();
      items.push_back(Field{item, f.path + "[" + std::to_string(i) + "]", mark, mark});
    }
    return items;
  }

  std::vector<double> numbers(const Field &f) const
  {
    if (!f.node.IsSequence())
      report_.fail(f, "expected a list of numbers, got " + describeNode(f.node));
    std::vector<double> values;
    for (const Field &item : list(f))
      values.push_back(number(item));
    return values;
  }

  Vec2d vec2(const Field &f) const
  {
    if (!f.node.IsSequence() || f.node.size() != 2)
      report_.fail(f, "expected a list of two numbers [x, y], got " +
                          (f.node.IsSequence() ? "a list of " + std::to_string(f.node.size())
                                               : describeNode(f.node)));
    const auto items = list(f);
    return {number(items[0]), number(items[1])};
  }

  // --- time functions --------------------------------------------------
  // A plain number is a constant; otherwise a map with a 'type'.
  TimeFunction timeFunction(const Field &f) const
  {
    if (f.node.IsScalar())
      return TimeFunction::constant(number(f));
    if (!f.node.IsMap())
      report_.fail(f, "expected a number or a time function map {type: ...}, got " + describeNode(f.node));
    const MapView m(report_, f,
                    {"type", "value", "t0", "t1", "from", "to", "t", "values", "amplitude", "frequency", "phase",
                     "offset"});
    const std::vector<std::string> types{"constant", "ramp", "smooth_step", "table", "sine"};
    const std::size_t type = choice(m.require("type", " (one of " + join(types) + ")"), types);
    // Each kind accepts only its own parameters.
    const std::vector<std::vector<std::string>> keys_of_type{
        {"value"},
        {"t0", "t1", "from", "to"},
        {"t0", "t1", "from", "to"},
        {"t", "values"},
        {"amplitude", "frequency", "phase", "offset", "t0"}};
    for (const char *key : {"value", "t0", "t1", "from", "to", "t", "values", "amplitude", "frequency",
                             "phase", "offset"}) {
      const auto &own = keys_of_type[type];
      if (std::find(own.begin(), own.end(), key) == own.end())
        m.forbid(key, "not a parameter of a " + types[type] + " function (it takes " + join(own) + ")");
    }
    switch (type) {
    case 0:
      return TimeFunction::constant(number(m.require("value")));
    case 1:
    case 2: {
      const double t0 = number(m.require("t0"));
      const Field t1_field = m.require("t1");
      const double t1 = number(t1_field);
      if (!(t1 > t0))
        report_.fail(t1_field, "must be > t0 (got t0 = " + fmt(t0) + ", t1 = " + fmt(t1) + ")");
      const double from = number(m.require("from"));
      const double to = number(m.require("to"));
      return type == 1 ? TimeFunction::ramp(t0, t1, from, to) : TimeFunction::smoothStep(t0, t1, from, to);
    }
    case 3: {
      const Field t_field = m.require("t");
      const Field v_field = m.require("values");
      const std::vector<double> t = numbers(t_field);
      const std::vector<double> v = numbers(v_field);
      if (t.size() < 2)
        report_.fail(t_field, "a table needs at least 2 points (got " + std::to_string(t.size()) + ")");
      if (v.size() != t.size())
        report_.fail(v_field, "must have as many entries as t (" + std::to_string(t.size()) + "), got " +
                                  std::to_string(v.size()));
      const auto items = list(t_field);
      for (std::size_t k = 1; k < t.size(); ++k)
        if (!(t[k] > t[k - 1]))
          report_.fail(items[k], "times must be strictly increasing (t[" + std::to_string(k) + "] = " +
                                     fmt(t[k]) + " after " + fmt(t[k - 1]) + ")");
      return TimeFunction::table(t, v);
    }
    default: {
      const double amplitude = number(m.require("amplitude"));
      const double frequency = nonNegative(m.require("frequency"));
      const double phase_deg = m.has("phase") ? number(*m.get("phase")) : 0.0;
      const double offset = m.has("offset") ? number(*m.get("offset")) : 0.0;
      const double t0 = m.has("t0") ? number(*m.get("t0")) : 0.0;
      return TimeFunction::sine(amplitude, frequency, phase_deg * kRadPerDeg, offset, t0);
    }
    }
  }

  // Angles are written in degrees; the Scene holds radians.
  TimeFunction angleFunction(const Field &f) const { return timeFunction(f).scaled(kRadPerDeg); }

  // --- references --------------------------------------------------------
  const BodySpec &body(const Field &f, const Scene &scene) const
  {
    const std::string s = text(f);
    for (const BodySpec &b : scene.bodies)
      if (b.name == s)
        return b;
    std::vector<std::string> names;
    for (const BodySpec &b : scene.bodies)
      names.push_back(b.name);
    report_.fail(f, "unknown body '" + s + "' (bodies: " + join(names) + ")");
  }

  // A material coordinate: start, end or s in [0, length] in metres.
  double materialCoordinate(const Field &f, const BodySpec &b) const
  {
    const std::string expected = "start, end or a number in [0, " + fmt(b.length) + "] (the length of body '" +
                                 b.name + "', m)";
    if (f.node.IsScalar() && f.node.Scalar() == "start")
      return 0.0;
    if (f.node.IsScalar() && f.node.Scalar() == "end")
      return b.length;
    double parsed = 0;
    if (!f.node.IsScalar() || f.node.Tag() == "!" || parseNumber(f.node.Scalar(), parsed) == NumberText::NotANumber)
      report_.fail(f, "expected " + expected + ", got " + describeNode(f.node));
    const double s = number(f);
    if (s < 0 || s > b.length)
      report_.fail(f, "must be " + expected + " (got " + f.node.Scalar() + ")");
    return s;
  }

  PointRef point(const MapView &m, const Scene &scene, const std::string &body_key = "body",
                 const std::string &at_key = "at") const
  {
    const BodySpec &b = body(m.require(body_key), scene);
    return PointRef{b.name, materialCoordinate(m.require(at_key), b)};
  }

  static const BodySpec &bodyNamed(const Scene &scene, const std::string &name)
  {
    return *std::find_if(scene.bodies.begin(), scene.bodies.end(),
                         [&](const BodySpec &b) { return b.name == name; });
  }

  // Names are unique within each list; `what` is e.g. "body".
  void claimName(std::map<std::string, std::string> &taken, const std::string &name, const Field &where,
                 const std::string &what, const std::string &item_path) const
  {
    const auto [it, inserted] = taken.emplace(name, item_path);
    if (!inserted)
      report_.fail(where, "duplicate " + what + " name '" + name + "' (also used by " + it->second + ")");
  }

  // Name from an optional 'name' key, or "<prefix><index>".
  std::string itemName(const MapView &m, std::map<std::string, std::string> &taken, const std::string &what,
                       const std::string &default_name) const
  {
    const std::optional<Field> given = m.get("name");
    const std::string result = given ? name(*given) : default_name;
    claimName(taken, result, given ? *given : m.self(), what, m.self().path);
    return result;
  }

  // --- sections ----------------------------------------------------------
  BodySpec parseBody(const Field &f, std::map<std::string, std::string> &taken) const;
  SectionSpec parseSection(const Field &f, bool rigid) const;
  // Components of registered physics types (physics_type.hpp).
  void parseSection(const MapView &parent, const std::string &key, const std::string &section, Scene &scene) const;
  ComponentSpec parseComponent(const Field &f, std::size_t index, const std::string &section, const Scene &scene,
                               std::map<std::string, std::string> &taken) const;
  void readKeys(const MapView &m, const TypeSchema &schema, const std::vector<const PhysicsType *> &siblings,
                const std::string &section, const Scene &scene, const std::string &prefix, ComponentSpec &spec,
                std::map<std::string, Field> &fields) const;
  void readValue(const Field &f, const KeySchema &k, const std::string &section, const Scene &scene,
                 const std::string &prefix, ComponentSpec &spec, std::map<std::string, Field> &fields) const;
  DynamicSpec parseDynamic(const Field &f) const;
  StaticSpec parseStatic(const Field &f) const;
  ModalSpec parseModal(const Field &f, bool required_nonzero) const;
  void parseOutput(const Field &f, Scene &scene) const;

  const Reporter &report_;
};

void SceneParser::parse(const Field &root, Scene &scene)
{
  const MapView top(report_, root,
                    {"name", "description", "analysis", "gravity", "bodies", "constraints", "loads", "masses",
                     "springs", "dynamic", "static", "modal", "tracking", "output"});
  scene.name = name(top.require("name"));
  if (const auto d = top.get("description"))
    scene.description = d->node.IsNull() ? "" : scalarText(*d, "a text");

  const std::vector<std::string> analyses{"static", "dynamic", "modal"};
  const Scene::Analysis analysis_of[] = {Scene::Analysis::Static, Scene::Analysis::Dynamic,
                                         Scene::Analysis::Modal};
  const std::size_t analysis = choice(top.require("analysis", " (one of " + join(analyses) + ")"), analyses);
  scene.analysis = analysis_of[analysis];

  if (const auto g = top.get("gravity"))
    scene.gravity = vec2(*g);

  // Bodies first: everything else refers to them.
  const Field bodies_field = top.require("bodies");
  const std::vector<Field> bodies = list(bodies_field);
  if (bodies.empty())
    report_.fail(bodies_field, "needs at least one body");
  std::map<std::string, std::string> body_names;
  for (const Field &item : bodies)
    scene.bodies.push_back(parseBody(item, body_names));

  parseSection(top, "constraints", "constraints", scene);
  parseSection(top, "loads", "loads", scene);
  parseSection(top, "masses", "masses", scene);

  // Analysis settings: a section that the chosen analysis would ignore is
  // an error, since the user evidently expected it to matter.
  const std::string chosen = " (analysis is " + analyses[analysis] + ")";
  if (scene.analysis == Scene::Analysis::Dynamic)
    scene.dynamic = parseDynamic(top.require("dynamic", " for analysis dynamic (t_end and dt)"));
  else
    top.forbid("dynamic", "only allowed when analysis is dynamic" + chosen);

  if (scene.analysis == Scene::Analysis::Dynamic)
    top.forbid("static", "only allowed when analysis is static or modal" + chosen);
  else if (const auto s = top.get("static"))
    scene.statics = parseStatic(*s);

  if (scene.analysis == Scene::Analysis::Modal)
    scene.modal = parseModal(top.require("modal", " for analysis modal (count >= 1)"), true);
  else if (const auto m = top.get("modal"))
    scene.modal = parseModal(*m, false);

  parseSection(top, "springs", "springs", scene);
  if (const auto tr = top.get("tracking")) {
    if (scene.analysis != Scene::Analysis::Dynamic)
      report_.fail(*tr, "frequency tracking needs 'analysis: dynamic'");
    const MapView m(report_, *tr, {"interval", "count", "shapes_at"});
    scene.tracking.interval = positive(m.require("interval"));
    if (const auto c = m.get("count")) scene.tracking.count = integer(*c, 1, 100);
    if (const auto sa = m.get("shapes_at"))
      for (const Field &item : list(*sa)) scene.tracking.shapesAt.push_back(nonNegative(item));
  }
  if (const auto o = top.get("output"))
    parseOutput(*o, scene);
}

BodySpec SceneParser::parseBody(const Field &f, std::map<std::string, std::string> &taken) const
{
  const MapView m(report_, f, {"name", "type", "length", "elements", "origin", "angle", "section"});
  BodySpec b;
  b.mark = report_.sourceMark(f);
  const Field name_field = m.require("name");
  b.name = name(name_field);
  claimName(taken, b.name, name_field, "body", f.path);

  if (const auto t = m.get("type"))
    b.type = choice(*t, {"ancf_beam", "rigid"}) == 0 ? BodySpec::Type::AncfBeam : BodySpec::Type::Rigid;
  const bool rigid = b.type == BodySpec::Type::Rigid;

  b.length = positive(m.require("length"));
  if (rigid) {
    m.forbid("elements", "not allowed for a rigid body (it has no mesh)");
    b.elements = 1;
  } else {
    b.elements = integer(m.require("elements"), 1, kMaxElements, "mesh too large");
  }
  if (const auto o = m.get("origin"))
    b.origin = vec2(*o);
  if (const auto a = m.get("angle"))
    b.angle = number(*a) * kRadPerDeg;
  b.section = parseSection(m.require("section"), rigid);
  return b;
}

// Two ways to give a section: the stiffnesses directly (EA, EI, rhoA) or
// the material and geometry (E, A, I, rho). A rigid body needs only its
// mass per length (rhoA, or rho and A).
SectionSpec SceneParser::parseSection(const Field &f, bool rigid) const
{
  const MapView m(report_, f, {"EA", "EI", "rhoA", "E", "A", "I", "rho"});
  if (rigid)
    for (const char *key : {"EA", "EI", "E", "I"})
      m.forbid(key, "a rigid body has no stiffness; give its mass per length: rhoA, or rho and A");
  const bool direct = m.has("EA") || m.has("EI") || m.has("rhoA");
  const bool material = m.has("E") || m.has("A") || m.has("I") || m.has("rho");
  const std::string forms = rigid ? "rhoA, or rho and A" : "EA, EI, rhoA, or E, A, I, rho";
  if (direct && material)
    report_.fail(f, "give either " + forms + " (not a mix of the two forms)");
  if (!direct && !material)
    report_.fail(f, "needs " + forms);

  SectionSpec s;
  if (direct) {
    if (!rigid) {
      s.EA = positive(m.require("EA"));
      s.EI = positive(m.require("EI"));
    }
    s.rhoA = positive(m.require("rhoA"));
    return s;
  }
  // Products of large or small inputs can overflow or underflow.
  const auto product = [&](const Field &where, double a, double b, const std::string &what) {
    const double p = a * b;
    if (!std::isfinite(p) || !(p > 0))
      report_.fail(where, what + " = " + fmt(a) + " * " + fmt(b) + " is out of range");
    return p;
  };
  const double A = positive(m.require("A"));
  const Field rho_field = m.require("rho");
  const double rho = positive(rho_field);
  s.rhoA = product(rho_field, rho, A, "rhoA");
  if (!rigid) {
    const Field E_field = m.require("E");
    const double E = positive(E_field);
    const double I = positive(m.require("I"));
    s.EA = product(E_field, E, A, "EA");
    s.EI = product(E_field, E, I, "EI");
  }
  return s;
}

// --- components of registered physics types ------------------------------

namespace {

// Sections whose items name their type with `type:`; the others hold one type.
bool hasTypeKey(const std::string &section) { return section == "constraints" || section == "loads"; }

// The noun in "duplicate <noun> name".
std::string itemNoun(const std::string &section)
{
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

} // namespace

void SceneParser::parseSection(const MapView &parent, const std::string &key, const std::string &section,
                               Scene &scene) const
{
  const auto field = parent.get(key);
  if (!field) return;
  std::map<std::string, std::string> taken;
  const auto items = list(*field);
  for (std::size_t i = 0; i < items.size(); ++i) {
    // Push before the next item is read: later items may refer to earlier ones.
    ComponentSpec spec = parseComponent(items[i], i, section, scene, taken);
    scene.components(section).push_back(std::move(spec));
  }
}

ComponentSpec SceneParser::parseComponent(const Field &f, std::size_t index, const std::string &section,
                                          const Scene &scene, std::map<std::string, std::string> &taken) const
{
  const std::vector<const PhysicsType *> types = physicsTypesOf(section);
  // Every key of every type of the section is known here, so that a key of
  // a sibling type gets "only allowed for ..." rather than "unknown key".
  std::vector<std::string> allowed{"name"}, typeNames;
  if (hasTypeKey(section)) allowed.insert(allowed.begin(), "type");
  for (const PhysicsType *t : types) {
    typeNames.push_back(t->schema.type);
    for (const KeySchema &k : t->schema.keys)
      if (std::find(allowed.begin(), allowed.end(), k.key) == allowed.end()) allowed.push_back(k.key);
  }
  const MapView m(report_, f, allowed);
  const PhysicsType *type = types.at(0);
  if (hasTypeKey(section))
    type = types[choice(m.require("type", " (one of " + join(typeNames) + ")"), typeNames)];
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
void SceneParser::readKeys(const MapView &m, const TypeSchema &schema, const std::vector<const PhysicsType *> &siblings,
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
    if ((rule.when == KeyRule::When::IfPresent && given) || (rule.when == KeyRule::When::IfAbsent && !given))
      m.forbid(rule.key, rule.reason);
  }
  for (const KeySchema &k : schema.keys) {
    const std::optional<Field> given = m.get(k.key);
    if (!given) {
      const bool needed = k.need == Need::Required || (k.need == Need::RequiredWith && m.has(k.other)) ||
                          (k.need == Need::RequiredWithout && !m.has(k.other));
      if (needed) m.require(k.key);
      if (k.hasDefault) spec.set(k.key, k.defaultNumber);
      continue;
    }
    readValue(*given, k, section, scene, prefix, spec, fields);
  }
}

void SceneParser::readValue(const Field &f, const KeySchema &k, const std::string &section, const Scene &scene,
                            const std::string &prefix, ComponentSpec &spec, std::map<std::string, Field> &fields) const
{
  fields.emplace(prefix + k.key, f);
  switch (k.kind) {
  case ValueKind::Number:
    spec.set(k.key, k.limit == Limit::Positive ? positive(f) : k.limit == Limit::NonNegative ? nonNegative(f) : number(f));
    return;
  case ValueKind::Integer:
    spec.set(k.key, static_cast<double>(integer(f, k.minInt, k.maxInt)));
    return;
  case ValueKind::Name:
    spec.set(k.key, name(f));
    return;
  case ValueKind::Vec2:
    spec.set(k.key, vec2(f));
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
  case ValueKind::Map: {
    std::vector<std::string> keys;
    for (const KeySchema &nested : k.nested->keys) keys.push_back(nested.key);
    const MapView m(report_, f, keys);
    ComponentSpec nested(k.nested->type, spec.name + "." + k.key);
    nested.mark = report_.sourceMark(f);
    readKeys(m, *k.nested, {}, section, scene, prefix + k.key + ".", nested, fields);
    spec.set(k.key, nested);
    return;
  }
  }
}

DynamicSpec SceneParser::parseDynamic(const Field &f) const
{
  const MapView m(report_, f, {"t_end", "dt", "dt_min", "rho_inf", "max_newton"});
  DynamicSpec d;
  d.t_end = positive(m.require("t_end"));
  const Field dt_field = m.require("dt");
  d.dt = positive(dt_field);
  if (d.dt > d.t_end)
    report_.fail(dt_field, "must be <= t_end (" + fmt(d.t_end) + "), got " + dt_field.node.Scalar());
  if (const auto dt_min = m.get("dt_min")) {
    d.dt_min = positive(*dt_min);
    if (d.dt_min > d.dt)
      report_.fail(*dt_min, "must be <= dt (" + fmt(d.dt) + "), got " + dt_min->node.Scalar());
  } else {
    d.dt_min = std::min(d.dt_min, d.dt); // the default must not exceed a small dt
  }
  if (const auto rho = m.get("rho_inf")) {
    d.rho_inf = number(*rho);
    if (d.rho_inf < 0 || d.rho_inf > 1)
      report_.fail(*rho, "must be in [0, 1] (got " + rho->node.Scalar() + ")");
  }
  if (const auto n = m.get("max_newton"))
    d.max_newton = integer(*n, 1, kMaxNewton);
  return d;
}

StaticSpec SceneParser::parseStatic(const Field &f) const
{
  const MapView m(report_, f, {"load_steps", "time"});
  StaticSpec s;
  if (const auto n = m.get("load_steps"))
    s.load_steps = integer(*n, 1, kMaxLoadSteps);
  if (const auto t = m.get("time"))
    s.time = nonNegative(*t);
  return s;
}

ModalSpec SceneParser::parseModal(const Field &f, bool required_nonzero) const
{
  const MapView m(report_, f, {"count", "at"});
  ModalSpec s;
  if (required_nonzero) {
    const Field count = m.require("count");
    s.count = integer(count, 0, kMaxModes);
    if (s.count < 1)
      report_.fail(count, "must be >= 1 for analysis modal (got " + count.node.Scalar() + ")");
  } else if (const auto count = m.get("count")) {
    s.count = integer(*count, 0, kMaxModes);
  }
  if (const auto at = m.get("at"))
    s.at = choice(*at, {"start", "end"}) == 0 ? "start" : "end";
  return s;
}

void SceneParser::parseOutput(const Field &f, Scene &scene) const
{
  const MapView m(report_, f, {"state_interval", "sensors", "frames"});
  OutputSpec &o = scene.output;
  if (const auto interval = m.get("state_interval"))
    o.state_interval = nonNegative(*interval);
  parseSection(m, "sensors", "output.sensors", scene);
  parseSection(m, "frames", "output.frames", scene);
}

// Counts the documents of a YAML stream, at most three, through yaml-cpp's
// event interface. yaml-cpp 0.7's LoadAll loops forever, allocating, on a
// document that starts with a stray ',' (yaml-cpp issue #1040): the parser
// reports the same empty document again and again without advancing. So
// the reader loads only the first document (YAML::Load, which stops after
// one), and this bounded pass finds further documents or a stuck parser.
class DocumentCounter : public YAML::EventHandler {
public:
  std::vector<YAML::Mark> starts;

  void OnDocumentStart(const YAML::Mark &mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark &, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark &, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark &, const std::string &, YAML::anchor_t, const std::string &) override {}
  void OnSequenceStart(const YAML::Mark &, const std::string &, YAML::anchor_t, YAML::EmitterStyle::value) override
  {
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark &, const std::string &, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

struct DocumentCount {
  std::size_t documents = 0;          // counted up to 3
  YAML::Mark second;                  // start of the second document, if any
  std::optional<YAML::Mark> stuck_at; // where the parser stopped advancing
};

DocumentCount countDocuments(const std::string &text)
{
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentCounter counter;
  while (counter.starts.size() < 3 && parser.HandleNextDocument(counter)) {
    const auto &starts = counter.starts;
    const std::size_t n = starts.size();
    if (n >= 2 && starts[n - 1].pos == starts[n - 2].pos)
      return {n, starts[1], starts[n - 1]};
  }
  const auto &starts = counter.starts;
  return {starts.size(), starts.size() >= 2 ? starts[1] : YAML::Mark{}, std::nullopt};
}

YAML::Mark markAtLineStart(const std::string &text, std::size_t offset)
{
  YAML::Mark mark;
  mark.pos = static_cast<int>(offset);
  mark.line = static_cast<int>(std::count(text.begin(), text.begin() + offset, '\n'));
  mark.column = 0;
  return mark;
}

[[noreturn]] void syntaxError(const std::string &file, const YAML::Mark &mark, const std::string &message)
{
  throw SceneError(file + ":" + std::to_string(std::max(mark.line, 0) + 1) + ":" +
                   std::to_string(std::max(mark.column, 0) + 1) + ": YAML syntax error: " + message);
}

// The parse proper; parseScene adds the catch-all around it.
Scene parseChecked(const std::string &text, const std::string &file_label)
{
  const Reporter report(file_label);
  // yaml-cpp silently stops at a NUL byte; say so instead of reading half a file.
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    report.fail(markAtLineStart(text, nul), "", "the file contains a NUL byte (is it a text file?)");

  YAML::Node root;
  DocumentCount count;
  try {
    count = countDocuments(text);
    if (count.stuck_at) {
      const std::size_t pos = static_cast<std::size_t>(std::max(count.stuck_at->pos, 0));
      const std::string found = pos < text.size() ? "'" + text.substr(pos, 1) + "'" : "end of file";
      syntaxError(file_label, *count.stuck_at, "unexpected " + found + " at the start of a document");
    }
    root = YAML::Load(text);
  } catch (const YAML::ParserException &e) {
    syntaxError(file_label, e.mark, e.msg);
  }
  const YAML::Mark start{}; // line 0, column 0 -> reported as 1:1
  if (root.IsNull() && count.documents <= 1)
    report.fail(start, "", "the scene file is empty; expected a map with at least name, analysis and bodies");
  if (count.documents > 1)
    report.fail(count.second, "", "a scene file holds one YAML document, but a second one starts here (remove the "
                                  "'---' separator)");
  if (!root.IsMap())
    report.fail(root.Mark(), "", "expected a map with at least name, analysis and bodies, got " + describeNode(root));

  Scene scene;
  scene.file = file_label;
  scene.text = text;
  SceneParser(report).parse(Field{root, "", root.Mark(), root.Mark()}, scene);
  return scene;
}

} // namespace

Scene parseScene(const std::string &text, const std::string &file_label)
{
  try {
    return parseChecked(text, file_label);
  } catch (const SceneError &) {
    throw;
  } catch (const YAML::Exception &e) {
    // Not expected (all access is checked), but a message beats a crash.
    throw SceneError(file_label + ":" + std::to_string(std::max(e.mark.line, 0) + 1) + ":" +
                     std::to_string(std::max(e.mark.column, 0) + 1) + ": YAML error: " + e.msg);
  } catch (const std::exception &e) {
    throw SceneError(file_label + ": internal error while reading the scene: " + e.what());
  }
}

Scene readSceneFile(const std::string &path)
{
  std::error_code ec;
  // An ifstream opens a directory without complaint; check the kind first.
  if (!std::filesystem::is_regular_file(path, ec))
    throw SceneError(path + ": cannot open scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw SceneError(path + ": cannot open scene file");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad())
    throw SceneError(path + ": cannot open scene file (read error)");
  return parseScene(content.str(), path);
}

} // namespace boomdyn
