// Allowed-collision matrix: adjacency (as MoveIt's setup assistant defines it), SRDF
// application, sampled generation (Adjacent / Default / Always / Never) and its SRDF round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene.hpp>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "robot_test_support.hpp"

namespace hullcheck {
namespace {

namespace fs = std::filesystem;

using NamePair = std::pair<std::string, std::string>;

NamePair ordered(const std::string& a, const std::string& b) {
  return a < b ? NamePair(a, b) : NamePair(b, a);
}

// Every allowed pair, by names (ordered), with its reason.
std::map<NamePair, CollisionAllowance> allowed_pairs(const RobotModel& model,
                                                     const AllowedCollisionMatrix& acm) {
  std::map<NamePair, CollisionAllowance> out;
  const int n = static_cast<int>(model.links().size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (acm.allowed(a, b))
        out[ordered(model.link(a).name, model.link(b).name)] = acm.allowance(a, b);
    }
  }
  return out;
}

std::set<NamePair> names(const std::map<NamePair, CollisionAllowance>& pairs) {
  std::set<NamePair> out;
  for (const auto& [p, r] : pairs) out.insert(p);
  return out;
}

std::set<NamePair> pair_set(std::initializer_list<NamePair> pairs) {
  std::set<NamePair> out;
  for (const NamePair& p : pairs) out.insert(ordered(p.first, p.second));
  return out;
}

void expect_same_matrix(const AllowedCollisionMatrix& a, const AllowedCollisionMatrix& b,
                        const RobotModel& model) {
  ASSERT_EQ(a.link_count(), b.link_count());
  for (int i = 0; i < a.link_count(); ++i) {
    for (int j = 0; j < a.link_count(); ++j) {
      EXPECT_EQ(a.allowance(i, j), b.allowance(i, j))
          << model.link(i).name << " / " << model.link(j).name << ": "
          << to_string(a.allowance(i, j)) << " vs " << to_string(b.allowance(i, j));
    }
  }
}

std::shared_ptr<const RobotModel> own_arm_model() {
  static const auto model =
      std::make_shared<const RobotModel>(RobotModel::from_urdf_file(test::own_arm().urdf));
  return model;
}

std::shared_ptr<const RobotModel> load_string(const std::string& xml) {
  return std::make_shared<const RobotModel>(
      RobotModel::from_urdf_string(xml, ".", {}, "constructed.urdf"));
}

using test::random_configuration;

// ---------------------------------------------------------------- the matrix itself

TEST(AllowedCollisionMatrix, Basics) {
  AllowedCollisionMatrix acm(4);
  EXPECT_EQ(acm.link_count(), 4);
  EXPECT_EQ(acm.allowed_pair_count(), 0);
  EXPECT_TRUE(acm.allowed(2, 2));  // a link is never checked against itself
  EXPECT_FALSE(acm.allowed(0, 3));
  acm.allow(3, 0, CollisionAllowance::kNever);
  EXPECT_TRUE(acm.allowed(0, 3));
  EXPECT_EQ(acm.allowance(0, 3), CollisionAllowance::kNever);  // symmetric
  EXPECT_EQ(acm.allowance(3, 0), CollisionAllowance::kNever);
  acm.allow(0, 3, CollisionAllowance::kUser);  // a later reason replaces the earlier one
  EXPECT_EQ(acm.allowance(3, 0), CollisionAllowance::kUser);
  acm.allow(1, 2, CollisionAllowance::kAdjacent);
  EXPECT_EQ(acm.allowed_pair_count(), 2);
  acm.check(3, 0);
  EXPECT_FALSE(acm.allowed(0, 3));
  EXPECT_EQ(acm.allowance(0, 3), CollisionAllowance::kChecked);
  EXPECT_EQ(acm.allowed_pair_count(), 1);
  acm.allow(1, 1, CollisionAllowance::kUser);  // no-op
  EXPECT_EQ(acm.allowed_pair_count(), 1);
}

TEST(AllowedCollisionMatrix, Misuse) {
  AllowedCollisionMatrix acm(3);
  try {
    acm.allow(0, 3, CollisionAllowance::kNever);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(0, 3; 3 links)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(acm.allow(-1, 0, CollisionAllowance::kNever), InputError);
  EXPECT_THROW(acm.check(0, 7), InputError);
  try {
    acm.allow(0, 1, CollisionAllowance::kChecked);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("kChecked"), std::string::npos) << e.what();
  }
  EXPECT_THROW(AllowedCollisionMatrix(-1), InputError);
}

TEST(AllowedCollisionMatrix, ReasonNames) {
  EXPECT_STREQ(to_string(CollisionAllowance::kChecked), "Checked");
  EXPECT_STREQ(to_string(CollisionAllowance::kAdjacent), "Adjacent");
  EXPECT_STREQ(to_string(CollisionAllowance::kNever), "Never");
  EXPECT_STREQ(to_string(CollisionAllowance::kDefault), "Default");
  EXPECT_STREQ(to_string(CollisionAllowance::kAlways), "Always");
  EXPECT_STREQ(to_string(CollisionAllowance::kUser), "User");
}

// ---------------------------------------------------------------- adjacency

TEST(Adjacency, OwnArmByHand) {
  // From robots/hullcheck_arm/urdf/hullcheck_arm.urdf: links joined by a joint; flange, tcp
  // and link7 form one rigid body (fixed joints); tcp has no geometry, but its only neighbour
  // is the flange, so skipping it joins nothing new. link6 is not adjacent to the flange (two
  // joints apart: joint7 and the fixed flange_joint), nor link7 to the fingers.
  const auto model = own_arm_model();
  const AllowedCollisionMatrix acm = AllowedCollisionMatrix::from_adjacency(*model);
  const auto pairs = allowed_pairs(*model, acm);
  EXPECT_EQ(names(pairs), pair_set({{"base_link", "link1"},
                                    {"link1", "link2"},
                                    {"link2", "link3"},
                                    {"link3", "link4"},
                                    {"link4", "link5"},
                                    {"link5", "link6"},
                                    {"link6", "link7"},
                                    {"link7", "flange"},
                                    {"flange", "finger_left"},
                                    {"flange", "finger_right"},
                                    {"flange", "tcp"},
                                    {"link7", "tcp"}}));
  for (const auto& [p, reason] : pairs) {
    EXPECT_EQ(reason, CollisionAllowance::kAdjacent) << p.first << " / " << p.second;
  }
  EXPECT_EQ(acm.allowed_pair_count(), 12);
  // Among links with geometry: exactly the 10 directly joined pairs, as the README says.
  const CollisionChecker checker(model, acm);
  EXPECT_EQ(checker.checked_link_pairs().size(), 55u - 10u);  // 11 links with geometry
}

TEST(Adjacency, LinksWithoutGeometryAreSkippedOver) {
  // a - x - y - b: x and y have no geometry, so a and b count as joined (and x, y with both).
  const auto model = load_string(R"(<robot name="skip">
    <link name="a"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <link name="x"/>
    <link name="y"/>
    <link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <link name="c"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <joint name="j1" type="continuous"><parent link="a"/><child link="x"/></joint>
    <joint name="j2" type="continuous"><parent link="x"/><child link="y"/></joint>
    <joint name="j3" type="continuous"><parent link="y"/><child link="b"/></joint>
    <joint name="j4" type="continuous"><parent link="b"/><child link="c"/></joint>
  </robot>)");
  const auto pairs = names(allowed_pairs(*model, AllowedCollisionMatrix::from_adjacency(*model)));
  EXPECT_EQ(pairs.count(ordered("a", "b")), 1u);
  EXPECT_EQ(pairs.count(ordered("b", "c")), 1u);
  EXPECT_EQ(pairs.count(ordered("a", "c")), 0u);  // b has geometry: not skipped
}

TEST(Adjacency, ChildrenOfALinkWithoutGeometryAreJoined) {
  // MoveIt joins every neighbour of a link without geometry, siblings included: both arms on
  // a bare root count as adjacent to each other (their first links touch at the root).
  const auto model = load_string(R"(<robot name="siblings">
    <link name="root"/>
    <link name="left"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <link name="right"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <link name="left2"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <joint name="jl" type="continuous"><parent link="root"/><child link="left"/></joint>
    <joint name="jr" type="continuous"><parent link="root"/><child link="right"/></joint>
    <joint name="jl2" type="continuous"><parent link="left"/><child link="left2"/></joint>
  </robot>)");
  const auto pairs = names(allowed_pairs(*model, AllowedCollisionMatrix::from_adjacency(*model)));
  EXPECT_EQ(pairs,
            pair_set({{"root", "left"}, {"root", "right"}, {"left", "right"}, {"left", "left2"}}));
}

TEST(Adjacency, FixedToolIsNotAdjacentToTheLinkBeforeItsCarrier) {
  // upper -(revolute)- lower -(fixed)- tool: lower and tool are one rigid body, but the tool
  // is two joints away from upper and can swing into it, so that pair stays checked (MoveIt's
  // Panda SRDF likewise lists panda_hand / panda_link6 as "Never", not "Adjacent").
  const auto model = load_string(R"(<robot name="tool">
    <link name="upper"><collision><geometry><box size="0.1 0.1 0.4"/></geometry></collision></link>
    <link name="lower"><collision><geometry><box size="0.1 0.1 0.4"/></geometry></collision></link>
    <link name="tool"><collision><geometry><box size="0.2 0.05 0.05"/></geometry></collision></link>
    <link name="frame"/>
    <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/>
      <origin xyz="0 0 0.4"/><axis xyz="0 1 0"/>
      <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
    <joint name="mount" type="fixed"><parent link="lower"/><child link="tool"/>
      <origin xyz="0.2 0 0"/></joint>
    <joint name="tip" type="fixed"><parent link="tool"/><child link="frame"/></joint>
  </robot>)");
  const AllowedCollisionMatrix acm = AllowedCollisionMatrix::from_adjacency(*model);
  const auto pairs = names(allowed_pairs(*model, acm));
  EXPECT_EQ(
      pairs,
      pair_set({{"upper", "lower"}, {"lower", "tool"}, {"lower", "frame"}, {"tool", "frame"}}));
  // And the tool does hit the upper link when the elbow folds.
  const CollisionChecker checker(model, acm);
  EXPECT_FALSE(!checker.is_valid(Eigen::VectorXd::Constant(1, 0.0)));
  EXPECT_TRUE(!checker.is_valid(Eigen::VectorXd::Constant(1, 1.5)));
}

TEST(Adjacency, PandaMatchesItsSrdfAdjacentPairs) {
  // MoveIt's setup assistant wrote the Panda SRDF; its "Adjacent" pairs are what
  // from_adjacency must give among links with geometry.
  const std::string dir = test::shared_dir() + "/robots/panda";
  const std::string urdf = dir + "/moveit_resources_panda_description/urdf/panda.urdf";
  if (test::shared_dir().empty() || !fs::exists(urdf)) GTEST_SKIP() << urdf << " absent";
  const RobotModel model = RobotModel::from_urdf_file(urdf);
  const Srdf srdf = read_srdf_file(dir + "/srdf/panda.srdf");
  std::set<NamePair> expected;
  for (const SrdfLinkPair& p : srdf.disabled_collisions) {
    if (p.reason == "Adjacent") expected.insert(ordered(p.link1, p.link2));
  }
  ASSERT_EQ(expected.size(), 10u);
  std::set<NamePair> got;
  for (const auto& [p, reason] :
       allowed_pairs(model, AllowedCollisionMatrix::from_adjacency(model))) {
    const bool geometry = !model.link(model.link_index(p.first)).shapes.empty() &&
                          !model.link(model.link_index(p.second)).shapes.empty();
    if (geometry) got.insert(p);
  }
  EXPECT_EQ(got, expected);
}

// ---------------------------------------------------------------- SRDF

TEST(FromSrdf, OwnArmSrdf) {
  const auto model = own_arm_model();
  const Srdf srdf = read_srdf_file(test::own_arm().srdf);
  std::vector<std::string> warnings;
  const AllowedCollisionMatrix acm = AllowedCollisionMatrix::from_srdf(*model, srdf, &warnings);
  EXPECT_TRUE(warnings.empty());
  std::map<NamePair, std::string> listed;
  for (const SrdfLinkPair& p : srdf.disabled_collisions) {
    listed[ordered(p.link1, p.link2)] = p.reason;
  }
  const AllowedCollisionMatrix adjacency = AllowedCollisionMatrix::from_adjacency(*model);
  const int n = static_cast<int>(model->links().size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      const auto it = listed.find(ordered(model->link(a).name, model->link(b).name));
      if (it != listed.end()) {
        EXPECT_EQ(to_string(acm.allowance(a, b)), it->second)
            << model->link(a).name << " / " << model->link(b).name;
      } else {
        EXPECT_EQ(acm.allowance(a, b), adjacency.allowance(a, b))
            << model->link(a).name << " / " << model->link(b).name;
      }
    }
  }
  EXPECT_EQ(acm.allowed_pair_count(), static_cast<int>(listed.size()) + 2);  // + tcp's pairs
}

