// Robot kinematics: forward kinematics against KDL (kdl_parser's tree of the same
// URDF), the configuration order against an independent depth-first walk of the URDF (parsed here
// with tinyxml2), mimic joints, limits and the default configuration, and the allocation-free
// forward kinematics; the SIMD block forward kinematics against KDL on every SIMD target.
#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <hullcheck/robot.hpp>
#include <iostream>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/tree.hpp>
#include <kdl/treefksolverpos_recursive.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <locale>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "robot_test_support.hpp"

namespace hullcheck {
namespace {

using test::RobotFile;

using test::find_robot;
using test::read_text;
using test::robot_ids;
using test::robot_name_for_test;

// ------------------------------------------------------------------------------------------
// The joints of a URDF, read here with tinyxml2.

double parse_double(const char* text, double fallback) {
  if (text == nullptr) return fallback;
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  double v = 0.0;
  in >> v;
  EXPECT_FALSE(in.fail()) << "bad number '" << text << "'";
  return v;
}

Eigen::Vector3d parse_vector(const char* text, const Eigen::Vector3d& fallback) {
  if (text == nullptr) return fallback;
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  Eigen::Vector3d v;
  in >> v.x() >> v.y() >> v.z();
  EXPECT_FALSE(in.fail()) << "bad vector '" << text << "'";
  return v;
}

struct UrdfJoint {
  std::string name, type, parent, child;
  double lower = 0.0, upper = 0.0;  // URDF defaults
  bool has_limit = false;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  std::string mimic;  // leader's name, or empty
  double multiplier = 1.0, offset = 0.0;
  bool movable() const { return type == "revolute" || type == "continuous" || type == "prismatic"; }
  bool active() const { return movable() && mimic.empty(); }
};

struct UrdfTree {
  std::vector<std::string> links;  // file order
  std::vector<UrdfJoint> joints;   // file order
  const UrdfJoint* joint(const std::string& name) const {
    for (const UrdfJoint& j : joints) {
      if (j.name == name) return &j;
    }
    return nullptr;
  }
  std::string root() const {
    std::set<std::string> children;
    for (const UrdfJoint& j : joints) children.insert(j.child);
    for (const std::string& l : links) {
      if (children.count(l) == 0) return l;
    }
    return "";
  }
  // Active joints depth-first from the root, children in file order.
  std::vector<std::string> depth_first_active() const {
    std::vector<std::string> out;
    walk(root(), &out);
    return out;
  }
  void walk(const std::string& link, std::vector<std::string>* out) const {
    for (const UrdfJoint& j : joints) {
      if (j.parent != link) continue;
      if (j.active()) out->push_back(j.name);
      walk(j.child, out);
    }
  }
  // Position of joint `name` as a function of the active joints' values (mimic chains followed).
  double position(const std::string& name, const std::map<std::string, double>& active) const {
    const UrdfJoint* j = joint(name);
    if (j->mimic.empty()) return active.at(name);
    return j->multiplier * position(j->mimic, active) + j->offset;
  }
  std::string mimic_leader(const std::string& name) const {
    const UrdfJoint* j = joint(name);
    return j->mimic.empty() ? name : mimic_leader(j->mimic);
  }
  // Longest sum of joint offsets from the root to a link, prismatic ranges included (m): a bound
  // on the coordinates met during forward kinematics.
  double reach() const { return reach_from(root()); }
  double reach_from(const std::string& link) const {
    double best = 0.0;
    for (const UrdfJoint& j : joints) {
      if (j.parent != link) continue;
      double step = j.xyz.norm();
      if (j.type == "prismatic") step += std::max(std::abs(j.lower), std::abs(j.upper));
      best = std::max(best, step + reach_from(j.child));
    }
    return best;
  }
};

UrdfTree parse_urdf_tree(const std::string& xml) {
  UrdfTree out;
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.Parse(xml.c_str(), xml.size()), tinyxml2::XML_SUCCESS);
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  EXPECT_NE(robot, nullptr);
  if (robot == nullptr) return out;
  for (const tinyxml2::XMLElement* l = robot->FirstChildElement("link"); l != nullptr;
       l = l->NextSiblingElement("link")) {
    out.links.emplace_back(l->Attribute("name"));
  }
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement("joint"); e != nullptr;
       e = e->NextSiblingElement("joint")) {
    UrdfJoint j;
    j.name = e->Attribute("name");
    j.type = e->Attribute("type");
    j.parent = e->FirstChildElement("parent")->Attribute("link");
    j.child = e->FirstChildElement("child")->Attribute("link");
    if (const tinyxml2::XMLElement* o = e->FirstChildElement("origin")) {
      j.xyz = parse_vector(o->Attribute("xyz"), Eigen::Vector3d::Zero());
    }
    if (const tinyxml2::XMLElement* a = e->FirstChildElement("axis")) {
      j.axis = parse_vector(a->Attribute("xyz"), Eigen::Vector3d::UnitX());
    }
    if (const tinyxml2::XMLElement* lim = e->FirstChildElement("limit")) {
      j.has_limit = true;
      j.lower = parse_double(lim->Attribute("lower"), 0.0);
      j.upper = parse_double(lim->Attribute("upper"), 0.0);
    }
    if (const tinyxml2::XMLElement* m = e->FirstChildElement("mimic")) {
      j.mimic = m->Attribute("joint");
      j.multiplier = parse_double(m->Attribute("multiplier"), 1.0);
      j.offset = parse_double(m->Attribute("offset"), 0.0);
    }
    out.joints.push_back(j);
  }
  return out;
}

