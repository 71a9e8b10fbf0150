// SRDF reading and writing: the project's own arm and the shared robots' files, checked against
// an independent tinyxml2 walk of the same file; exact round trips; clear errors.
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/srdf.hpp>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include "robot_test_support.hpp"

namespace hullcheck {
namespace {

namespace fs = std::filesystem;

using test::expect_contains;
using test::input_error_of;

// ---------------------------------------------------------------- independent reference

std::string attr(const tinyxml2::XMLElement* e, const char* name) {
  const char* v = e->Attribute(name);
  return v == nullptr ? std::string() : std::string(v);
}

// What the SRDF at `path` holds, read element by element with tinyxml2 and strtod (not with
// the library's reader).
Srdf reference_srdf(const std::string& path) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.LoadFile(path.c_str()), tinyxml2::XML_SUCCESS) << path;
  Srdf out;
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr) return out;
  out.robot_name = attr(robot, "name");
  for (const tinyxml2::XMLElement* v = robot->FirstChildElement("virtual_joint"); v != nullptr;
       v = v->NextSiblingElement("virtual_joint")) {
    out.virtual_joints.push_back(
        {attr(v, "name"), attr(v, "type"), attr(v, "parent_frame"), attr(v, "child_link")});
  }
  for (const tinyxml2::XMLElement* g = robot->FirstChildElement("group"); g != nullptr;
       g = g->NextSiblingElement("group")) {
    SrdfGroup group;
    group.name = attr(g, "name");
    for (const tinyxml2::XMLElement* c = g->FirstChildElement("joint"); c != nullptr;
         c = c->NextSiblingElement("joint")) {
      group.joints.push_back(attr(c, "name"));
    }
    for (const tinyxml2::XMLElement* c = g->FirstChildElement("link"); c != nullptr;
         c = c->NextSiblingElement("link")) {
      group.links.push_back(attr(c, "name"));
    }
    for (const tinyxml2::XMLElement* c = g->FirstChildElement("chain"); c != nullptr;
         c = c->NextSiblingElement("chain")) {
      group.chains.emplace_back(attr(c, "base_link"), attr(c, "tip_link"));
    }
    for (const tinyxml2::XMLElement* c = g->FirstChildElement("group"); c != nullptr;
         c = c->NextSiblingElement("group")) {
      group.subgroups.push_back(attr(c, "name"));
    }
    out.groups.push_back(group);
  }
  for (const tinyxml2::XMLElement* s = robot->FirstChildElement("group_state"); s != nullptr;
       s = s->NextSiblingElement("group_state")) {
    SrdfGroupState state;
    state.name = attr(s, "name");
    state.group = attr(s, "group");
    for (const tinyxml2::XMLElement* j = s->FirstChildElement("joint"); j != nullptr;
         j = j->NextSiblingElement("joint")) {
      const std::string text = attr(j, "value");
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      EXPECT_NE(end, text.c_str()) << path << ": " << text;
      state.joint_values.emplace_back(attr(j, "name"), value);
    }
    out.group_states.push_back(state);
  }
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement("end_effector"); e != nullptr;
       e = e->NextSiblingElement("end_effector")) {
    out.end_effectors.push_back(
        {attr(e, "name"), attr(e, "group"), attr(e, "parent_link"), attr(e, "parent_group")});
  }
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement("disable_collisions"); e != nullptr;
       e = e->NextSiblingElement("disable_collisions")) {
    out.disabled_collisions.push_back({attr(e, "link1"), attr(e, "link2"), attr(e, "reason")});
  }
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement("enable_collisions"); e != nullptr;
       e = e->NextSiblingElement("enable_collisions")) {
    out.enabled_collisions.push_back({attr(e, "link1"), attr(e, "link2"), attr(e, "reason")});
  }
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement("disable_default_collisions");
       e != nullptr; e = e->NextSiblingElement("disable_default_collisions")) {
    out.disabled_links.push_back(attr(e, "link"));
  }
  return out;
}