TEST(FromSrdf, ReasonsWarningsDefaultsAndReEnabling) {
  const auto model = own_arm_model();
  const int n = static_cast<int>(model->links().size());
  const auto id = [&](const char* name) { return model->link_index(name); };
  Srdf srdf;
  srdf.disabled_collisions = {{"link1", "link4", "Never"},
                              {"link1", "link5", "Default"},
                              {"link1", "link6", "Always"},
                              {"link1", "link7", "User"},
                              {"link2", "link5", "Because I said so"},
                              {"link2", "link6", ""},
                              {"link3", "link6", "Adjacent"},
                              {"link2", "ghost_link", "Never"},
                              {"phantom", "link3", "Never"}};
  srdf.disabled_links = {"finger_left", "nobody"};
  srdf.enabled_collisions = {{"link1", "link7", ""},          // re-enables a disabled pair
                             {"link6", "link7", "Adjacent"},  // and an adjacent one
                             {"link2", "spectre", ""}};
  std::vector<std::string> warnings;
  const AllowedCollisionMatrix acm = AllowedCollisionMatrix::from_srdf(*model, srdf, &warnings);
  EXPECT_EQ(acm.allowance(id("link1"), id("link4")), CollisionAllowance::kNever);
  EXPECT_EQ(acm.allowance(id("link5"), id("link1")), CollisionAllowance::kDefault);
  EXPECT_EQ(acm.allowance(id("link1"), id("link6")), CollisionAllowance::kAlways);
  EXPECT_EQ(acm.allowance(id("link2"), id("link5")), CollisionAllowance::kUser);
  EXPECT_EQ(acm.allowance(id("link2"), id("link6")), CollisionAllowance::kUser);
  EXPECT_EQ(acm.allowance(id("link3"), id("link6")), CollisionAllowance::kAdjacent);
  EXPECT_EQ(acm.allowance(id("link1"), id("link7")), CollisionAllowance::kChecked);
  EXPECT_EQ(acm.allowance(id("link6"), id("link7")), CollisionAllowance::kChecked);
  // disable_default_collisions: every pair with the finger allowed; adjacent ones keep their
  // reason.
  for (int b = 0; b < n; ++b) {
    if (b == id("finger_left")) continue;
    EXPECT_TRUE(acm.allowed(id("finger_left"), b)) << model->link(b).name;
  }
  EXPECT_EQ(acm.allowance(id("finger_left"), id("flange")), CollisionAllowance::kAdjacent);
  EXPECT_EQ(acm.allowance(id("finger_left"), id("base_link")), CollisionAllowance::kUser);
  // Untouched pairs stay checked.
  EXPECT_EQ(acm.allowance(id("base_link"), id("link5")), CollisionAllowance::kChecked);
  // Unknown names: skipped, one warning per unknown name, naming robot and link.
  ASSERT_EQ(warnings.size(), 4u);
  const std::string all =
      warnings[0] + "\n" + warnings[1] + "\n" + warnings[2] + "\n" + warnings[3];
  for (const char* name : {"ghost_link", "phantom", "nobody", "spectre"}) {
    EXPECT_NE(all.find(std::string("'") + name + "'"), std::string::npos) << all;
  }
  EXPECT_NE(warnings[0].find("hullcheck_arm"), std::string::npos) << warnings[0];
  EXPECT_NE(all.find("disable_default_collisions"), std::string::npos) << all;
  EXPECT_NE(all.find("enable_collisions"), std::string::npos) << all;
  // Without a warnings vector: the same matrix, no throw.
  expect_same_matrix(AllowedCollisionMatrix::from_srdf(*model, srdf), acm, *model);
}

