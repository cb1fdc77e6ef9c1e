// Scene file reader: YAML text -> validated Scene (format: docs/scenes.md).
//
// Design: yaml-cpp only builds the node tree. Every value is then pulled out
// through the checked accessors of checked_yaml.hpp, which know the value's
// key path and source position, so any rejection can say
// "<file>:<line>:<column>: key '<path>': <reason>". The reader stops at the
// first error: later errors are often consequences of the first one. This
// file reads the document, the top level and analysis settings; bodies and
// the components of physics types are read by component_reader.cpp.
#include "boomdyn/scene_reader.hpp"

#include "checked_yaml.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <system_error>

namespace boomdyn {

namespace {

using namespace scene_io;

// Converts the scene document into a Scene, one section at a time.
class SceneParser : CheckedYaml {
public:
  explicit SceneParser(const Reporter &report) : CheckedYaml(report) {}

  void parse(const Field &root, Scene &scene);

private:
  // --- sections ----------------------------------------------------------
  // Components of registered physics types: component_reader.cpp.
  void parseSection(const MapView &parent, const std::string &key, const std::string &section, Scene &scene) const
  {
    readComponents(report_, parent, key, section, scene);
  }
  DynamicSpec parseDynamic(const Field &f) const;
  StaticSpec parseStatic(const Field &f) const;
  ModalSpec parseModal(const Field &f, bool required_nonzero) const;
  void parseOutput(const Field &f, Scene &scene) const;
  void parseFollow(const Field &f, TrackingSpec &tracking) const;
  void refuseTrackingWithFreeFriction(const Field &tracking, const Scene &scene) const;
};

// tracking.follow: a number of lowest modes, or a list of frequencies (Hz)
// near which the followed modes are at the first analysis.
void SceneParser::parseFollow(const Field &f, TrackingSpec &tracking) const
{
  const std::string count = " (tracking.count is " + std::to_string(tracking.count) + ")";
  if (f.node.IsSequence()) {
    for (const Field &item : list(f)) tracking.followHz.push_back(positive(item));
    if (tracking.followHz.empty()) report_.fail(f, "needs at least one frequency (Hz)");
    for (std::size_t i = 0; i < tracking.followHz.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (tracking.followHz[i] == tracking.followHz[j])
          report_.fail(f, "lists the frequency " + numberText(tracking.followHz[i]) + " Hz twice");
    tracking.follow = static_cast<int>(tracking.followHz.size());
    if (tracking.follow > tracking.count)
      report_.fail(f, "follows " + std::to_string(tracking.follow) + " modes but each analysis finds only count" +
                          " of them" + count + ": raise tracking.count");
  } else {
    tracking.follow = integer(f, 1, 100);
    if (tracking.follow > tracking.count)
      report_.fail(f, "follows the lowest " + std::to_string(tracking.follow) + " modes but each analysis finds only " +
                          "count of them" + count + ": raise tracking.count");
  }
}

// Frequency tracking linearizes with the LuGre bristle state z frozen
// (docs/model.md §5): the friction force is then a constant load, and a
// joint whose slide no extraction_drive prescribes has no tangential
// stiffness at all, stick or slip. Every analysis would stop with "the system
// is a mechanism" (issue 40). In stick the right linearization is a spring
// sigma0 |lambda_n| between track and slider (z follows the relative
// displacement), in slip none (a zero-frequency sliding mode); the pencil
// would have to know which, from the velocities it does not see. Refused
// here, naming the keys, instead of failing at the first analysis.
void SceneParser::refuseTrackingWithFreeFriction(const Field &tracking, const Scene &scene) const
{
  std::set<std::string> driven;
  for (const ComponentSpec &c : scene.constraints)
    if (c.type == "extraction_drive" && c.has("joint")) driven.insert(c.text("joint"));
  for (const ComponentSpec &c : scene.constraints)
    if (c.type == "sliding_joint" && c.has("friction") && !driven.count(c.name))
      report_.fail(tracking, "frequency tracking with LuGre friction at a freely sliding joint is not supported: "
                             "constraint '" + c.name + "' has 'friction' and no extraction_drive prescribes its "
                             "slide. The eigen-analysis freezes the bristle state z, so the joint has no tangential "
                             "stiffness (stick: the bristle spring sigma0 times the normal force is missing; slip: "
                             "a zero-frequency sliding mode) and every analysis would stop as a mechanism. Remove "
                             "'tracking' or the joint's 'friction' (docs/model.md §5)");
}

void SceneParser::parse(const Field &root, Scene &scene)
{
  const MapView top(report_, root,
                    {"name", "description", "dimension", "analysis", "gravity", "bodies", "constraints", "loads",
                     "masses", "springs", "dynamic", "static", "modal", "tracking", "output"});
  scene.name = name(top.require("name"));
  if (const auto d = top.get("description"))
    scene.description = d->node.IsNull() ? "" : scalarText(*d, "a text");

  const std::vector<std::string> analyses{"static", "dynamic", "modal"};
  const Scene::Analysis analysis_of[] = {Scene::Analysis::Static, Scene::Analysis::Dynamic,
                                         Scene::Analysis::Modal};
  const std::size_t analysis = choice(top.require("analysis", " (one of " + join(analyses) + ")"), analyses);
  scene.analysis = analysis_of[analysis];

  // The dimension first: it decides the length of every vector and which
  // types the sections take.
  if (const auto d = top.get("dimension")) {
    if (!d->node.IsScalar() || (d->node.Scalar() != "2" && d->node.Scalar() != "3"))
      report_.fail(*d, "must be 2 (a planar scene, the default) or 3 (a spatial scene), got " +
                           (d->node.IsScalar() ? d->node.Scalar() : describeNode(d->node)));
    scene.dimension = d->node.Scalar() == "3" ? 3 : 2;
  }
  if (const auto g = top.get("gravity")) {
    if (scene.dimension == 3) {
      scene.gravity3 = vec3(*g);
      scene.gravity = {scene.gravity3[0], scene.gravity3[1]};
    } else {
      if (g->node.IsSequence() && g->node.size() == 3)
        report_.fail(*g, "expected a list of two numbers [x, y], got a list of 3 (a spatial scene needs the "
                         "top-level key 'dimension: 3')");
      scene.gravity = vec2(*g);
      scene.gravity3 = {scene.gravity[0], scene.gravity[1], 0.0};
    }
  }

  // Bodies first: everything else refers to them.
  const Field bodies_field = top.require("bodies");
  const std::vector<Field> bodies = list(bodies_field);
  if (bodies.empty())
    report_.fail(bodies_field, "needs at least one body");
  readBodies(report_, bodies, scene); // by the body types' schemas: component_reader.cpp

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
    const MapView m(report_, *tr, {"interval", "count", "shapes_at", "follow"});
    scene.tracking.interval = positive(m.require("interval"));
    if (const auto c = m.get("count")) scene.tracking.count = integer(*c, 1, 100);
    if (const auto sa = m.get("shapes_at"))
      for (const Field &item : list(*sa)) scene.tracking.shapesAt.push_back(nonNegative(item));
    if (const auto fo = m.get("follow")) parseFollow(*fo, scene.tracking);
    refuseTrackingWithFreeFriction(*tr, scene);
  }
  if (const auto o = top.get("output"))
    parseOutput(*o, scene);
}

DynamicSpec SceneParser::parseDynamic(const Field &f) const
{
  const MapView m(report_, f, {"t_end", "dt", "dt_min", "rho_inf", "max_newton", "initial"});
  DynamicSpec d;
  d.t_end = positive(m.require("t_end"));
  const Field dt_field = m.require("dt");
  d.dt = positive(dt_field);
  if (d.dt > d.t_end)
    report_.fail(dt_field, "must be <= t_end (" + numberText(d.t_end) + "), got " + dt_field.node.Scalar());
  if (const auto dt_min = m.get("dt_min")) {
    d.dt_min = positive(*dt_min);
    if (d.dt_min > d.dt)
      report_.fail(*dt_min, "must be <= dt (" + numberText(d.dt) + "), got " + dt_min->node.Scalar());
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
  if (const auto initial = m.get("initial"))
    d.startStatic = choice(*initial, {"undeformed", "static"}) == 1;
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

// The offset of the first byte that is not part of a valid UTF-8 sequence
// (overlong forms and surrogates included), or npos.
std::size_t firstInvalidUtf8(const std::string &text)
{
  const auto *p = reinterpret_cast<const unsigned char *>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = p[i];
    std::size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (len == 0 || i + len > n || (len == 2 && c < 0xC2)) return i;
    for (std::size_t k = 1; k < len; ++k)
      if ((p[i + k] & 0xC0) != 0x80) return i;
    if (len == 3) {
      const unsigned cp = ((c & 0x0Fu) << 12) | ((p[i + 1] & 0x3Fu) << 6) | (p[i + 2] & 0x3Fu);
      if (cp < 0x800 || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
    }
    if (len == 4) {
      const unsigned cp = ((c & 0x07u) << 18) | ((p[i + 1] & 0x3Fu) << 12) | ((p[i + 2] & 0x3Fu) << 6) | (p[i + 3] & 0x3Fu);
      if (cp < 0x10000 || cp > 0x10FFFF) return i;
    }
    i += len;
  }
  return std::string::npos;
}

std::string hexByte(char c)
{
  static const char digits[] = "0123456789ABCDEF";
  const auto b = static_cast<unsigned char>(c);
  return std::string{digits[b >> 4], digits[b & 0xF]};
}

// The parse proper; parseScene adds the catch-all around it.
Scene parseChecked(const std::string &text, const std::string &file_label)
{
  const Reporter report(file_label);
  // yaml-cpp silently stops at a NUL byte; say so instead of reading half a file.
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    report.fail(markAtLineStart(text, nul), "", "the file contains a NUL byte (is it a text file?)");
  // The scene text is stored in the results as UTF-8 and read back by the
  // Python tools: a file in another encoding (Latin-1 'é' in a comment) is
  // refused where its first invalid byte is.
  if (const auto bad = firstInvalidUtf8(text); bad != std::string::npos)
    report.fail(markAtLineStart(text, bad), "",
                "the file is not valid UTF-8 (byte 0x" + hexByte(text[bad]) + "); save it as UTF-8");

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