// Field-by-field equality with readable failures; values compared exactly.
void expect_same(const Srdf& actual, const Srdf& expected, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(actual.robot_name, expected.robot_name);
  ASSERT_EQ(actual.virtual_joints.size(), expected.virtual_joints.size());
  for (std::size_t i = 0; i < expected.virtual_joints.size(); ++i) {
    EXPECT_EQ(actual.virtual_joints[i].name, expected.virtual_joints[i].name);
    EXPECT_EQ(actual.virtual_joints[i].type, expected.virtual_joints[i].type);
    EXPECT_EQ(actual.virtual_joints[i].parent_frame, expected.virtual_joints[i].parent_frame);
    EXPECT_EQ(actual.virtual_joints[i].child_link, expected.virtual_joints[i].child_link);
  }
  ASSERT_EQ(actual.groups.size(), expected.groups.size());
  for (std::size_t i = 0; i < expected.groups.size(); ++i) {
    const SrdfGroup& a = actual.groups[i];
    const SrdfGroup& e = expected.groups[i];
    EXPECT_EQ(a.name, e.name);
    EXPECT_EQ(a.joints, e.joints) << e.name;
    EXPECT_EQ(a.links, e.links) << e.name;
    EXPECT_EQ(a.chains, e.chains) << e.name;
    EXPECT_EQ(a.subgroups, e.subgroups) << e.name;
  }
  ASSERT_EQ(actual.group_states.size(), expected.group_states.size());
  for (std::size_t i = 0; i < expected.group_states.size(); ++i) {
    const SrdfGroupState& a = actual.group_states[i];
    const SrdfGroupState& e = expected.group_states[i];
    EXPECT_EQ(a.name, e.name);
    EXPECT_EQ(a.group, e.group);
    ASSERT_EQ(a.joint_values.size(), e.joint_values.size()) << e.name;
    for (std::size_t j = 0; j < e.joint_values.size(); ++j) {
      EXPECT_EQ(a.joint_values[j].first, e.joint_values[j].first) << e.name;
      // Exact: the same decimal text must give the same double.
      EXPECT_EQ(a.joint_values[j].second, e.joint_values[j].second)
          << e.name << " " << e.joint_values[j].first;
    }
  }
  ASSERT_EQ(actual.end_effectors.size(), expected.end_effectors.size());
  for (std::size_t i = 0; i < expected.end_effectors.size(); ++i) {
    EXPECT_EQ(actual.end_effectors[i].name, expected.end_effectors[i].name);
    EXPECT_EQ(actual.end_effectors[i].group, expected.end_effectors[i].group);
    EXPECT_EQ(actual.end_effectors[i].parent_link, expected.end_effectors[i].parent_link);
    EXPECT_EQ(actual.end_effectors[i].parent_group, expected.end_effectors[i].parent_group);
  }
  const auto same_pairs = [](const std::vector<SrdfLinkPair>& a,
                             const std::vector<SrdfLinkPair>& e) {
    ASSERT_EQ(a.size(), e.size());
    for (std::size_t i = 0; i < e.size(); ++i) {
      EXPECT_EQ(a[i].link1, e[i].link1) << i;
      EXPECT_EQ(a[i].link2, e[i].link2) << i;
      EXPECT_EQ(a[i].reason, e[i].reason) << i;
    }
  };
  same_pairs(actual.disabled_collisions, expected.disabled_collisions);
  same_pairs(actual.enabled_collisions, expected.enabled_collisions);
  EXPECT_EQ(actual.disabled_links, expected.disabled_links);
}

// ---------------------------------------------------------------- the project's own arm

