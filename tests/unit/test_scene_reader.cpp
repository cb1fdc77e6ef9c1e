// Scene reader: a full scene parses into the right values (units
// converted), every class of bad input is rejected with a located message,
// every example in inputs/ parses, and every file in tests/bad_input/ is
// rejected with the message its first line announces.
#include "boomdyn/scene_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

using namespace boomdyn;
namespace fs = std::filesystem;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Runs parseScene and returns the SceneError message ("" if none).
std::string errorOf(const std::string &text, const std::string &label = "test.yaml")
{
  try {
    parseScene(text, label);
  } catch (const SceneError &e) {
    return e.what();
  }
  return "";
}

// A valid minimal scene to which single lines are added or changed.
const char *const kMinimal = R"(name: minimal
analysis: static
bodies:
  - name: boom
    length: 2
    elements: 4
    section: {EA: 1.0e9, EI: 1.0e6, rhoA: 30}
)";

// Expects text to be rejected with a message that starts with
// "test.yaml:<line>:", names the key path and contains the reason.
void expectRejected(const std::string &text, int line, const std::string &path, const std::string &reason)
{
  const std::string message = errorOf(text);
  ASSERT_FALSE(message.empty()) << "accepted:\n" << text;
  EXPECT_EQ(message.rfind("test.yaml:" + std::to_string(line) + ":", 0), 0u) << message;
  EXPECT_NE(message.find("key '" + path + "'"), std::string::npos) << message;
  EXPECT_NE(message.find(reason), std::string::npos) << message;
}

std::string readText(const fs::path &path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

std::vector<fs::path> yamlFilesIn(const fs::path &dir)
{
  std::vector<fs::path> files;
  for (const auto &entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".yaml")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

} // namespace

TEST(SceneReader, MinimalSceneGetsDefaults)
{
  const Scene s = parseScene(kMinimal, "min.yaml");
  EXPECT_EQ(s.file, "min.yaml");
  EXPECT_EQ(s.text, kMinimal);
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.analysis, Scene::Analysis::Static);
  EXPECT_EQ(s.gravity, (Vec2d{0, 0}));
  ASSERT_EQ(s.bodies.size(), 1u);
  const BodySpec &b = s.bodies[0];
  EXPECT_EQ(b.type, BodySpec::Type::AncfBeam);
  EXPECT_EQ(b.origin, (Vec2d{0, 0}));
  EXPECT_EQ(b.angle, 0.0);
  EXPECT_EQ(b.mark.file, "min.yaml");
  EXPECT_EQ(b.mark.line, 4);
  EXPECT_EQ(b.mark.key, "bodies[0]");
  EXPECT_EQ(s.statics.load_steps, 1);
  EXPECT_EQ(s.statics.time, 0.0);
  EXPECT_EQ(s.modal.count, 0);
  EXPECT_EQ(s.output.state_interval, 0.0);
  EXPECT_TRUE(s.constraints.empty());
  EXPECT_TRUE(s.forces.empty());
  EXPECT_TRUE(s.masses.empty());
  EXPECT_TRUE(s.output.sensors.empty());
}