// ------------------------------------------------------------------------------------------
// Forward kinematics against KDL.

struct FkComparison {
  double max_rotation_error = 0.0;
  double max_translation_error = 0.0;
  std::string worst_link;
  double reach = 0.0;
  double ns_per_call = 0.0;
  int configurations = 0;
  double max_block_rotation_error = 0.0;  // compute_link_poses_block, every SIMD target
  double max_block_translation_error = 0.0;
  std::string block_targets;  // the targets run
};

// Random configurations (uniform within the URDF's limits, continuous joints in [-pi, pi]),
// evaluated by RobotModel and by KDL (which gets every joint's position, mimic joints computed
// here from the URDF).
FkComparison compare_with_kdl(const std::string& xml, const RobotModel& model, int configurations,
                              std::uint64_t seed) {
  FkComparison out;
  const UrdfTree urdf = parse_urdf_tree(xml);
  KDL::Tree tree;
  EXPECT_TRUE(kdl_parser::treeFromString(xml, tree));
  KDL::TreeFkSolverPos_recursive solver(tree);
  // KDL's q index of each non-fixed joint, by joint name.
  std::map<std::string, unsigned> kdl_index;
  for (const auto& [segment_name, element] : tree.getSegments()) {
    const KDL::Joint& joint = GetTreeElementSegment(element).getJoint();
    if (joint.getType() == KDL::Joint::None) continue;
    kdl_index[joint.getName()] = GetTreeElementQNr(element);
  }
  EXPECT_EQ(kdl_index.size(), tree.getNrOfJoints());
  std::size_t movable = 0;
  for (const UrdfJoint& j : urdf.joints) movable += j.movable() ? 1 : 0;
  EXPECT_EQ(kdl_index.size(), movable);
  EXPECT_EQ(tree.getNrOfSegments() + 1, model.links().size());  // KDL's root is no segment

  const std::vector<std::string> names = model.variable_names();
  std::mt19937_64 rng(seed);
  const double pi = std::acos(-1.0);
  std::vector<Eigen::VectorXd> qs;
  std::vector<KDL::JntArray> kdl_qs;
  for (int c = 0; c < configurations; ++c) {
    std::map<std::string, double> active;
    for (const UrdfJoint& j : urdf.joints) {
      if (!j.active()) continue;
      const double lo = j.type == "continuous" ? -pi : j.lower;
      const double hi = j.type == "continuous" ? pi : j.upper;
      active[j.name] = std::uniform_real_distribution<double>(lo, hi)(rng);
    }
    Eigen::VectorXd q(model.variable_count());
    for (int i = 0; i < model.variable_count(); ++i) {
      q[i] = active.at(names[static_cast<std::size_t>(i)]);
    }
    KDL::JntArray kq(tree.getNrOfJoints());
    for (const auto& [name, index] : kdl_index) kq(index) = urdf.position(name, active);
    qs.push_back(q);
    kdl_qs.push_back(kq);
  }

  std::vector<Eigen::Isometry3d> poses;
  for (int c = 0; c < configurations; ++c) {
    model.compute_link_poses(qs[static_cast<std::size_t>(c)], poses);
    for (std::size_t l = 0; l < model.links().size(); ++l) {
      const std::string& name = model.links()[l].name;
      KDL::Frame f;
      if (solver.JntToCart(kdl_qs[static_cast<std::size_t>(c)], f, name) < 0) {
        ADD_FAILURE() << "KDL cannot evaluate link " << name;
        return out;
      }
      double rot = 0.0, trans = 0.0;
      for (int r = 0; r < 3; ++r) {
        trans = std::max(trans, std::abs(f.p(r) - poses[l].translation()[r]));
        for (int k = 0; k < 3; ++k) {
          rot = std::max(rot, std::abs(f.M(r, k) - poses[l].linear()(r, k)));
        }
      }
      if (rot > out.max_rotation_error || trans > out.max_translation_error) out.worst_link = name;
      out.max_rotation_error = std::max(out.max_rotation_error, rot);
      out.max_translation_error = std::max(out.max_translation_error, trans);
      EXPECT_EQ(poses[l].matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1));
    }
  }
  out.configurations = configurations;
  out.reach = urdf.reach();

  // The SIMD block evaluation on every SIMD target Highway compiled that this CPU runs (each
  // forced in turn: a CPU without AVX2 or AVX-512 takes one of the narrower ones), blocks of
  // 1 to kPoseBlockLanes configurations, each lane against KDL.
  LinkPoseBlock block;
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    out.block_targets +=
        std::string(out.block_targets.empty() ? "" : " ") + hwy::TargetName(target);
    for (int c = 0; c < configurations;) {
      const int count = std::min(configurations - c, 1 + c % kPoseBlockLanes);
      // The columns of a matrix: consecutive configurations `stride` values apart.
      Eigen::MatrixXd columns(model.variable_count(), count);
      for (int k = 0; k < count; ++k) columns.col(k) = qs[static_cast<std::size_t>(c + k)];
      model.compute_link_poses_block(columns.data(), columns.rows(), count, block);
      for (int k = 0; k < std::min(count + 1, kPoseBlockLanes); ++k) {  // and one repeat
        const int config = c + std::min(k, count - 1);  // lanes past count repeat the last
        for (std::size_t l = 0; l < model.links().size(); ++l) {
          KDL::Frame f;
          solver.JntToCart(kdl_qs[static_cast<std::size_t>(config)], f, model.links()[l].name);
          const Eigen::Isometry3d p = block.pose(static_cast<int>(l), k);
          for (int r = 0; r < 3; ++r) {
            out.max_block_translation_error =
                std::max(out.max_block_translation_error, std::abs(f.p(r) - p.translation()[r]));
            for (int m = 0; m < 3; ++m) {
              out.max_block_rotation_error =
                  std::max(out.max_block_rotation_error, std::abs(f.M(r, m) - p.linear()(r, m)));
            }
          }
        }
      }
      c += count;
    }
  }
  hwy::SetSupportedTargetsForTest(0);

  // Speed of the unchecked evaluation: the best of 5 rounds (the machine may be busy).
  using Clock = std::chrono::steady_clock;
  const int repeats = std::max(1, 5000 / configurations);
  double checksum = 0.0;
  out.ns_per_call = INFINITY;
  for (int round = 0; round < 5; ++round) {
    const auto t0 = Clock::now();
    for (int r = 0; r < repeats; ++r) {
      for (const Eigen::VectorXd& q : qs) {
        model.compute_link_poses_unchecked(q.data(), poses.data());
        checksum += poses.back().translation().x();
      }
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    out.ns_per_call =
        std::min(out.ns_per_call, seconds * 1e9 / (static_cast<double>(repeats) * configurations));
  }
  EXPECT_TRUE(std::isfinite(checksum));
  return out;
}