TEST(FromSrdf, SharedRobots) {
  int done = 0;
  for (const test::RobotFile& robot : test::shared_robots()) {
    if (robot.srdf.empty() || !fs::exists(robot.srdf)) continue;
    SCOPED_TRACE(robot.id);
    const RobotModel model = RobotModel::from_urdf_file(robot.urdf);
    const Srdf srdf = read_srdf_file(robot.srdf);
    std::vector<std::string> warnings;
    const AllowedCollisionMatrix acm = AllowedCollisionMatrix::from_srdf(model, srdf, &warnings);
    for (const std::string& w : warnings) std::printf("[ %s ] %s\n", robot.id.c_str(), w.c_str());
    int listed_known = 0;
    for (const SrdfLinkPair& p : srdf.disabled_collisions) {
      const int a = model.link_index(p.link1);
      const int b = model.link_index(p.link2);
      if (a < 0 || b < 0) continue;
      ++listed_known;
      EXPECT_TRUE(acm.allowed(a, b)) << p.link1 << " / " << p.link2;
      EXPECT_EQ(to_string(acm.allowance(a, b)), p.reason) << p.link1 << " / " << p.link2;
    }
    EXPECT_GE(acm.allowed_pair_count(), listed_known);
    ++done;
  }
  if (done == 0) GTEST_SKIP() << "no shared robots with an SRDF";
}