TEST(SceneReader, FullSceneParsesWithUnitsConverted)
{
  const std::string text = R"(name: full
description: "every feature"
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - name: boom
    type: ancf_beam
    length: 2.0
    elements: 8
    origin: [1, 0.5]
    angle: 90
    section: {E: 2.0e11, A: 0.004, I: 2.0e-5, rho: 7850}
  - name: jib
    length: 1.0
    elements: 1e1
    origin: [1, 2.5]
    section:
      EA: 1.0e9
      EI: 1.0e6
      rhoA: 30.0
  - name: hook
    type: rigid
    length: 0.5
    origin: [2, 2.5]
    angle: -90
    section: {rhoA: 12}
constraints:
  - type: clamp
    body: boom
    at: start
    angle: {type: smooth_step, t0: 0, t1: 5.7, from: 90, to: 125}
  - type: pin
    name: knuckle
    body: jib
    at: 0
    other: boom
    other_at: end
  - type: pin
    body: hook
    at: start
    point: [2, 2.5]
  - type: angle_drive
    body: jib
    at: start
    angle: {type: sine, amplitude: 10, frequency: 0.5, phase: 90, offset: 5}
loads:
  - type: point_force
    name: wind
    body: jib
    at: end
    force: [100, 0]
    scale: {type: table, t: [0, 1, 2], values: [0, 1, 0.5]}
  - type: point_force
    body: boom
    at: 1.5
    force: [0, -10]
masses:
  - name: payload
    body: hook
    at: end
    mass: 250
  - body: jib
    at: 0.25
    mass: 5
dynamic:
  t_end: 2
  dt: 1.0e-3
  dt_min: 1.0e-7
  rho_inf: 0.6
  max_newton: 12
modal:
  count: 4
  at: start
output:
  state_interval: 0.05
  sensors:
    - name: tip
      body: jib
      at: end
    - body: boom
      at: 1
)";
  const Scene s = parseScene(text, "inputs/full.yaml");
  EXPECT_EQ(s.description, "every feature");
  EXPECT_EQ(s.analysis, Scene::Analysis::Dynamic);
  EXPECT_EQ(s.gravity, (Vec2d{0, -9.81}));

  ASSERT_EQ(s.bodies.size(), 3u);
  const BodySpec &boom = s.bodies[0];
  EXPECT_EQ(boom.name, "boom");
  EXPECT_EQ(boom.length, 2.0);
  EXPECT_EQ(boom.elements, 8);
  EXPECT_EQ(boom.origin, (Vec2d{1, 0.5}));
  EXPECT_NEAR(boom.angle, 90 * kDeg, 1e-15);
  EXPECT_DOUBLE_EQ(boom.section.EA, 2.0e11 * 0.004);
  EXPECT_DOUBLE_EQ(boom.section.EI, 2.0e11 * 2.0e-5);
  EXPECT_DOUBLE_EQ(boom.section.rhoA, 7850 * 0.004);
  EXPECT_EQ(boom.mark.line, 6);
  EXPECT_EQ(boom.mark.file, "inputs/full.yaml");
  const BodySpec &jib = s.bodies[1];
  EXPECT_EQ(jib.elements, 10);
  EXPECT_EQ(jib.section.EA, 1.0e9);
  EXPECT_EQ(jib.section.EI, 1.0e6);
  EXPECT_EQ(jib.section.rhoA, 30.0);
  const BodySpec &hook = s.bodies[2];
  EXPECT_EQ(hook.type, BodySpec::Type::Rigid);
  EXPECT_EQ(hook.elements, 1);
  EXPECT_NEAR(hook.angle, -90 * kDeg, 1e-15);
  EXPECT_EQ(hook.section.rhoA, 12.0);
  EXPECT_EQ(hook.section.EA, 0.0);

  ASSERT_EQ(s.constraints.size(), 4u);
  const ComponentSpec &clamp = s.constraints[0];
  EXPECT_EQ(clamp.type, "clamp");
  EXPECT_EQ(clamp.name, "clamp0"); // default "<type><index>"
  EXPECT_EQ(clamp.text("body"), "boom");
  EXPECT_EQ(clamp.number("at"), 0.0);
  EXPECT_FALSE(clamp.has("other"));
  EXPECT_EQ(clamp.vec2("point"), (Vec2d{1, 0.5})); // default: the body's start point
  EXPECT_EQ(clamp.function("angle").kind(), TimeFunction::Kind::SmoothStep);
  EXPECT_NEAR(clamp.function("angle").value(0.0), 90 * kDeg, 1e-15);
  EXPECT_NEAR(clamp.function("angle").value(5.7), 125 * kDeg, 1e-15);
  EXPECT_NEAR(clamp.function("angle").value(100.0), 125 * kDeg, 1e-15);
  EXPECT_EQ(clamp.mark.key, "constraints[0]");
  EXPECT_EQ(clamp.mark.line, 28);

  const ComponentSpec &knuckle = s.constraints[1];
  EXPECT_EQ(knuckle.type, "pin");
  EXPECT_EQ(knuckle.name, "knuckle");
  EXPECT_EQ(knuckle.text("body"), "jib");
  EXPECT_EQ(knuckle.number("at"), 0.0);
  ASSERT_TRUE(knuckle.has("other"));
  EXPECT_EQ(knuckle.text("other"), "boom");
  EXPECT_EQ(knuckle.number("other_at"), 2.0);

  const ComponentSpec &hang = s.constraints[2];
  EXPECT_EQ(hang.name, "pin2");
  EXPECT_EQ(hang.vec2("point"), (Vec2d{2, 2.5}));

  const ComponentSpec &drive = s.constraints[3];
  EXPECT_EQ(drive.type, "angle_drive");
  EXPECT_EQ(drive.name, "angle_drive3");
  EXPECT_EQ(drive.function("angle").kind(), TimeFunction::Kind::Sine);
  // 5 + 10 sin(90 deg) degrees at t = 0; amplitude and offset scaled to rad,
  // phase converted from degrees.
  EXPECT_NEAR(drive.function("angle").value(0.0), 15 * kDeg, 1e-14);
  EXPECT_NEAR(drive.function("angle").value(1.0), -5 * kDeg, 1e-14); // half a period later

  ASSERT_EQ(s.forces.size(), 2u);
  EXPECT_EQ(s.forces[0].name, "wind");
  EXPECT_EQ(s.forces[0].number("at"), 1.0);
  EXPECT_EQ(s.forces[0].vec2("force"), (Vec2d{100, 0}));
  EXPECT_EQ(s.forces[0].function("scale").kind(), TimeFunction::Kind::Table);
  EXPECT_DOUBLE_EQ(s.forces[0].function("scale").value(1.5), 0.75); // not converted: dimensionless
  EXPECT_EQ(s.forces[1].name, "force1");
  EXPECT_EQ(s.forces[1].number("at"), 1.5);
  EXPECT_EQ(s.forces[1].function("scale").value(3.0), 1.0);

  ASSERT_EQ(s.masses.size(), 2u);
  EXPECT_EQ(s.masses[0].name, "payload");
  EXPECT_EQ(s.masses[0].text("body"), "hook");
  EXPECT_EQ(s.masses[0].number("at"), 0.5);
  EXPECT_EQ(s.masses[0].number("mass"), 250.0);
  EXPECT_EQ(s.masses[1].name, "mass1");
  EXPECT_EQ(s.masses[1].number("at"), 0.25);

  EXPECT_EQ(s.dynamic.t_end, 2.0);
  EXPECT_EQ(s.dynamic.dt, 1e-3);
  EXPECT_EQ(s.dynamic.dt_min, 1e-7);
  EXPECT_EQ(s.dynamic.rho_inf, 0.6);
  EXPECT_EQ(s.dynamic.max_newton, 12);
  EXPECT_EQ(s.modal.count, 4);
  EXPECT_EQ(s.modal.at, "start");
  EXPECT_EQ(s.output.state_interval, 0.05);
  ASSERT_EQ(s.output.sensors.size(), 2u);
  EXPECT_EQ(s.output.sensors[0].name, "tip");
  EXPECT_EQ(s.output.sensors[0].number("at"), 1.0);
  EXPECT_EQ(s.output.sensors[1].name, "sensor1");
  EXPECT_EQ(s.output.sensors[1].text("body"), "boom");
}