void expect_fk_matches_kdl(const std::string& id, const std::string& xml, const RobotModel& model,
                           int configurations) {
  const FkComparison c = compare_with_kdl(xml, model, configurations, 20240601);
  // Absolute 1e-12 for rotation entries and for translations in metres: the robots reach up
  // to 2.5 m, and the errors met are below 1e-15 (a tolerance scaled by the reach is not needed).
  const double translation_tolerance = 1e-12;
  EXPECT_LE(c.max_rotation_error, 1e-12) << "worst link " << c.worst_link;
  EXPECT_LE(c.max_translation_error, translation_tolerance) << "worst link " << c.worst_link;
  EXPECT_LE(c.max_block_rotation_error, 1e-12) << "SIMD targets " << c.block_targets;
  EXPECT_LE(c.max_block_translation_error, translation_tolerance)
      << "SIMD targets " << c.block_targets;
  EXPECT_FALSE(c.block_targets.empty());
  std::cout << "[          ] " << id << ": " << model.links().size() << " links, "
            << model.variable_count() << " variables, reach " << c.reach << " m; over "
            << c.configurations << " configurations max |dR| " << c.max_rotation_error
            << ", max |dt| " << c.max_translation_error << " m (tolerance " << translation_tolerance
            << "); FK " << c.ns_per_call << " ns/call; blocks on SIMD targets " << c.block_targets
            << ": max |dR| " << c.max_block_rotation_error << ", max |dt| "
            << c.max_block_translation_error << " m\n";
}