// ---------------------------------------------------------------- generation

TEST(GenerateCollisionMatrix, OwnArm) {
  const auto model = own_arm_model();
  CollisionMatrixOptions options;
  options.samples = 2000;
  options.seed = 1;
  const GeneratedCollisionMatrix g = generate_collision_matrix(*model, options);
  EXPECT_EQ(g.samples, 2000);
  // 11 links with geometry: 55 pairs, each counted once.
  EXPECT_EQ(g.adjacent + g.default_pose + g.always + g.never + g.checked, 55);
  EXPECT_EQ(g.adjacent, 10);
  EXPECT_EQ(g.default_pose, 0);  // home is free of self-collision
  EXPECT_EQ(g.always, 0);
  EXPECT_GT(g.never, 0);
  EXPECT_GT(g.checked, 0);
  std::printf(
      "[ hullcheck_arm ] %d samples: %d Adjacent, %d Default, %d Always, %d Never, %d "
      "checked\n",
      g.samples, g.adjacent, g.default_pose, g.always, g.never, g.checked);
  // Adjacent pairs are the adjacency matrix's, with that reason; the reason counts match.
  const AllowedCollisionMatrix adjacency = AllowedCollisionMatrix::from_adjacency(*model);
  const int n = static_cast<int>(model->links().size());
  std::map<CollisionAllowance, int> counts;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (adjacency.allowed(a, b)) {
        EXPECT_EQ(g.matrix.allowance(a, b), CollisionAllowance::kAdjacent);
      }
      if (!model->link(a).shapes.empty() && !model->link(b).shapes.empty()) {
        ++counts[g.matrix.allowance(a, b)];
      }
    }
  }
  EXPECT_EQ(counts[CollisionAllowance::kAdjacent], g.adjacent);
  EXPECT_EQ(counts[CollisionAllowance::kNever], g.never);
  EXPECT_EQ(counts[CollisionAllowance::kChecked], g.checked);
  // Deterministic for a seed.
  const GeneratedCollisionMatrix again = generate_collision_matrix(*model, options);
  expect_same_matrix(again.matrix, g.matrix, *model);
  EXPECT_EQ(again.never, g.never);
  EXPECT_EQ(again.checked, g.checked);
}