TEST(SceneReader, ClampAngleDefaultsToBodyAngleAndGroundToMaterialPoint)
{
  const std::string text = R"(name: tilted
analysis: static
bodies:
  - name: boom
    length: 2
    elements: 2
    origin: [1, 1]
    angle: 30
    section: {EA: 1, EI: 1, rhoA: 1}
constraints:
  - type: clamp
    body: boom
    at: 1.0
)";
  const Scene s = parseScene(text, "t.yaml");
  const ComponentSpec &c = s.constraints.at(0);
  EXPECT_NEAR(c.vec2("point")[0], 1 + std::cos(30 * kDeg), 1e-15);
  EXPECT_NEAR(c.vec2("point")[1], 1 + std::sin(30 * kDeg), 1e-15);
  EXPECT_EQ(c.function("angle").kind(), TimeFunction::Kind::Constant);
  EXPECT_NEAR(c.function("angle").value(0), 30 * kDeg, 1e-15);
}

TEST(SceneReader, DistanceConstraintBetweenBodiesAndToGround)
{
  const std::string bodies = std::string(kMinimal) + R"(  - name: jib
    length: 1
    elements: 2
    origin: [2, 0]
    section: {EA: 1, EI: 1, rhoA: 1}
constraints:
)";
  const Scene s = parseScene(bodies + R"(  - {type: distance, name: stay, body: boom, at: 1, other: jib, other_at: end}
  - {type: distance, body: jib, at: 0.5, point: [2, 3], length: 3.2}
)",
                             "t.yaml");
  ASSERT_EQ(s.constraints.size(), 2u);
  const ComponentSpec &stay = s.constraints[0];
  EXPECT_EQ(stay.type, "distance");
  EXPECT_EQ(stay.name, "stay");
  EXPECT_EQ(stay.text("body"), "boom");
  EXPECT_EQ(stay.number("at"), 1.0);
  EXPECT_EQ(stay.text("other"), "jib");
  EXPECT_EQ(stay.number("other_at"), 1.0); // `end` of the 1 m jib
  EXPECT_FALSE(stay.has("length"));         // the builder takes the initial distance
  const ComponentSpec &ground = s.constraints[1];
  EXPECT_EQ(ground.name, "distance1");
  EXPECT_EQ(ground.vec2("point"), (Vec2d{2, 3}));
  EXPECT_EQ(ground.number("length"), 3.2);

  // The schema's rules, with the file:line: key messages of every type.
  expectRejected(bodies + "  - {type: distance, body: boom, at: 1, other: jib, other_at: 0, point: [0, 0]}\n", 14,
                 "constraints[0].point", "not allowed together with 'other' (the link joins two bodies)");
  expectRejected(bodies + "  - {type: distance, body: boom, at: 1}\n", 14, "constraints[0].point",
                 "missing required key");
  expectRejected(bodies + "  - {type: distance, body: boom, at: 1, point: [0, 0], other_at: 0}\n", 14,
                 "constraints[0].other_at", "only allowed together with 'other'");
  expectRejected(bodies + "  - {type: distance, body: boom, at: 1, point: [0, 0], length: 0}\n", 14,
                 "constraints[0].length", "must be > 0 (got 0)");
  expectRejected(bodies + "  - {type: distance, body: boom, at: 1, point: [0, 0], angle: 3}\n", 14,
                 "constraints[0].angle", "not allowed for a distance");
  expectRejected(bodies + "  - {type: distance, body: boom, at: 1, point: [0, 0], track: jib}\n", 14,
                 "constraints[0].track", "only allowed for a sliding_joint");
  expectRejected(bodies + "  - {type: pin, body: boom, at: 1, length: 2}\n", 14, "constraints[0].length",
                 "only allowed for a rope or an elastic_rope or a distance");
}