class RobotFk : public testing::TestWithParam<std::string> {};

TEST_P(RobotFk, LinkPosesMatchKdlOnAThousandRandomConfigurations) {
  HULLCHECK_GET_ROBOT_OR_SKIP(robot);
  const RobotModel model = RobotModel::from_urdf_file(robot.urdf);
  expect_fk_matches_kdl(robot.id, read_text(robot.urdf), model, 1000);
}

INSTANTIATE_TEST_SUITE_P(AllRobots, RobotFk, testing::ValuesIn(robot_ids()), robot_name_for_test);

// A synthetic tree with what the real robots lack: branches declared out of order, a fixed joint
// between movable ones, off-axis and negative axes, a prismatic joint along a slanted axis, a
// chain of mimics with multipliers and offsets, a mimic of a continuous joint.
const char* const kSyntheticUrdf = R"(<?xml version="1.0"?>
<robot name="synthetic">
  <link name="root"/>
  <link name="a1"/><link name="a2"/><link name="a3"/><link name="a4"/><link name="a5"/>
  <link name="b1"/><link name="b2"/><link name="b3"/><link name="b4"/>
  <link name="c1"/>
  <joint name="zb_shoulder" type="revolute">
    <parent link="root"/><child link="b1"/>
    <origin xyz="0.1 -0.2 0.3" rpy="0.4 -0.5 0.6"/>
    <axis xyz="1 1 0"/>
    <limit lower="-2" upper="2.5" effort="1" velocity="1"/>
  </joint>
  <joint name="za_fixed" type="fixed">
    <parent link="b1"/><child link="b2"/>
    <origin xyz="0 0.3 0" rpy="1.2 0 -0.3"/>
  </joint>
  <joint name="zc_slide" type="prismatic">
    <parent link="b2"/><child link="b3"/>
    <origin xyz="0.05 0 0.1" rpy="0 0.7 0"/>
    <axis xyz="0.3 -0.4 1.2"/>
    <limit lower="-0.2" upper="0.4" effort="1" velocity="1"/>
  </joint>
  <joint name="zd_follow_slide" type="prismatic">
    <parent link="b3"/><child link="b4"/>
    <origin xyz="0 0 0.05"/>
    <axis xyz="0 -1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="zc_slide" multiplier="-1.5" offset="0.01"/>
  </joint>
  <joint name="a_base" type="continuous">
    <parent link="root"/><child link="a1"/>
    <origin xyz="0 0 0.2" rpy="0 0 0"/>
    <axis xyz="0 0 -1"/>
  </joint>
  <joint name="a_elbow" type="revolute">
    <parent link="a1"/><child link="a2"/>
    <origin xyz="0.3 0 0" rpy="0 0 0.3"/>
    <axis xyz="-1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="a_mimic1" type="revolute">
    <parent link="a2"/><child link="a3"/>
    <origin xyz="0 0.2 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
    <mimic joint="a_elbow" multiplier="0.5" offset="0.25"/>
  </joint>
  <joint name="a_mimic2" type="continuous">
    <parent link="a3"/><child link="a4"/>
    <origin xyz="0 0 0.1" rpy="0.1 0.2 0.3"/>
    <axis xyz="0.2 0.3 0.4"/>
    <mimic joint="a_mimic1" multiplier="-2" offset="-0.1"/>
  </joint>
  <joint name="a_wrist" type="continuous">
    <parent link="a4"/><child link="a5"/>
    <origin xyz="0.01 0.02 0.03"/>
    <axis xyz="0 0 1"/>
  </joint>
  <joint name="c_follow_base" type="revolute">
    <parent link="root"/><child link="c1"/>
    <origin xyz="-0.4 0 0" rpy="3.0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-4" upper="4" effort="1" velocity="1"/>
    <mimic joint="a_base" multiplier="1" offset="0.5"/>
  </joint>
