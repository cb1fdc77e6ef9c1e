#include "checked_yaml.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <system_error>

namespace boomdyn::scene_io {

std::string join(const std::vector<std::string> &items)
{
  std::string out;
  for (const auto &item : items)
    out += (out.empty() ? "" : ", ") + item;
  return out;
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

// Every nonzero number of a scene lies between these magnitudes (SI units:
// nothing physical comes near them, and products of a few such numbers stay
// far from a double's limits, about 1e-308 and 1e308).
constexpr double kSmallestMagnitude = 1e-100, kLargestMagnitude = 1e100;

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

std::string childPath(const std::string &parent, const std::string &key)
{
  return parent.empty() ? key : parent + "." + key;
}

MapView::MapView(const Reporter &report, const Field &field, const std::vector<std::string> &allowed)
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
std::string MapView::unknownKeyReason(const std::string &name, const std::vector<std::string> &allowed)
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
// --- scalars ---------------------------------------------------------
const std::string &CheckedYaml::scalarText(const Field &f, const std::string &expected) const
{
  if (!f.node.IsScalar())
    report_.fail(f, "expected " + expected + ", got " + describeNode(f.node));
  return f.node.Scalar();
}

double CheckedYaml::number(const Field &f) const
{
  const std::string &text = scalarText(f, "a number");
  // A quoted "2.0" is a string in YAML; accepting it would hide typos
  // such as a misplaced quote swallowing the rest of the line.
  if (f.node.Tag() == "!")
    report_.fail(f, "expected a number, got " + describeNode(f.node));
  double value = 0;
  switch (parseNumber(text, value)) {
  case NumberText::Ok:
    // Magnitudes far outside any physical input (a length of 1e-310, a
    // density of 1e-300, a gravity of 1e300, a sine of 1e308 Hz) overflow or
    // underflow in the products of the model and were reported as a
    // singular system: name the value here instead.
    if (value != 0 && !(std::fabs(value) >= kSmallestMagnitude && std::fabs(value) <= kLargestMagnitude))
      report_.fail(f, "the magnitude of " + text + " is outside the range boomdyn computes with (0, or " +
                          numberText(kSmallestMagnitude) + " to " + numberText(kLargestMagnitude) +
                          "): products of it would overflow or underflow");
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

double CheckedYaml::positive(const Field &f) const
{
  const double x = number(f);
  if (!(x > 0))
    report_.fail(f, "must be > 0 (got " + f.node.Scalar() + ")");
  return x;
}

double CheckedYaml::nonNegative(const Field &f) const
{
  const double x = number(f);
  if (!(x >= 0))
    report_.fail(f, "must be >= 0 (got " + f.node.Scalar() + ")");
  return x;
}

// Integers may be written as 8, 8.0 or 1e6, but must be whole numbers.
int CheckedYaml::integer(const Field &f, int lo, int hi, const std::string &too_large) const
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

std::string CheckedYaml::text(const Field &f) const
{
  const std::string &s = scalarText(f, "a text");
  if (s.empty())
    report_.fail(f, "must not be empty");
  return s;
}

// Names end up in output files and plot legends; keep them to a
// character set that is safe in file names, HDF5 paths and CSV headers.
std::string CheckedYaml::name(const Field &f) const
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
std::size_t CheckedYaml::choice(const Field &f, const std::vector<std::string> &options) const
{
  const std::string expected = "one of " + join(options);
  const std::string &s = scalarText(f, expected);
  const auto it = std::find(options.begin(), options.end(), s);
  if (it == options.end())
    report_.fail(f, "must be " + expected + " (got '" + s + "')");
  return static_cast<std::size_t>(it - options.begin());
}

std::vector<Field> CheckedYaml::list(const Field &f) const
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

std::vector<double> CheckedYaml::numbers(const Field &f) const
{
  if (!f.node.IsSequence())
    report_.fail(f, "expected a list of numbers, got " + describeNode(f.node));
  std::vector<double> values;
  for (const Field &item : list(f))
    values.push_back(number(item));
  return values;
}

Vec2d CheckedYaml::vec2(const Field &f) const
{
  if (!f.node.IsSequence() || f.node.size() != 2)
    report_.fail(f, "expected a list of two numbers [x, y], got " +
                        (f.node.IsSequence() ? "a list of " + std::to_string(f.node.size())
                                             : describeNode(f.node)));
  const auto items = list(f);
  return {number(items[0]), number(items[1])};
}

Vec3d CheckedYaml::vec3(const Field &f) const
{
  if (!f.node.IsSequence() || f.node.size() != 3)
    report_.fail(f, "expected a list of three numbers [x, y, z] (the scene is spatial: dimension 3), got " +
                        (f.node.IsSequence() ? "a list of " + std::to_string(f.node.size())
                                             : describeNode(f.node)));
  const auto items = list(f);
  return {number(items[0]), number(items[1]), number(items[2])};
}

// --- time functions --------------------------------------------------
// A plain number is a constant; otherwise a map with a 'type'.
TimeFunction CheckedYaml::timeFunction(const Field &f) const
{
  if (f.node.IsScalar())
    return TimeFunction::constant(number(f));
  if (!f.node.IsMap())
    report_.fail(f, "expected a number or a time function map {type: ...}, got " + describeNode(f.node));
  const MapView m(report_, f,
                  {"type", "value", "t0", "t1", "from", "to", "t", "values", "amplitude", "frequency", "phase",
                   "offset", "speed", "accel", "jerk"});
  const std::vector<std::string> types{"constant", "ramp", "smooth_step", "table", "sine", "accel_limited"};
  const std::size_t type = choice(m.require("type", " (one of " + join(types) + ")"), types);
  // Each kind accepts only its own parameters.
  const std::vector<std::vector<std::string>> keys_of_type{
      {"value"},
      {"t0", "t1", "from", "to"},
      {"t0", "t1", "from", "to"},
      {"t", "values"},
      {"amplitude", "frequency", "phase", "offset", "t0"},
      {"t0", "from", "to", "speed", "accel", "jerk"}};
  for (const char *key : {"value", "t0", "t1", "from", "to", "t", "values", "amplitude", "frequency",
                           "phase", "offset", "speed", "accel", "jerk"}) {
    const auto &own = keys_of_type[type];
    if (std::find(own.begin(), own.end(), key) == own.end())
      m.forbid(key, std::string("not a parameter of ") + (types[type][0] == 'a' ? "an " : "a ") + types[type] +
                        " function (it takes " + join(own) + ")");
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
      report_.fail(t1_field, "must be > t0 (got t0 = " + numberText(t0) + ", t1 = " + numberText(t1) + ")");
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
                                   numberText(t[k]) + " after " + numberText(t[k - 1]) + ")");
    return TimeFunction::table(t, v);
  }
  case 5: {
    // A move from `from` to `to` starting at t0 (TimeFunction::accelLimited).
    const double t0 = m.has("t0") ? number(*m.get("t0")) : 0.0;
    const double from = m.has("from") ? number(*m.get("from")) : 0.0;
    const double to = number(m.require("to", " (where the move ends)"));
    const double speed = positive(m.require("speed", " (the largest rate, units of the value per second)"));
    const double accel = positive(m.require("accel", " (the largest acceleration, units of the value per s^2)"));
    const double jerk = m.has("jerk") ? positive(*m.get("jerk")) : 0.0;
    return TimeFunction::accelLimited(t0, from, to, speed, accel, jerk);
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
const BodySpec &CheckedYaml::body(const Field &f, const Scene &scene) const
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
double CheckedYaml::materialCoordinate(const Field &f, const BodySpec &b) const
{
  const std::string expected = "start, end or a number in [0, " + numberText(b.length) + "] (the length of body '" +
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

PointRef CheckedYaml::point(const MapView &m, const Scene &scene, const std::string &body_key,
               const std::string &at_key) const
{
  const BodySpec &b = body(m.require(body_key), scene);
  return PointRef{b.name, materialCoordinate(m.require(at_key), b)};
}

const BodySpec &CheckedYaml::bodyNamed(const Scene &scene, const std::string &name)
{
  return *std::find_if(scene.bodies.begin(), scene.bodies.end(),
                       [&](const BodySpec &b) { return b.name == name; });
}

// Names are unique within each list; `what` is e.g. "body".
void CheckedYaml::claimName(std::map<std::string, std::string> &taken, const std::string &name, const Field &where,
               const std::string &what, const std::string &item_path) const
{
  const auto [it, inserted] = taken.emplace(name, item_path);
  if (!inserted)
    report_.fail(where, "duplicate " + what + " name '" + name + "' (also used by " + it->second + ")");
}

// Name from an optional 'name' key, or "<prefix><index>".
std::string CheckedYaml::itemName(const MapView &m, std::map<std::string, std::string> &taken, const std::string &what,
                     const std::string &default_name) const
{
  const std::optional<Field> given = m.get("name");
  const std::string result = given ? name(*given) : default_name;
  claimName(taken, result, given ? *given : m.self(), what, m.self().path);
  return result;
}

} // namespace boomdyn::scene_io