TEST(SceneReader, DynamicDefaultsAndDtMinFollowsSmallDt)
{
  const std::string base = R"(name: d
analysis: dynamic
bodies:
  - {name: b, length: 1, elements: 1, section: {EA: 1, EI: 1, rhoA: 1}}
)";
  const Scene s = parseScene(base + "dynamic: {t_end: 1, dt: 0.01}\n", "d.yaml");
  EXPECT_EQ(s.dynamic.dt_min, DynamicSpec{}.dt_min);
  EXPECT_EQ(s.dynamic.rho_inf, DynamicSpec{}.rho_inf);
  EXPECT_EQ(s.dynamic.max_newton, DynamicSpec{}.max_newton);
  const Scene tiny = parseScene(base + "dynamic: {t_end: 1.0e-9, dt: 1.0e-12}\n", "d.yaml");
  EXPECT_EQ(tiny.dynamic.dt_min, 1e-12);
}

TEST(SceneReader, ModalAnalysisAcceptsStaticSection)
{
  const std::string text = std::string(kMinimal) + "static: {load_steps: 3, time: 0.5}\nmodal: {count: 6}\n";
  std::string modal = text;
  modal.replace(modal.find("analysis: static"), 16, "analysis: modal");
  const Scene s = parseScene(modal, "m.yaml");
  EXPECT_EQ(s.analysis, Scene::Analysis::Modal);
  EXPECT_EQ(s.statics.load_steps, 3);
  EXPECT_EQ(s.statics.time, 0.5);
  EXPECT_EQ(s.modal.count, 6);
  EXPECT_EQ(s.modal.at, "end");
}