</robot>
)";

TEST(RobotFk, SyntheticTreeMatchesKdl) {
  const RobotModel model = RobotModel::from_urdf_string(kSyntheticUrdf, ".");
  EXPECT_EQ(model.variable_names(),
            (std::vector<std::string>{"zb_shoulder", "zc_slide", "a_base", "a_elbow", "a_wrist"}));
  expect_fk_matches_kdl("synthetic", kSyntheticUrdf, model, 1000);
}

// Continuous joints accept values up to +-RobotModel::kMaxContinuousValue (1e6 rad); Highway
// documents its sine and cosine as accurate on +-39000 rad only, so the block evaluation
// reduces angles first (the Highway measured here is in fact accurate up to 3e6 rad, so this
// guards the reduction and a Highway that keeps to its documented range). Every SIMD target
// against the scalar evaluation (libm's exact reduction), both rotation paths (about a frame
// axis, and Rodrigues about a general one).
TEST(RobotFk, BlockReducesLargeContinuousAngles) {
  const char* urdf = R"(<robot name="spinner">
  <link name="base"/><link name="a"/><link name="b"/>
  <joint name="spin" type="continuous">
    <parent link="base"/><child link="a"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="tilt" type="continuous">
    <parent link="a"/><child link="b"/><origin xyz="0.5 0 0"/><axis xyz="0.48 0.6 0.64"/>
  </joint>
</robot>)";
  const RobotModel model = RobotModel::from_urdf_string(urdf, ".");
  const double values[] = {0.3,   39000.5,  -39001.2, 1e5 + 0.1, -5e5 - 2.0,
                           7.7e5, 999999.9, -1e6,     1e6,       123456.789};
  constexpr int kCount = sizeof(values) / sizeof(values[0]);
  Eigen::MatrixXd columns(model.variable_count(), kCount);
  for (int k = 0; k < kCount; ++k) {
    columns.col(k).setConstant(values[k]);
    columns(1, k) = values[kCount - 1 - k];
  }
  std::vector<Eigen::Isometry3d> poses;
  LinkPoseBlock block;
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    for (int first = 0; first < kCount; first += kPoseBlockLanes) {
      const int count = std::min(kPoseBlockLanes, kCount - first);
      model.compute_link_poses_block(columns.col(first).data(), columns.rows(), count, block);
      for (int k = 0; k < count; ++k) {
        model.compute_link_poses(columns.col(first + k), poses);
        for (std::size_t l = 0; l < poses.size(); ++l) {
          const double error = (block.pose(static_cast<int>(l), k).matrix() - poses[l].matrix())
                                   .cwiseAbs()
                                   .maxCoeff();
          EXPECT_LE(error, 1e-12) << hwy::TargetName(target) << ", link " << l
                                  << ", q = " << columns.col(first + k).transpose();
        }
      }
    }
  }
  hwy::SetSupportedTargetsForTest(0);
}

// The block evaluation keeps a per-thread copy of a model's steps: models used in turn on one
// thread (and a model destroyed, another built in its place) each get their own.
TEST(RobotFk, BlockFollowsTheModelInUse) {
  const RobotModel arm = RobotModel::from_urdf_file(test::own_arm().urdf);
  LinkPoseBlock block;
  std::vector<Eigen::Isometry3d> poses;
  const auto check = [&](const RobotModel& model) {
    const Eigen::VectorXd q = Eigen::VectorXd::Constant(model.variable_count(), 0.3);
    model.compute_link_poses_block(q.data(), q.size(), 1, block);
    model.compute_link_poses(q, poses);
    ASSERT_EQ(block.values.size(), poses.size() * 12 * kPoseBlockLanes);
    for (std::size_t l = 0; l < poses.size(); ++l) {
      EXPECT_LE((block.pose(static_cast<int>(l), 0).matrix() - poses[l].matrix()).norm(), 1e-12)
          << "link " << l;
    }
  };
  for (int round = 0; round < 3; ++round) {
    const RobotModel synthetic = RobotModel::from_urdf_string(kSyntheticUrdf, ".");
    check(arm);
    check(synthetic);
  }
}