TEST(GenerateCollisionMatrix, NeverPairsRarelyCollideInFreshSamples) {
  // Independent check of "Never": a checker with adjacency only, at 5000 configurations of
  // another seed. A pair generation called "Never" after 2000 samples may collide in a thin
  // region it did not sample; that must be rare.
  const auto model = own_arm_model();
  CollisionMatrixOptions options;
  options.samples = 2000;
  const GeneratedCollisionMatrix g = generate_collision_matrix(*model, options);
  const CollisionChecker checker(model, AllowedCollisionMatrix::from_adjacency(*model));
  std::mt19937_64 rng(20261121);
  std::vector<Eigen::Isometry3d> poses;
  std::vector<std::pair<int, int>> pairs;
  std::map<std::pair<int, int>, int> never_hits;
  int samples_with_never_hit = 0, samples_colliding = 0;
  const int fresh = 5000;
  for (int s = 0; s < fresh; ++s) {
    model->compute_link_poses(random_configuration(*model, rng), poses);
    pairs.clear();
    checker.colliding_link_pairs_at(poses, pairs);
    bool hit = false;
    for (const auto& p : pairs) {
      if (g.matrix.allowance(p.first, p.second) == CollisionAllowance::kNever) {
        ++never_hits[p];
        hit = true;
      }
    }
    samples_with_never_hit += hit;
    samples_colliding += !pairs.empty();
  }
  std::printf(
      "[ hullcheck_arm ] %d fresh samples: %d in self-collision, %d with a \"Never\" "
      "pair colliding\n",
      fresh, samples_colliding, samples_with_never_hit);
  for (const auto& [p, count] : never_hits) {
    std::printf("  Never pair %s / %s collided %d times\n", model->link(p.first).name.c_str(),
                model->link(p.second).name.c_str(), count);
  }
  EXPECT_GT(samples_colliding, 100);               // the check has teeth: collisions do happen
  EXPECT_LE(samples_with_never_hit, fresh / 500);  // at most 0.2 %
}