// --- one test per error class ---------------------------------------------

TEST(SceneReaderErrors, SyntaxError)
{
  const std::string message = errorOf("name: x\nbodies: [1, 2\n");
  EXPECT_EQ(message.rfind("test.yaml:", 0), 0u) << message;
  EXPECT_NE(message.find("YAML syntax error"), std::string::npos) << message;
  EXPECT_TRUE(std::regex_search(message, std::regex(":[0-9]+:[0-9]+: "))) << message;
}

TEST(SceneReaderErrors, UnknownKeyNamesAllowedKeysAndSuggestion)
{
  std::string text = kMinimal;
  text.replace(text.find("length"), 6, "lenght");
  expectRejected(text, 5, "bodies[0].lenght", "unknown key");
  const std::string message = errorOf(text);
  EXPECT_NE(message.find("did you mean 'length'"), std::string::npos) << message;
  EXPECT_NE(message.find("allowed keys here: name, type, length"), std::string::npos) << message;
}

TEST(SceneReaderErrors, WrongType)
{
  std::string text = kMinimal;
  text.replace(text.find("length: 2"), 9, "length: [2]");
  expectRejected(text, 5, "bodies[0].length", "expected a number, got a list");
}

TEST(SceneReaderErrors, QuotedNumberIsAString)
{
  std::string text = kMinimal;
  text.replace(text.find("length: 2"), 9, "length: \"2\"");
  expectRejected(text, 5, "bodies[0].length", "quoted string");
}

TEST(SceneReaderErrors, MissingKeyPointsAtParent)
{
  std::string text = kMinimal;
  text.replace(text.find("    elements: 4\n"), 16, "");
  expectRejected(text, 4, "bodies[0].elements", "missing required key");
}

TEST(SceneReaderErrors, NonPhysicalValue)
{
  std::string text = kMinimal;
  text.replace(text.find("length: 2"), 9, "length: -2");
  expectRejected(text, 5, "bodies[0].length", "must be > 0 (got -2)");
  // The exact form given in the format description.
  EXPECT_EQ(errorOf(text), "test.yaml:5:13: key 'bodies[0].length': must be > 0 (got -2)");
}

TEST(SceneReaderErrors, UnknownBodyReference)
{
  const std::string text = std::string(kMinimal) + "constraints:\n  - {type: clamp, body: bom, at: start}\n";
  expectRejected(text, 9, "constraints[0].body", "unknown body 'bom' (bodies: boom)");
}

TEST(SceneReaderErrors, AtOutsideBody)
{
  const std::string text = std::string(kMinimal) + "masses:\n  - body: boom\n    at: 2.5\n    mass: 1\n";
  expectRejected(text, 10, "masses[0].at", "number in [0, 2]");
}

TEST(SceneReaderErrors, DuplicateName)
{
  const std::string text = std::string(kMinimal) +
                           "  - name: boom\n    length: 1\n    elements: 1\n    section: {EA: 1, EI: 1, rhoA: 1}\n";
  expectRejected(text, 8, "bodies[1].name", "duplicate body name 'boom' (also used by bodies[0])");
}

TEST(SceneReaderErrors, DuplicateKey)
{
  std::string text = kMinimal;
  text.replace(text.find("    elements: 4\n"), 16, "    elements: 4\n    length: 3\n");
  expectRejected(text, 7, "bodies[0].length", "duplicate key (first given on line 5)");
}

TEST(SceneReaderErrors, NotFiniteNumbers)
{
  for (const std::string bad : {".nan", ".NaN", ".inf", "-.inf", "nan", "inf", "-Infinity"}) {
    std::string text = kMinimal;
    text.replace(text.find("length: 2"), 9, "length: " + bad);
    expectRejected(text, 5, "bodies[0].length", "must be a finite number");
  }
  std::string text = kMinimal;
  text.replace(text.find("length: 2"), 9, "length: 1e999");
  expectRejected(text, 5, "bodies[0].length", "out of range");
}