// Hand-computed poses of the own arm: its README gives the zero configuration (flange at
// z = 1.256 m, tcp at z = 1.371 m) and the layout makes a few others easy.
TEST(RobotFk, OwnArmKnownPoses) {
  const RobotModel model = RobotModel::from_urdf_file(test::own_arm().urdf);
  std::vector<Eigen::Isometry3d> poses;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.variable_count());
  model.compute_link_poses(q, poses);
  const auto at = [&](const char* link) {
    return poses[static_cast<std::size_t>(model.link_index(link))];
  };
  EXPECT_EQ(at("base_link").matrix(), Eigen::Matrix4d::Identity());
  EXPECT_LE((at("flange").translation() - Eigen::Vector3d(0, 0, 1.256)).norm(), 1e-12);
  EXPECT_LE((at("tcp").translation() - Eigen::Vector3d(0, 0, 1.371)).norm(), 1e-12);
  EXPECT_LE((at("link4").translation() - Eigen::Vector3d(0, 0, 0.74)).norm(), 1e-12);
  // Fingers 8 mm apart when closed, each moving 0.04 m outwards at most, symmetrically.
  q[model.variable_index("finger_joint1")] = 0.03;
  model.compute_link_poses(q, poses);
  const Eigen::Vector3d left = at("finger_left").translation();
  const Eigen::Vector3d right = at("finger_right").translation();
  EXPECT_NEAR((left - right).norm(), 0.008 + 2 * 0.03, 1e-12);
  EXPECT_LE((left + right - 2 * Eigen::Vector3d(0, 0, 1.256 + 0.075)).norm(), 1e-12);
  // joint1 turns everything above about the world z axis.
  q.setZero();
  q[model.variable_index("joint2")] = 0.5 * std::acos(-1.0);  // upper arm horizontal
  model.compute_link_poses(q, poses);
  const Eigen::Vector3d flat_flange = at("flange").translation();
  EXPECT_NEAR(flat_flange.z(), 0.34, 1e-12);
  EXPECT_NEAR(std::hypot(flat_flange.x(), flat_flange.y()), 1.256 - 0.34, 1e-12);
  q[model.variable_index("joint1")] = 0.3;
  model.compute_link_poses(q, poses);
  const Eigen::Vector3d turned = at("flange").translation();
  EXPECT_LE((turned - Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) * flat_flange).norm(),
            1e-12);
}

// ------------------------------------------------------------------------------------------
// Configuration order, mimic joints, limits, default configuration.

class RobotConfigOrder : public testing::TestWithParam<std::string> {};

TEST_P(RobotConfigOrder, DepthFirstFileOrderMimicsLimitsAndDefault) {
  HULLCHECK_GET_ROBOT_OR_SKIP(robot);
  const std::string xml = read_text(robot.urdf);
  const UrdfTree urdf = parse_urdf_tree(xml);
  const RobotModel model = RobotModel::from_urdf_file(robot.urdf);
  const std::vector<std::string> expected = urdf.depth_first_active();
  EXPECT_EQ(model.variable_names(), expected);
  ASSERT_EQ(model.variable_count(), static_cast<int>(expected.size()));
  const Eigen::VectorXd lower = model.lower_limits();
  const Eigen::VectorXd upper = model.upper_limits();
  const Eigen::VectorXd start = model.default_configuration();
  ASSERT_EQ(lower.size(), model.variable_count());
  ASSERT_EQ(upper.size(), model.variable_count());
  ASSERT_EQ(start.size(), model.variable_count());
  for (int i = 0; i < model.variable_count(); ++i) {
    const std::string& name = expected[static_cast<std::size_t>(i)];
    SCOPED_TRACE(name);
    EXPECT_EQ(model.variable_index(name), i);
    EXPECT_EQ(model.joint(model.variable_joint(i)).name, name);
    EXPECT_EQ(model.joint(model.variable_joint(i)).variable, i);
    const UrdfJoint& j = *urdf.joint(name);
    if (j.type == "continuous") {
      EXPECT_EQ(lower[i], -INFINITY);
      EXPECT_EQ(upper[i], INFINITY);
    } else {
      EXPECT_EQ(lower[i], j.lower);
      EXPECT_EQ(upper[i], j.upper);
    }
    EXPECT_GE(start[i], lower[i]);
    EXPECT_LE(start[i], upper[i]);
    // MoveIt's default: 0 when within the limits, else the middle of the range.
    EXPECT_EQ(start[i], lower[i] <= 0.0 && 0.0 <= upper[i] ? 0.0 : 0.5 * (lower[i] + upper[i]));
  }
  for (const UrdfJoint& j : urdf.joints) {
    SCOPED_TRACE(j.name);
    const Joint& joint = model.joint(model.joint_index(j.name));
    if (j.active()) continue;
    EXPECT_EQ(joint.variable, -1);
    EXPECT_EQ(model.variable_index(j.name), -1);
    if (!j.movable()) {
      EXPECT_EQ(joint.mimic_variable, -1);  // <mimic> on a fixed joint means nothing
      continue;
    }
    // A mimic: its position follows the chain's end.
    const std::string leader = urdf.mimic_leader(j.name);
    EXPECT_EQ(joint.mimic_variable, model.variable_index(leader));
    ASSERT_GE(joint.mimic_variable, 0);
    const std::map<std::string, double> zero = {{leader, 0.0}}, one = {{leader, 1.0}};
    EXPECT_NEAR(joint.mimic_offset, urdf.position(j.name, zero), 1e-15);
    EXPECT_NEAR(joint.mimic_multiplier, urdf.position(j.name, one) - urdf.position(j.name, zero),
                1e-15);
  }
  EXPECT_EQ(model.variable_index("no such joint"), -1);
  EXPECT_NO_THROW(model.check_configuration(start));
}