TEST(Srdf, OwnArm) {
  const std::string path = test::own_arm().srdf;
  const Srdf srdf = read_srdf_file(path);
  expect_same(srdf, reference_srdf(path), path);

  // By hand, from robots/hullcheck_arm/README.md and the file.
  EXPECT_EQ(srdf.robot_name, "hullcheck_arm");
  ASSERT_EQ(srdf.groups.size(), 3u);
  const SrdfGroup* arm = srdf.group("arm");
  ASSERT_NE(arm, nullptr);
  ASSERT_EQ(arm->chains.size(), 1u);
  EXPECT_EQ(arm->chains[0], std::make_pair(std::string("base_link"), std::string("link7")));
  EXPECT_TRUE(arm->joints.empty() && arm->links.empty() && arm->subgroups.empty());
  const SrdfGroup* gripper = srdf.group("gripper");
  ASSERT_NE(gripper, nullptr);
  EXPECT_EQ(gripper->links,
            (std::vector<std::string>{"flange", "finger_left", "finger_right", "tcp"}));
  EXPECT_EQ(gripper->joints, std::vector<std::string>{"finger_joint1"});
  const SrdfGroup* both = srdf.group("arm_with_gripper");
  ASSERT_NE(both, nullptr);
  EXPECT_EQ(both->subgroups, (std::vector<std::string>{"arm", "gripper"}));
  EXPECT_EQ(srdf.group("no_such_group"), nullptr);

  // home ready stow left right shelf_low shelf_high (arm), open closed (gripper)
  ASSERT_EQ(srdf.group_states.size(), 9u);
  const SrdfGroupState* ready = srdf.group_state("arm", "ready");
  ASSERT_NE(ready, nullptr);
  const std::vector<std::pair<std::string, double>> ready_values = {
      {"joint1", 0.0}, {"joint2", 0.3},    {"joint3", 0.0}, {"joint4", -1.6},
      {"joint5", 0.0}, {"joint6", 1.2416}, {"joint7", 0.0}};
  EXPECT_EQ(ready->joint_values, ready_values);
  const SrdfGroupState* stow = srdf.group_state("arm", "stow");
  ASSERT_NE(stow, nullptr);
  EXPECT_EQ(stow->joint_values[3], std::make_pair(std::string("joint4"), -1.85));
  const SrdfGroupState* open = srdf.group_state("gripper", "open");
  ASSERT_NE(open, nullptr);
  EXPECT_EQ(open->joint_values,
            (std::vector<std::pair<std::string, double>>{{"finger_joint1", 0.04}}));
  EXPECT_EQ(srdf.group_state("arm", "open"), nullptr);  // the group matters
  EXPECT_NE(srdf.group_state("gripper", "closed"), nullptr);
  EXPECT_NE(srdf.group_state("arm", "home"), nullptr);
  const SrdfGroupState* left = srdf.group_state("arm", "left");
  const SrdfGroupState* right = srdf.group_state("arm", "right");
  ASSERT_TRUE(left != nullptr && right != nullptr);
  // The demo's two sides of the wall: mirror images through joint1 only.
  EXPECT_EQ(left->joint_values[0], std::make_pair(std::string("joint1"), 0.5));
  EXPECT_EQ(right->joint_values[0], std::make_pair(std::string("joint1"), -0.5));
  for (std::size_t i = 1; i < left->joint_values.size(); ++i) {
    EXPECT_EQ(left->joint_values[i], right->joint_values[i]);
  }

  ASSERT_EQ(srdf.end_effectors.size(), 1u);
  EXPECT_EQ(srdf.end_effectors[0].name, "hand");
  EXPECT_EQ(srdf.end_effectors[0].parent_link, "link7");
  EXPECT_EQ(srdf.end_effectors[0].group, "gripper");
  EXPECT_EQ(srdf.end_effectors[0].parent_group, "arm");

  // The collision matrix is generated by the project's tool: every directly joined pair is
  // disabled as Adjacent, the rest as Adjacent or Never; the count is the reference's.
  EXPECT_GE(srdf.disabled_collisions.size(), 10u);
  const auto reason_of = [&](const std::string& a, const std::string& b) -> std::string {
    for (const SrdfLinkPair& p : srdf.disabled_collisions) {
      if ((p.link1 == a && p.link2 == b) || (p.link1 == b && p.link2 == a)) return p.reason;
    }
    return "(checked)";
  };
  const std::vector<std::pair<std::string, std::string>> joined = {
      {"base_link", "link1"},    {"link1", "link2"},        {"link2", "link3"}, {"link3", "link4"},
      {"link4", "link5"},        {"link5", "link6"},        {"link6", "link7"}, {"link7", "flange"},
      {"flange", "finger_left"}, {"flange", "finger_right"}};
  for (const auto& [a, b] : joined) EXPECT_EQ(reason_of(a, b), "Adjacent") << a << " " << b;
  for (const SrdfLinkPair& p : srdf.disabled_collisions) {
    EXPECT_TRUE(p.reason == "Adjacent" || p.reason == "Never") << p.link1 << " " << p.link2;
    EXPECT_NE(p.link1, "tcp");  // no geometry: never listed
    EXPECT_NE(p.link2, "tcp");
  }
  ASSERT_EQ(srdf.virtual_joints.size(), 1u);
  EXPECT_EQ(srdf.virtual_joints[0].name, "fixed_base");
  EXPECT_EQ(srdf.virtual_joints[0].type, "fixed");
  EXPECT_EQ(srdf.virtual_joints[0].parent_frame, "world");
  EXPECT_EQ(srdf.virtual_joints[0].child_link, "base_link");
  EXPECT_TRUE(srdf.enabled_collisions.empty());
  EXPECT_TRUE(srdf.disabled_links.empty());
}