// base (box) -[j1: prismatic along -x, 0..1]- carriage (small sphere far above)
//   -[j2: prismatic along z, 0..1 mm]- tip (long box, 1 cm from base at q1 = 0, into it for
//   q1 > 0.01: about 99 % of the samples);
// base -[jb: prismatic along y, -1..1]- blocker (box at x 0.5, inside the tip for |qb| < 0.1,
//   which includes the default 0: 10 % of the samples);
// base -[jf: revolute about z]- far (sphere 5 m below);
// base -[js: prismatic along -z, 0..1]- sometimes (box at x 1.5, z 0.2 - qs: meets the tip
//   for qs in (0.1, 0.3) and q1 < 0.61, about 12 %; free at the default).
const char* const kSemantics = R"(<robot name="semantics">
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="carriage"><collision><origin xyz="0 0 3"/>
    <geometry><sphere radius="0.01"/></geometry></collision></link>
  <link name="tip"><collision><origin xyz="1.06 0 0"/>
    <geometry><box size="2 0.1 0.1"/></geometry></collision></link>
  <link name="blocker"><collision><origin xyz="0.5 0 0"/>
    <geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="far"><collision><origin xyz="0 0 -5"/>
    <geometry><sphere radius="0.05"/></geometry></collision></link>
  <link name="sometimes"><collision><origin xyz="1.5 0 0.2"/>
    <geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="j1" type="prismatic"><parent link="base"/><child link="carriage"/>
    <axis xyz="-1 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="prismatic"><parent link="carriage"/><child link="tip"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="0.001" effort="1" velocity="1"/></joint>
  <joint name="jb" type="prismatic"><parent link="base"/><child link="blocker"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="jf" type="revolute"><parent link="base"/><child link="far"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="js" type="prismatic"><parent link="base"/><child link="sometimes"/>
    <axis xyz="0 0 -1"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>)";

TEST(GenerateCollisionMatrix, AlwaysDefaultNeverSemantics) {
  const auto model = load_string(kSemantics);
  CollisionMatrixOptions options;
  options.samples = 2000;
  options.seed = 5;
  const GeneratedCollisionMatrix g = generate_collision_matrix(*model, options);
  const auto reason = [&](const char* a, const char* b) {
    return to_string(g.matrix.allowance(model->link_index(a), model->link_index(b)));
  };
  // Adjacent: joined by a joint.
  EXPECT_STREQ(reason("base", "carriage"), "Adjacent");
  EXPECT_STREQ(reason("carriage", "tip"), "Adjacent");
  EXPECT_STREQ(reason("base", "blocker"), "Adjacent");
  EXPECT_STREQ(reason("base", "far"), "Adjacent");
  EXPECT_STREQ(reason("base", "sometimes"), "Adjacent");
  // Overlapping in ~99 % of samples, but not in the default configuration: Always.
  EXPECT_STREQ(reason("base", "tip"), "Always");
  // Overlapping in the default configuration (and in 10 % of samples): Default.
  EXPECT_STREQ(reason("tip", "blocker"), "Default");
  // Sometimes: checked.
  EXPECT_STREQ(reason("tip", "sometimes"), "Checked");
  // Far apart everywhere: Never.
  for (const char* other : {"carriage", "tip", "blocker", "sometimes"}) {
    EXPECT_STREQ(reason("far", other), "Never") << other;
  }
  EXPECT_STREQ(reason("carriage", "blocker"), "Never");
  EXPECT_STREQ(reason("carriage", "sometimes"), "Never");
  EXPECT_STREQ(reason("blocker", "sometimes"), "Never");
  EXPECT_EQ(g.adjacent, 5);
  EXPECT_EQ(g.default_pose, 1);
  EXPECT_EQ(g.always, 1);
  EXPECT_EQ(g.checked, 1);
  EXPECT_EQ(g.never, 7);

  // With always_fraction = 1 the 99 % pair is no longer "Always".
  options.always_fraction = 1.0;
  const GeneratedCollisionMatrix strict = generate_collision_matrix(*model, options);
  EXPECT_STREQ(
      to_string(strict.matrix.allowance(model->link_index("base"), model->link_index("tip"))),
      "Checked");
}