INSTANTIATE_TEST_SUITE_P(AllRobots, RobotConfigOrder, testing::ValuesIn(robot_ids()),
                         robot_name_for_test);

TEST(RobotConfigOrder, OwnArm) {
  const RobotModel model = RobotModel::from_urdf_file(test::own_arm().urdf);
  EXPECT_EQ(model.variable_names(),
            (std::vector<std::string>{"joint1", "joint2", "joint3", "joint4", "joint5", "joint6",
                                      "joint7", "finger_joint1"}));
  for (int i = 0; i < 7; ++i) EXPECT_EQ(model.variable_index("joint" + std::to_string(i + 1)), i);
  EXPECT_EQ(model.variable_index("finger_joint1"), 7);
  EXPECT_EQ(model.variable_index("finger_joint2"), -1);
  EXPECT_EQ(model.variable_index("flange_joint"), -1);
  EXPECT_EQ(model.variable_index("tcp_joint"), -1);
  EXPECT_EQ(model.variable_index("link1"), -1);  // a link, not a joint
  const Joint& f2 = model.joint(model.joint_index("finger_joint2"));
  EXPECT_EQ(f2.variable, -1);
  EXPECT_EQ(f2.mimic_variable, model.variable_index("finger_joint1"));
  EXPECT_EQ(f2.mimic_multiplier, 1.0);
  EXPECT_EQ(f2.mimic_offset, 0.0);
  EXPECT_EQ(model.joint(model.joint_index("finger_joint1")).mimic_variable, -1);

  const Eigen::VectorXd lo = model.lower_limits(), hi = model.upper_limits();
  const Eigen::VectorXd d = model.default_configuration();
  ASSERT_EQ(d.size(), 8);
  for (int i = 0; i < 8; ++i) {
    EXPECT_LE(lo[i], d[i]);
    EXPECT_LE(d[i], hi[i]);
    EXPECT_EQ(d[i], 0.0);  // every range holds 0
  }
  EXPECT_EQ(lo[0], -2.9671);
  EXPECT_EQ(hi[1], 2.0944);
  EXPECT_EQ(lo[6], -INFINITY);  // joint7 is continuous
  EXPECT_EQ(hi[6], INFINITY);
  EXPECT_EQ(lo[7], 0.0);
  EXPECT_EQ(hi[7], 0.04);
}