// The section's forms, its products and a rigid body's section, as the body
// types' schemas (src/bodies/) declare them.
TEST(SceneReaderErrors, BodySectionFormsAndProducts)
{
  const auto withSection = [](const std::string &type, const std::string &section) {
    std::string text = kMinimal;
    text.replace(text.find("    section: {EA: 1.0e9, EI: 1.0e6, rhoA: 30}"), 45, "    section: " + section);
    if (type == "rigid") text.replace(text.find("    elements: 4\n"), 16, "    type: rigid\n");
    return text;
  };
  // Factors whose products would leave a double's range are refused as
  // numbers already (every magnitude within 1e-100 to 1e100, issue 17).
  expectRejected(withSection("ancf_beam", "{E: 1.0e300, A: 1.0e10, I: 1, rho: 1}"), 7, "bodies[0].section.E",
                 "the magnitude of 1.0e300 is outside the range boomdyn computes with");
  expectRejected(withSection("ancf_beam", "{E: 1, A: 1.0e-200, I: 1, rho: 1.0e-200}"), 7, "bodies[0].section.A",
                 "the magnitude of 1.0e-200 is outside the range boomdyn computes with");
  expectRejected(withSection("rigid", "{rhoA: 30, A: 1}"), 7, "bodies[0].section",
                 "give either rhoA, or rho and A (not a mix of the two forms)");
  expectRejected(withSection("rigid", "{}"), 7, "bodies[0].section", "needs rhoA, or rho and A");
  expectRejected(withSection("rigid", "{A: 1}"), 7, "bodies[0].section.rho", "missing required key");
  expectRejected(withSection("rigid", "{rhoA: 30, I: 1}"), 7, "bodies[0].section.I", "a rigid body has no stiffness");
  expectRejected(withSection("rigid", "{rhoA: 30, G: 1}"), 7, "bodies[0].section.G", "unknown key");

  const Scene rigid = parseScene(withSection("rigid", "{rho: 7850, A: 0.004}") + "    angle: 90\n", "test.yaml");
  EXPECT_EQ(rigid.bodies.at(0).type, BodySpec::Type::Rigid);
  EXPECT_EQ(rigid.bodies.at(0).section.rhoA, 7850 * 0.004);
  EXPECT_EQ(rigid.bodies.at(0).section.EA, 0.0);
  EXPECT_DOUBLE_EQ(rigid.bodies.at(0).angle, std::acos(0.0)); // degrees in the file, radians in the spec
}

TEST(SceneReaderErrors, EmptyAndNonMapDocuments)
{
  for (const std::string text : {"", "   \n", "# only a comment\n", "~\n"})
    EXPECT_NE(errorOf(text).find("test.yaml:1:1: key '(top level)': the scene file is empty"), std::string::npos)
        << errorOf(text);
  EXPECT_NE(errorOf("- a\n- b\n").find("got a list"), std::string::npos);
  EXPECT_NE(errorOf("just text\n").find("got 'just text'"), std::string::npos);
  EXPECT_NE(errorOf(std::string(kMinimal) + "---\nname: second\n").find("one YAML document"), std::string::npos);
  // yaml-cpp 0.7's LoadAll loops forever on these (yaml-cpp issue #1040).
  EXPECT_NE(errorOf(",\n").find("test.yaml:1:1: YAML syntax error: unexpected ','"), std::string::npos);
  EXPECT_NE(errorOf("# c\n---\n, x\n").find("test.yaml:3:1: YAML syntax error"), std::string::npos);
}

TEST(SceneReaderErrors, MissingFile)
{
  try {
    readSceneFile("/nonexistent/dir/scene.yaml");
    FAIL() << "no exception";
  } catch (const SceneError &e) {
    EXPECT_STREQ(e.what(), "/nonexistent/dir/scene.yaml: cannot open scene file");
  }
  EXPECT_THROW(readSceneFile(BOOMDYN_SOURCE_DIR "/inputs"), SceneError); // a directory
}