// ---------------------------------------------------------------- shared robots

struct SharedSrdfCase {
  std::string id;
  std::size_t groups;
  std::size_t states;
  std::size_t disabled;
};

TEST(Srdf, SharedRobotsMatchIndependentReading) {
  // Counts by hand (grep) from the files; the element-by-element comparison is against the
  // tinyxml2 reference reader.
  const std::vector<SharedSrdfCase> cases = {{"panda", 3, 5, 34},
                                             {"ur5e", 1, 2, 11},
                                             {"abb_irb2400", 1, 1, 15},
                                             {"mbm_panda", 3, 5, 34},
                                             {"mbm_ur5", 2, 3, 88}};
  int checked = 0;
  for (const test::RobotFile& robot : test::shared_robots()) {
    if (robot.srdf.empty() || !fs::exists(robot.srdf)) continue;
    SCOPED_TRACE(robot.id);
    const Srdf srdf = read_srdf_file(robot.srdf);
    const Srdf reference = reference_srdf(robot.srdf);
    expect_same(srdf, reference, robot.srdf);
    for (const SharedSrdfCase& c : cases) {
      if (c.id != robot.id) continue;
      EXPECT_EQ(srdf.groups.size(), c.groups);
      EXPECT_EQ(srdf.group_states.size(), c.states);
      EXPECT_EQ(srdf.disabled_collisions.size(), c.disabled);
    }
    // Every state's values are finite and name a joint once.
    for (const SrdfGroupState& s : srdf.group_states) {
      EXPECT_NE(srdf.group(s.group), nullptr) << s.name;
      for (const auto& [joint, value] : s.joint_values) {
        EXPECT_TRUE(std::isfinite(value)) << s.name << " " << joint;
      }
    }
    // And the text round-trips.
    expect_same(parse_srdf(write_srdf(srdf)), srdf, robot.id + " round trip");
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "no shared robots with an SRDF (../shared absent)";
}

TEST(Srdf, PandaByHand) {
  const std::string path = test::shared_dir() + "/robots/panda/srdf/panda.srdf";
  if (test::shared_dir().empty() || !fs::exists(path)) GTEST_SKIP() << path << " absent";
  const Srdf srdf = read_srdf_file(path);
  EXPECT_EQ(srdf.robot_name, "panda");
  ASSERT_NE(srdf.group("panda_arm"), nullptr);
  EXPECT_EQ(srdf.group("panda_arm")->chains,
            (std::vector<std::pair<std::string, std::string>>{{"panda_link0", "panda_link8"}}));
  const SrdfGroup* hand = srdf.group("hand");
  ASSERT_NE(hand, nullptr);
  // <passive_joint> is not a <joint>.
  EXPECT_EQ(hand->joints, std::vector<std::string>{"panda_finger_joint1"});
  EXPECT_EQ(hand->links.size(), 3u);
  ASSERT_NE(srdf.group("panda_arm_hand"), nullptr);
  EXPECT_EQ(srdf.group("panda_arm_hand")->subgroups,
            (std::vector<std::string>{"panda_arm", "hand"}));
  const SrdfGroupState* ready = srdf.group_state("panda_arm", "ready");
  ASSERT_NE(ready, nullptr);
  ASSERT_EQ(ready->joint_values.size(), 7u);
  EXPECT_EQ(ready->joint_values[1], std::make_pair(std::string("panda_joint2"), -0.785));
  EXPECT_EQ(ready->joint_values[3], std::make_pair(std::string("panda_joint4"), -2.356));
  EXPECT_EQ(ready->joint_values[5], std::make_pair(std::string("panda_joint6"), 1.571));
  const SrdfGroupState* transport = srdf.group_state("panda_arm", "transport");
  ASSERT_NE(transport, nullptr);
  EXPECT_EQ(transport->joint_values[1].second, -0.5599);
  const SrdfGroupState* open = srdf.group_state("hand", "open");
  ASSERT_NE(open, nullptr);
  EXPECT_EQ(open->joint_values.size(), 2u);
  EXPECT_EQ(open->joint_values[1], std::make_pair(std::string("panda_finger_joint2"), 0.035));
  int adjacent = 0, never = 0, by_default = 0;
  for (const SrdfLinkPair& p : srdf.disabled_collisions) {
    adjacent += p.reason == "Adjacent";
    never += p.reason == "Never";
    by_default += p.reason == "Default";
  }
  EXPECT_EQ(adjacent, 10);
  EXPECT_EQ(never, 23);
  EXPECT_EQ(by_default, 1);
  ASSERT_EQ(srdf.end_effectors.size(), 1u);
  EXPECT_EQ(srdf.end_effectors[0].parent_link, "panda_link8");
  EXPECT_EQ(srdf.end_effectors[0].parent_group, "panda_arm");
}

// ---------------------------------------------------------------- writing

Srdf tricky_srdf() {
  Srdf s;
  s.robot_name = "r&d <\"robot\">";
  s.virtual_joints.push_back({"world_joint", "floating", "odom", "base"});
  s.virtual_joints.push_back({"second", "fixed", "world", "l1"});
  s.groups.push_back({"arm", {"j1", "j2"}, {"l1"}, {{"base", "tip"}}, {"sub"}});
  s.groups.push_back({"sub", {}, {"l'2"}, {}, {}});
  SrdfGroupState state{"odd_values", "arm", {}};
  const double values[] = {0.1,
                           1.0 / 3.0,
                           -M_PI,
                           2.0 / 3.0 * 1e-7,
                           1e300,
                           -1e-300,
                           std::numeric_limits<double>::min(),
                           std::numeric_limits<double>::max(),
                           std::nextafter(1.0, 2.0),
                           std::numeric_limits<double>::denorm_min(),
                           -3.5e-310,
                           0.0,
                           -0.0};
  int i = 0;
  for (const double v : values) state.joint_values.emplace_back("j" + std::to_string(i++), v);
  s.group_states.push_back(state);
  s.group_states.push_back({"empty", "sub", {}});
  s.end_effectors.push_back({"ee", "sub", "tip", ""});
  s.end_effectors.push_back({"ee2", "sub", "tip", "arm"});
  s.disabled_collisions.push_back({"l1", "tip", "Never"});
  s.disabled_collisions.push_back({"l1", "base", ""});
  s.disabled_collisions.push_back({"l1", "l'2", "Because & so"});
  s.enabled_collisions.push_back({"l1", "tip", "Never"});
  s.disabled_links.push_back("camera");
  return s;
}

TEST(Srdf, WriteThenParseRoundTripsExactly) {
  const Srdf s = tricky_srdf();
  const std::string text = write_srdf(s);
  const Srdf back = parse_srdf(text);
  expect_same(back, s, "round trip");
  // A comment changes nothing that is read back.
  expect_same(parse_srdf(write_srdf(s, "written by a test -- with dashes")), s, "comment");
  // Bit-exact values, sign of zero included.
  const auto& values = back.group_states[0].joint_values;
  EXPECT_TRUE(std::signbit(values.back().second));
  EXPECT_EQ(values[1].second, 1.0 / 3.0);
  // Writing again gives the same text.
  EXPECT_EQ(write_srdf(back), text);
}

TEST(Srdf, RandomValuesRoundTripBitExactly) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  Srdf s;
  s.robot_name = "random";
  SrdfGroupState state{"random", "g", {}};
  for (int i = 0; i < 2000; ++i) {
    state.joint_values.emplace_back("j" + std::to_string(i),
                                    angle(rng) * std::pow(10.0, exponent(rng)));
  }
  s.group_states.push_back(state);
  const Srdf back = parse_srdf(write_srdf(s));
  ASSERT_EQ(back.group_states.size(), 1u);
  ASSERT_EQ(back.group_states[0].joint_values.size(), state.joint_values.size());
  for (std::size_t i = 0; i < state.joint_values.size(); ++i) {
    ASSERT_EQ(back.group_states[0].joint_values[i].second, state.joint_values[i].second) << i;
  }
}