// Children in file order, not in name order (urdfdom keeps joints in a name-sorted map) and not
// in the order links are declared; ranges that exclude 0 default to their middle (MoveIt).
TEST(RobotConfigOrder, ChildrenInFileOrderAndDefaultClamped) {
  const std::string xml = R"(<robot name="order">
    <link name="z_root"/><link name="m"/><link name="b"/><link name="a"/><link name="c"/>
    <link name="d"/>
    <joint name="j_zeta" type="revolute"><parent link="z_root"/><child link="m"/>
      <limit lower="0.5" upper="1.5" effort="1" velocity="1"/></joint>
    <joint name="j_alpha" type="prismatic"><parent link="z_root"/><child link="a"/>
      <limit lower="-0.3" upper="-0.1" effort="1" velocity="1"/></joint>
    <joint name="j_mid" type="continuous"><parent link="m"/><child link="b"/></joint>
    <joint name="j_fixed" type="fixed"><parent link="a"/><child link="c"/></joint>
    <joint name="j_beta" type="revolute"><parent link="c"/><child link="d"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  </robot>)";
  const RobotModel model = RobotModel::from_urdf_string(xml, ".");
  const std::vector<std::string> expected = {"j_zeta", "j_mid", "j_alpha", "j_beta"};
  EXPECT_EQ(model.variable_names(), expected);
  EXPECT_EQ(parse_urdf_tree(xml).depth_first_active(), expected);
  EXPECT_EQ(model.default_configuration(), Eigen::Vector4d(1.0, 0.0, -0.2, 0.0));
  EXPECT_EQ(model.link(0).name, "z_root");
  EXPECT_EQ(model.link(0).parent_joint, -1);
  // Links: the root first, every parent before its children.
  for (const Joint& j : model.joints()) EXPECT_LT(j.parent_link, j.child_link);
  const Link& root = model.link(0);
  ASSERT_EQ(root.child_joints.size(), 2u);
  EXPECT_EQ(model.joint(root.child_joints[0]).name, "j_zeta");
  EXPECT_EQ(model.joint(root.child_joints[1]).name, "j_alpha");
}

// ------------------------------------------------------------------------------------------
// Allocation-free forward kinematics.

class RobotFkNoAlloc : public testing::TestWithParam<std::string> {};

TEST_P(RobotFkNoAlloc, PresizedVectorIsReusedAndUncheckedGivesTheSamePoses) {
  HULLCHECK_GET_ROBOT_OR_SKIP(robot);
  const RobotModel model = RobotModel::from_urdf_file(robot.urdf);
  const std::size_t n = model.links().size();
  std::vector<Eigen::Isometry3d> poses(n, Eigen::Isometry3d::Identity());
  const Eigen::Isometry3d* const data = poses.data();
  const std::size_t capacity = poses.capacity();
  std::vector<Eigen::Isometry3d> unchecked(n);
  std::mt19937_64 rng(99);
  const Eigen::VectorXd lo = model.lower_limits(), hi = model.upper_limits();
  for (int c = 0; c < 200; ++c) {
    Eigen::VectorXd q(model.variable_count());
    for (int i = 0; i < q.size(); ++i) {
      const double a = std::isfinite(lo[i]) ? lo[i] : -3.2, b = std::isfinite(hi[i]) ? hi[i] : 3.2;
      q[i] = std::uniform_real_distribution<double>(a, b)(rng);
    }
    model.compute_link_poses(q, poses);
    ASSERT_EQ(poses.data(), data);
    ASSERT_EQ(poses.size(), n);
    ASSERT_EQ(poses.capacity(), capacity);
    model.compute_link_poses_unchecked(q.data(), unchecked.data());
    for (std::size_t l = 0; l < n; ++l) {
      ASSERT_EQ(poses[l].matrix(), unchecked[l].matrix()) << model.links()[l].name;
    }
    // A configuration held in a segment of a larger vector (Eigen::Ref without a copy).
    Eigen::VectorXd padded(q.size() + 2);
    padded << 7.0, q, -7.0;
    model.compute_link_poses(padded.segment(1, q.size()), poses);
    ASSERT_EQ(poses.data(), data);
    for (std::size_t l = 0; l < n; ++l) ASSERT_EQ(poses[l].matrix(), unchecked[l].matrix());
  }
  // A vector of the wrong size is resized; then it is reused.
  std::vector<Eigen::Isometry3d> empty;
  model.compute_link_poses(model.default_configuration(), empty);
  EXPECT_EQ(empty.size(), n);
  std::vector<Eigen::Isometry3d> longer(n + 3);
  model.compute_link_poses(model.default_configuration(), longer);
  EXPECT_EQ(longer.size(), n);
}

INSTANTIATE_TEST_SUITE_P(AllRobots, RobotFkNoAlloc, testing::ValuesIn(robot_ids()),
                         robot_name_for_test);

}  // namespace
}  // namespace hullcheck