TEST(SceneReaderErrors, NeverCrashesOnMangledInput)
{
  // Every prefix and a few byte-level corruptions of a full scene must
  // either parse or raise SceneError, never anything else.
  const std::string text = readText(fs::path(BOOMDYN_SOURCE_DIR) / "inputs" / "elevation_drive.yaml");
  ASSERT_FALSE(text.empty());
  int rejected = 0;
  for (std::size_t n = 0; n <= text.size(); n += 7) {
    EXPECT_NO_THROW({
      try {
        parseScene(text.substr(0, n), "prefix.yaml");
      } catch (const SceneError &) {
        ++rejected;
      }
    }) << "prefix of "
       << n << " bytes";
  }
  EXPECT_GT(rejected, 0);
  for (std::size_t pos = 0; pos < text.size(); pos += 13) {
    for (char c : {'\t', '[', '{', ',', ':', '-', '\0', '\xff', '"', '&', '*'}) {
      std::string mangled = text;
      mangled[pos] = c;
      EXPECT_NO_THROW({
        try {
          parseScene(mangled, "mangled.yaml");
        } catch (const SceneError &) {
        }
      }) << "byte "
         << pos << " set to " << int(c);
    }
  }
}

// --- files -------------------------------------------------------------------

TEST(SceneReaderFiles, EveryExampleInputParses)
{
  const auto files = yamlFilesIn(fs::path(BOOMDYN_SOURCE_DIR) / "inputs");
  EXPECT_GE(files.size(), 7u);
  for (const auto &file : files) {
    try {
      const Scene s = readSceneFile(file.string());
      EXPECT_EQ(s.file, file.string());
      EXPECT_FALSE(s.text.empty());
    } catch (const SceneError &e) {
      ADD_FAILURE() << e.what();
    }
  }
}

TEST(SceneReaderFiles, ExampleValuesMatchTheirComments)
{
  const fs::path dir = fs::path(BOOMDYN_SOURCE_DIR) / "inputs";
  const Scene s = readSceneFile((dir / "cantilever_static.yaml").string());
  const SectionSpec &section = s.bodies.at(0).section;
  EXPECT_NEAR(section.EA, 8.5176e8, 1e3);
  EXPECT_NEAR(section.EI, 4.9531e6, 1e2);
  EXPECT_NEAR(section.rhoA, 31.84, 1e-2);
  EXPECT_EQ(s.statics.load_steps, 10);
  EXPECT_EQ(s.bodies.at(0).elements, 16);

  const Scene drive = readSceneFile((dir / "elevation_drive.yaml").string());
  const TimeFunction &angle = drive.constraints.at(0).function("angle");
  EXPECT_EQ(angle.kind(), TimeFunction::Kind::SmoothStep);
  EXPECT_NEAR(angle.value(5.7), 35 * kDeg, 1e-14);
  EXPECT_EQ(angle.rate(0.0), 0.0);

  const Scene pinned = readSceneFile((dir / "two_beams_pinned.yaml").string());
  ASSERT_TRUE(pinned.constraints.at(1).has("other"));
}

// Each bad file starts with "# expect: <substring>"; an optional second line
// "# line: <n>" pins the reported line. The message must contain the file
// name, ":<line>:" and the expected substring.
TEST(SceneReaderFiles, EveryBadInputIsRejectedAsAnnounced)
{
  const auto files = yamlFilesIn(fs::path(BOOMDYN_SOURCE_DIR) / "tests" / "bad_input");
  EXPECT_GE(files.size(), 60u);
  const std::regex expect_re("^# expect: (.*)$");
  const std::regex line_re("^# line: ([0-9]+)$");
  for (const auto &file : files) {
    SCOPED_TRACE(file.filename().string());
    std::ifstream in(file);
    std::string first, second;
    std::getline(in, first);
    std::getline(in, second);
    std::smatch match;
    ASSERT_TRUE(std::regex_match(first, match, expect_re)) << "first line must be '# expect: ...'";
    const std::string expected = match[1];
    std::string message;
    try {
      readSceneFile(file.string());
    } catch (const SceneError &e) {
      message = e.what();
    }
    ASSERT_FALSE(message.empty()) << "was accepted";
    EXPECT_NE(message.find(file.filename().string()), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    if (std::regex_match(second, match, line_re))
      EXPECT_NE(message.find(":" + std::string(match[1]) + ":"), std::string::npos) << message;
    else
      EXPECT_TRUE(std::regex_search(message, std::regex(":[0-9]+:"))) << message;
  }
}