TEST(Srdf, WrittenTextIsMoveItShaped) {
  const std::string text = write_srdf(tricky_srdf());
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(text.c_str()), tinyxml2::XML_SUCCESS) << text;
  const tinyxml2::XMLElement* robot = doc.RootElement();
  ASSERT_NE(robot, nullptr);
  EXPECT_STREQ(robot->Name(), "robot");
  const tinyxml2::XMLElement* dc = robot->FirstChildElement("disable_collisions");
  ASSERT_NE(dc, nullptr);
  EXPECT_STREQ(dc->Attribute("link1"), "l1");
  EXPECT_STREQ(dc->Attribute("link2"), "tip");
  EXPECT_STREQ(dc->Attribute("reason"), "Never");
  const tinyxml2::XMLElement* state = robot->FirstChildElement("group_state");
  ASSERT_NE(state, nullptr);
  EXPECT_STREQ(state->Attribute("group"), "arm");
  EXPECT_STREQ(state->FirstChildElement("joint")->Attribute("value"), "0.1");  // shortest exact
}

TEST(Srdf, FileWrittenAndReadBack) {
  const fs::path path =
      fs::temp_directory_path() /
      ("hullcheck_srdf_" +
       std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + ".srdf");
  {
    std::ofstream out(path);
    out << write_srdf(tricky_srdf());
  }
  const Srdf back = read_srdf_file(path.string());
  fs::remove(path);
  expect_same(back, tricky_srdf(), "file");
}

