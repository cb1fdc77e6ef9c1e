// The registry of physics types: every registered type is complete enough
// for the reader and the docs (names, help, references between keys), and
// the reader dispatches on it.
#include "boomdyn/physics_type.hpp"
#include "boomdyn/scene_reader.hpp"
#include "boomdyn/schema_markdown.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <tuple>

using namespace boomdyn;

namespace {

void checkSchema(const TypeSchema &s, const std::string &where)
{
  EXPECT_FALSE(s.summary.empty()) << where;
  std::set<std::string> keys;
  for (const KeySchema &k : s.keys) {
    EXPECT_TRUE(keys.insert(k.key).second) << where << ": key '" << k.key << "' twice";
    EXPECT_FALSE(k.help.empty()) << where << ": key '" << k.key << "' has no help text";
    EXPECT_NE(k.key, "type") << where;
    EXPECT_NE(k.key, "name") << where;
    // Keys that refer to other keys name keys listed before them.
    for (const std::string *ref : {&k.bodyKey, &k.differentFrom, &k.other})
      if (!ref->empty()) EXPECT_TRUE(keys.count(*ref) || s.find(*ref)) << where << ": '" << k.key << "' refers to '" << *ref << "'";
    if (k.kind == ValueKind::MaterialCoordinate) {
      ASSERT_TRUE(keys.count(k.bodyKey)) << where << ": '" << k.key << "' needs its body key before it";
      EXPECT_EQ(s.find(k.bodyKey)->kind, ValueKind::Body) << where;
    }
    if (k.kind == ValueKind::Map || k.kind == ValueKind::MapList) {
      ASSERT_NE(k.nested, nullptr) << where << ": map '" << k.key << "' without a schema";
      checkSchema(*k.nested, where + "." + k.key);
    }
    if (k.kind == ValueKind::Component) EXPECT_FALSE(k.refType.empty()) << where;
    if (k.hasDefault) EXPECT_EQ(k.need, Need::Optional) << where << ": '" << k.key << "' has a default but is required";
    if (k.need == Need::InForm) {
      bool listed = false;
      for (const auto &form : s.forms) listed = listed || std::count(form.begin(), form.end(), k.key) > 0;
      EXPECT_TRUE(listed) << where << ": '" << k.key << "' is needed in its form but no form lists it";
    }
  }
  for (const auto &form : s.forms)
    for (const std::string &key : form) EXPECT_TRUE(s.find(key)) << where << ": form lists unknown key '" << key << "'";
  EXPECT_EQ(s.forms.empty(), s.formsText.empty()) << where << ": forms need their text for messages";
  for (const KeyRule &r : s.rules) {
    EXPECT_FALSE(r.reason.empty()) << where;
    if (r.when != KeyRule::When::Always) EXPECT_TRUE(s.find(r.condition)) << where << ": rule on '" << r.condition << "'";
  }
}

} // namespace

TEST(PhysicsTypes, EverySchemaIsCompleteAndTypesAreUniquePerSection)
{
  std::set<std::tuple<std::string, std::string, int>> seen;
  ASSERT_FALSE(physicsTypes().empty());
  for (const PhysicsType &t : physicsTypes()) {
    const std::string where = t.schema.section + "/" + t.schema.type;
    EXPECT_TRUE(seen.insert({t.schema.section, t.schema.type, t.dimension}).second) << where << " registered twice";
    EXPECT_TRUE(t.dimension == 2 || t.dimension == 3) << where;
    EXPECT_FALSE(t.schema.defaultName.empty()) << where;
    if (t.schema.section == "bodies") { // built from the typed view BodySpec
      EXPECT_NE(t.describeBody, nullptr) << where << ": no typed view";
      EXPECT_NE(t.buildBody, nullptr) << where << ": no builder";
      EXPECT_EQ(&bodyType(t.bodyKind), &t) << where << ": BodySpec::Type taken twice";
    } else {
      EXPECT_NO_THROW(Scene().components(t.schema.section)) << where << ": unknown section";
      EXPECT_NE(t.build, nullptr) << where << ": no builder";
    }
    checkSchema(t.schema, where);
    EXPECT_EQ(findPhysicsType(t.schema.section, t.schema.type, t.dimension), &t);
  }
  EXPECT_EQ(findPhysicsType("constraints", "weld"), nullptr);
  EXPECT_EQ(findPhysicsType("loads", "pin"), nullptr); // types belong to one section
}

TEST(PhysicsTypes, ConstraintTypesInRegistrationOrderAndInTheDocs)
{
  std::vector<std::string> names;
  for (const PhysicsType *t : physicsTypesOf("constraints")) names.push_back(t->schema.type);
  const std::vector<std::string> expected{"clamp",           "pin",  "angle_drive",  "sliding_joint",
                                          "extraction_drive", "rope", "elastic_rope", "distance",
                                          "ground_contact", "hydraulic_cylinder"};
  EXPECT_EQ(names, expected);
  const std::string md = schemaMarkdown("constraints");
  for (const std::string &n : expected) EXPECT_NE(md.find("#### `" + n + "`"), std::string::npos) << n;
  EXPECT_NE(md.find("`sliding_joint`.`friction`"), std::string::npos); // nested schemas get their own table
  EXPECT_THROW(regenerateSchemaBlocks("no generated blocks here\n"), std::runtime_error);
}