TEST(GenerateCollisionMatrix, BadOptions) {
  const auto model = load_string(kSemantics);
  const auto message = [&](const CollisionMatrixOptions& o) -> std::string {
    try {
      generate_collision_matrix(*model, o);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  };
  CollisionMatrixOptions o;
  o.samples = 0;
  EXPECT_NE(message(o).find("samples"), std::string::npos) << message(o);
  for (const double f : {0.0, -0.5, 1.5, std::nan("")}) {
    o = CollisionMatrixOptions();
    o.samples = 10;
    o.always_fraction = f;
    EXPECT_NE(message(o).find("always_fraction"), std::string::npos) << f << ": " << message(o);
  }
}

void expect_srdf_round_trip(const RobotModel& model, const AllowedCollisionMatrix& matrix) {
  const Srdf srdf = collision_matrix_to_srdf(model, matrix);
  EXPECT_EQ(srdf.robot_name, model.name());
  EXPECT_TRUE(srdf.groups.empty() && srdf.group_states.empty());
  for (const SrdfLinkPair& p : srdf.disabled_collisions) {
    // Link order, never a link without geometry.
    EXPECT_LT(model.link_index(p.link1), model.link_index(p.link2));
    EXPECT_FALSE(model.link(model.link_index(p.link1)).shapes.empty());
    EXPECT_FALSE(model.link(model.link_index(p.link2)).shapes.empty());
  }
  const Srdf back = parse_srdf(write_srdf(srdf));
  std::vector<std::string> warnings;
  expect_same_matrix(AllowedCollisionMatrix::from_srdf(model, back, &warnings), matrix, model);
  EXPECT_TRUE(warnings.empty());
}

TEST(GenerateCollisionMatrix, SrdfRoundTrip) {
  const auto arm = own_arm_model();
  CollisionMatrixOptions options;
  options.samples = 500;
  const GeneratedCollisionMatrix g = generate_collision_matrix(*arm, options);
  {
    SCOPED_TRACE("hullcheck_arm");
    expect_srdf_round_trip(*arm, g.matrix);
    const Srdf srdf = collision_matrix_to_srdf(*arm, g.matrix);
    EXPECT_EQ(static_cast<int>(srdf.disabled_collisions.size()),
              g.adjacent + g.default_pose + g.always + g.never);
  }
  {
    SCOPED_TRACE("semantics");
    const auto model = load_string(kSemantics);
    options.samples = 300;
    expect_srdf_round_trip(*model, generate_collision_matrix(*model, options).matrix);
  }
  EXPECT_THROW(collision_matrix_to_srdf(*arm, AllowedCollisionMatrix(3)), InputError);
}

TEST(GenerateCollisionMatrix, UsesPadding) {
  // Padding the base by 2 cm closes the 1 cm gap of the default configuration: base / tip
  // becomes "Default" instead of "Always".
  RobotLoadOptions load;
  load.link_padding["base"] = 0.02;
  const RobotModel model = RobotModel::from_urdf_string(kSemantics, ".", load);
  CollisionMatrixOptions options;
  options.samples = 200;
  const GeneratedCollisionMatrix g = generate_collision_matrix(model, options);
  EXPECT_STREQ(to_string(g.matrix.allowance(model.link_index("base"), model.link_index("tip"))),
               "Default");
}

}  // namespace
}  // namespace hullcheck