// ---------------------------------------------------------------- errors

TEST(SrdfErrors, MalformedXml) {
  const std::string msg = input_error_of(
      [] { parse_srdf("<robot name=\"r\">\n  <group name=\"arm\">\n</robot>\n", "broken.srdf"); });
  expect_contains(msg, {"broken.srdf", "malformed"});
}

TEST(SrdfErrors, RootIsNotRobot) {
  expect_contains(input_error_of([] { parse_srdf("<semantic name=\"r\"/>", "x.srdf"); }),
                  {"x.srdf", "<robot>"});
}

TEST(SrdfErrors, MissingAttributeNamesLineAndAttribute) {
  const std::string xml =
      "<robot name=\"r\">\n"
      "  <group name=\"arm\"><joint name=\"j1\"/></group>\n"
      "  <group_state name=\"home\">\n"
      "    <joint name=\"j1\" value=\"0\"/>\n"
      "  </group_state>\n"
      "</robot>\n";
  const std::string msg = input_error_of([&] { parse_srdf(xml, "missing.srdf"); });
  expect_contains(msg, {"missing.srdf", "line 3", "<group_state>", "'group'"});

  const std::string pair =
      "<robot name=\"r\">\n\n\n\n  <disable_collisions link1=\"a\" reason=\"Never\"/>\n</robot>";
  expect_contains(input_error_of([&] { parse_srdf(pair, "pair.srdf"); }),
                  {"pair.srdf", "line 5", "<disable_collisions>", "'link2'"});

  const std::string chain =
      "<robot name=\"r\">\n  <group name=\"g\">\n    <chain base_link=\"b\"/>\n  </group>\n"
      "</robot>";
  expect_contains(input_error_of([&] { parse_srdf(chain, "chain.srdf"); }),
                  {"chain.srdf", "line 3", "<chain>", "'tip_link'"});

  const std::string value =
      "<robot name=\"r\">\n  <group_state name=\"s\" group=\"g\">\n    <joint name=\"j\"/>\n"
      "  </group_state>\n</robot>";
  expect_contains(input_error_of([&] { parse_srdf(value, "value.srdf"); }),
                  {"value.srdf", "line 3", "<joint>", "'value'"});
}

TEST(SrdfErrors, NonNumericJointValue) {
  const auto srdf_with_value = [](const std::string& value) {
    return "<robot name=\"r\">\n  <group_state name=\"s\" group=\"g\">\n"
           "    <joint name=\"elbow\" value=\"" +
           value + "\"/>\n  </group_state>\n</robot>\n";
  };
  for (const std::string bad :
       {"abc", "nan", "inf", "", "  ", "1e999", "0.5rad", "1,5", "--1", "1 x"}) {
    SCOPED_TRACE(bad);
    const std::string msg =
        input_error_of([&] { parse_srdf(srdf_with_value(bad), "values.srdf"); });
    expect_contains(msg, {"values.srdf", "line 3", "value"});
    if (bad.find_first_not_of(' ') != std::string::npos) {
      expect_contains(msg, {"'" + bad + "'", "not a finite number"});
    }
  }
  // Accepted spellings (a multi-DOF joint's list gives its first value).
  for (const auto& [text, value] :
       std::vector<std::pair<std::string, double>>{{"1.5", 1.5},
                                                   {" -2e-3 ", -2e-3},
                                                   {"+0.25", 0.25},
                                                   {"3", 3.0},
                                                   {".5", 0.5},
                                                   {"0.25 1 2", 0.25}}) {
    const Srdf s = parse_srdf(srdf_with_value(text));
    ASSERT_EQ(s.group_states.size(), 1u);
    EXPECT_EQ(s.group_states[0].joint_values.at(0).second, value) << text;
  }
}

TEST(SrdfErrors, MissingFile) {
  const std::string path =
      (fs::temp_directory_path() / "hullcheck_no_such_dir_4711" / "absent.srdf").string();
  expect_contains(input_error_of([&] { read_srdf_file(path); }), {path, "cannot open"});
}

TEST(Srdf, UnknownElementsAreSkipped) {
  const Srdf s = parse_srdf(
      "<robot name=\"r\">\n"
      "  <virtual_joint name=\"v\" type=\"fixed\" parent_frame=\"world\" child_link=\"b\"/>\n"
      "  <passive_joint name=\"p\"/>\n"
      "  <link_sphere_approximation link=\"b\"><sphere center=\"0 0 0\" radius=\"1\"/>"
      "</link_sphere_approximation>\n"
      "  <disable_default_collisions link=\"cam\"/>\n"
      "  <enable_collisions link1=\"a\" link2=\"b\" reason=\"Never\"/>\n"
      "</robot>\n");
  EXPECT_EQ(s.robot_name, "r");
  EXPECT_TRUE(s.groups.empty());
  EXPECT_EQ(s.disabled_links, std::vector<std::string>{"cam"});
  ASSERT_EQ(s.enabled_collisions.size(), 1u);
  EXPECT_EQ(s.enabled_collisions[0].link2, "b");
}

}  // namespace
}  // namespace hullcheck
