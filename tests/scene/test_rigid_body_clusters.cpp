// Self clusters (src/scene/rigid_body_clusters.cpp): the hulls of rigid bodies (links joined by
// fixed joints) that check_motion tests before a cluster's self blocks.
//  - Every body's hull contains every shape of its links, padding included: support values
//    along many directions in the body's root frame, against each shape's own support placed
//    by forward kinematics at random configurations (a hull missing a shape, its margin, or a
//    fixed joint's offset fails); and it is not loose: over polytopes (meshes, boxes) it
//    touches them along every direction, over round shapes it stays within its prisms' bound.
//  - A hand-made arm whose tool is five links on fixed joints (sphere, boxes, cylinders), able
//    to fold onto its base: check_motion's accepted motions are free under FCL at dense
//    samples, its contacts are contacts. The MotionBenchMaker UR5's gripper (twelve links on
//    fixed joints) is covered by MotionCheckFcl.Ur5*.
//  - Lines (a self block moved by three joints, both links decomposed: one piece against the
//    other link's hull): two U-shaped links, one dipping into the other, against FCL densely.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "collision_checker_internals.hpp"
#include "fcl_checker.hpp"
#include "robot_test_support.hpp"
#include "scene_test_support.hpp"
#include "test_support.hpp"

namespace hullcheck {

// The checker's rigid bodies and clusters, for this test only (a friend of CollisionChecker).
struct RigidBodyTestAccess {
  static int clusters(const CollisionChecker& c) {
    return static_cast<int>(c.self_clusters_.size());
  }
  static int rigid_root(const CollisionChecker& c, int link) { return c.rigid_root(link); }
  // The rigid bodies of the checker's clusters: root link and hull.
  static std::vector<std::pair<int, const Shape*>> bodies(const CollisionChecker& c) {
    std::vector<std::pair<int, const Shape*>> out;
    for (const auto& b : c.bodies_) out.emplace_back(b.root, b.hull.get());
    return out;
  }
  // Self blocks check_motion may split into lines: both links decomposed (a hull holding
  // several pieces), more than two values moving them relative to each other.
  static int line_blocks(const CollisionChecker& c) {
    int count = 0;
    for (const auto& block : c.self_blocks_) {
      const auto& a = c.link_balls_[static_cast<std::size_t>(block.link_a)];
      const auto& b = c.link_balls_[static_cast<std::size_t>(block.link_b)];
      const auto shapes = [&](int link) {
        return c.shape_begin_[static_cast<std::size_t>(link) + 1] -
               c.shape_begin_[static_cast<std::size_t>(link)];
      };
      int keys[2];
      count += a.bound >= 0 && b.bound >= 0 && shapes(a.link) > 1 && shapes(b.link) > 1 &&
               c.relative_drivers(a.link, b.link, 2, keys) > 2;
    }
    return count;
  }
  static std::pair<Eigen::Vector3d, double> body_ball(const CollisionChecker& c, int body) {
    const auto& b = c.bodies_[static_cast<std::size_t>(body)];
    return {b.center, b.radius};
  }
};

namespace {

// An arm folding onto its base, its tool five links on fixed joints (none of them padded:
// FCL's oracle takes unpadded shapes).
const char* const kToolArm = R"(<robot name="tool_arm">
  <link name="base"><collision><origin xyz="0 0 0.05"/><geometry><box size="0.3 0.3 0.1"/>
    </geometry></collision></link>
  <link name="upper"><collision><origin xyz="0 0 0.25"/><geometry>
    <cylinder radius="0.04" length="0.4"/></geometry></collision></link>
  <link name="fore"><collision><origin xyz="0 0 0.18"/><geometry><box size="0.05 0.05 0.3"/>
    </geometry></collision></link>
  <link name="flange"><collision><origin xyz="0 0 0.02"/><geometry>
    <cylinder radius="0.035" length="0.04"/></geometry></collision></link>
  <link name="palm"><collision><geometry><sphere radius="0.045"/></geometry></collision></link>
  <link name="finger_l"><collision><origin xyz="0 0 0.04"/><geometry>
    <box size="0.015 0.02 0.08"/></geometry></collision></link>
  <link name="finger_r"><collision><origin xyz="0 0 0.04"/><geometry>
    <cylinder radius="0.008" length="0.08"/></geometry></collision></link>
  <link name="camera"><collision><geometry><box size="0.03 0.06 0.02"/></geometry>
    </collision></link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="fold" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="0 0 0.48"/><axis xyz="0 1 0"/>
    <limit lower="-2.9" upper="2.9" effort="1" velocity="1"/></joint>
  <joint name="wrist" type="revolute"><parent link="fore"/><child link="flange"/>
    <origin xyz="0 0 0.36"/><axis xyz="1 0 0"/>
    <limit lower="-2.9" upper="2.9" effort="1" velocity="1"/></joint>
  <joint name="palm_fix" type="fixed"><parent link="flange"/><child link="palm"/>
    <origin xyz="0 0 0.085"/></joint>
  <joint name="left_fix" type="fixed"><parent link="palm"/><child link="finger_l"/>
    <origin xyz="0.03 0 0.03" rpy="0 0.2 0"/></joint>
  <joint name="right_fix" type="fixed"><parent link="palm"/><child link="finger_r"/>
    <origin xyz="-0.03 0 0.03" rpy="0 -0.2 0"/></joint>
  <joint name="camera_fix" type="fixed"><parent link="flange"/><child link="camera"/>
    <origin xyz="0.05 0 0.02" rpy="0.3 0 0.5"/></joint>
</robot>)";

std::shared_ptr<const RobotModel> tool_arm() {
  return std::make_shared<const RobotModel>(
      RobotModel::from_urdf_string(kToolArm, ".", {}, "tool_arm.urdf"));
}

// Every pair checked except neighbours along the chain and the tool's links among themselves.
AllowedCollisionMatrix tool_arm_matrix(const RobotModel& model) {
  AllowedCollisionMatrix matrix(static_cast<int>(model.links().size()));
  const auto id = [&](const char* name) { return model.link_index(name); };
  matrix.allow(id("base"), id("upper"), CollisionAllowance::kAdjacent);
  matrix.allow(id("upper"), id("fore"), CollisionAllowance::kAdjacent);
  matrix.allow(id("fore"), id("flange"), CollisionAllowance::kAdjacent);
  const char* const tool[] = {"flange", "palm", "finger_l", "finger_r", "camera"};
  for (const char* a : tool) {
    for (const char* b : tool) {
      if (id(a) < id(b)) matrix.allow(id(a), id(b), CollisionAllowance::kAdjacent);
    }
  }
  for (const char* t : tool) {
    if (std::string(t) != "flange") matrix.allow(id("fore"), id(t), CollisionAllowance::kAdjacent);
  }
  return matrix;
}

// The largest extent of a round core (sphere, capsule, cylinder radius) among `model`'s shapes
// of the links rooted at `root`, m: what the prisms may add to the hull's reach.
double round_radius(const CollisionChecker& checker, const RobotModel& model, int root) {
  double r = 0.0;
  for (int l = 0; l < static_cast<int>(model.links().size()); ++l) {
    if (RigidBodyTestAccess::rigid_root(checker, l) != root) continue;
    for (const CollisionShape& cs : model.link(l).shapes) {
      const Shape::Geometry& g = cs.shape.geometry();
      if (const auto* s = std::get_if<Sphere>(&g)) r = std::max(r, s->radius);
      if (const auto* c = std::get_if<Cylinder>(&g)) r = std::max(r, c->radius);
      if (const auto* c = std::get_if<Capsule>(&g)) r = std::max(r, c->radius);
    }
  }
  return r;
}

struct HullStats {
  int bodies = 0;
  long checks = 0;
  double worst_excess = 0.0;  // largest (hull's support - the shapes' largest) over directions
};

// Every body hull of `checker` against the shapes of its links, along `directions` random
// directions at `configurations` random configurations.
void check_body_hulls(const CollisionChecker& checker, int configurations, int directions,
                      HullStats* stats) {
  const RobotModel& model = checker.model();
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Isometry3d> poses;
  const auto bodies = RigidBodyTestAccess::bodies(checker);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto [root, hull] = bodies[b];
    const double round = round_radius(checker, model, root);
    const auto [center, radius] = RigidBodyTestAccess::body_ball(checker, static_cast<int>(b));
    ++stats->bodies;
    for (int k = 0; k < configurations; ++k) {
      model.compute_link_poses(test::random_configuration(model, rng), poses);
      const Eigen::Isometry3d to_root = poses[static_cast<std::size_t>(root)].inverse();
      for (int d = 0; d < directions; ++d) {
        const Eigen::Vector3d u =
            Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
        const double hull_reach = u.dot(hull->support(u));
        // The body's ball holds its hull.
        EXPECT_GE(u.dot(center) + radius, hull_reach - 1e-9) << model.link(root).name;
        double shapes_reach = -std::numeric_limits<double>::infinity();
        for (int l = 0; l < static_cast<int>(model.links().size()); ++l) {
          if (RigidBodyTestAccess::rigid_root(checker, l) != root) continue;
          for (const CollisionShape& cs : model.link(l).shapes) {
            const Eigen::Isometry3d place =
                to_root * poses[static_cast<std::size_t>(l)] * cs.origin;
            const Eigen::Vector3d p = place * cs.shape.support(place.linear().transpose() * u);
            const double reach = u.dot(p);
            EXPECT_LE(reach, hull_reach + 1e-9)
                << "the hull of " << model.link(root).name << "'s body misses a shape of "
                << model.link(l).name << " along " << u.transpose();
            shapes_reach = std::max(shapes_reach, reach);
            ++stats->checks;
          }
        }
        const double excess = hull_reach - shapes_reach;
        // Polytopes: the hull's support is theirs; round cores: within their prisms' bound
        // (a 12-sided prism whose ends reach past a sphere's pole by its radius).
        EXPECT_LE(excess, 0.45 * round + 1e-9)
            << model.link(root).name << " along " << u.transpose();
        stats->worst_excess = std::max(stats->worst_excess, excess);
      }
    }
  }
}

TEST(RigidBodyClusters, BodyHullsHoldTheirLinksShapesOnTheRobots) {
  HullStats stats;
  for (const test::RobotFile& robot : test::all_robots()) {
    SCOPED_TRACE(robot.urdf);
    const auto model = test::cached_model(robot.urdf);
    const AllowedCollisionMatrix matrix =
        robot.srdf.empty() ? AllowedCollisionMatrix(static_cast<int>(model->links().size()))
                           : AllowedCollisionMatrix::from_srdf(*model, read_srdf_file(robot.srdf));
    const CollisionChecker checker(model, matrix);
    check_body_hulls(checker, 3, 60, &stats);
  }
  std::printf("[ hulls    ] %d bodies, %ld shape supports checked, largest excess %.2e m\n",
              stats.bodies, stats.checks, stats.worst_excess);
}

TEST(RigidBodyClusters, PaddedToolHullHoldsItsShapes) {
  auto model = std::make_shared<RobotModel>(
      RobotModel::from_urdf_string(kToolArm, ".", {}, "tool_arm.urdf"));
  model->set_default_padding(0.004);
  model->set_link_padding("finger_r", 0.012);  // the largest margin must grow the whole hull
  const CollisionChecker checker(model, tool_arm_matrix(*model));
  ASSERT_EQ(RigidBodyTestAccess::clusters(checker), 2);  // the tool with the base, and the upper
  HullStats stats;
  check_body_hulls(checker, 4, 400, &stats);
  EXPECT_EQ(stats.bodies, 3);
}

// Random motions from valid states: accepted ones free at dense FCL samples, contacts within
// min_clearance + resolution of touching; at least a tenth of each.
void dense_fcl_check(const std::shared_ptr<const RobotModel>& model,
                     const AllowedCollisionMatrix& matrix, const PlanningScene& scene,
                     const CollisionChecker& checker, int motions, const char* tag) {
  test::FclChecker fcl(*model, matrix, scene);
  std::vector<Eigen::Isometry3d> poses;
  const auto fcl_free = [&](const Eigen::VectorXd& q) {
    model->compute_link_poses(q, poses);
    fcl.set_link_poses(poses);
    return !fcl.in_collision();
  };
  const MotionCheckOptions options;
  std::mt19937_64 rng(17);
  int accepted = 0, contacts = 0;
  constexpr int kDense = 400;
  for (int k = 0; k < motions; ++k) {
    Eigen::VectorXd q0, q1;
    do {
      q0 = test::random_configuration(*model, rng);
    } while (!checker.is_valid(q0));
    q1 = test::random_configuration(*model, rng);
    const MotionCheckResult r = checker.check_motion(q0, q1, options);
    const auto at = [&](double t) { return Eigen::VectorXd(q0 + t * (q1 - q0)); };
    for (int i = 0; i <= kDense; ++i) {
      const double t = r.last_free * i / kDense;
      EXPECT_TRUE(fcl_free(at(t)))
          << "motion " << k << " collides at t = " << t << " <= last_free " << r.last_free;
    }
    if (r.free()) {
      ++accepted;
      continue;
    }
    ASSERT_NE(r.verdict, MotionVerdict::kStateBudget) << "motion " << k;
    ++contacts;
    model->compute_link_poses(at(r.contact), poses);
    fcl.set_link_poses(poses);
    const test::FclDistance d = fcl.min_distance();
    EXPECT_LE(d.collision ? 0.0 : d.distance, options.min_clearance + options.resolution + 1e-6)
        << "motion " << k;
  }
  std::printf("[ %-8s ] %d motions: %d accepted (free at %d FCL samples each), %d contact\n", tag,
              motions, accepted, kDense, contacts);
  EXPECT_GT(accepted, motions / 10);
  EXPECT_GT(contacts, motions / 10);
}

TEST(RigidBodyClusters, ToolArmMotionsAgreeWithDenseFcl) {
  const auto model = tool_arm();
  const AllowedCollisionMatrix matrix = tool_arm_matrix(*model);
  PlanningScene scene;  // a post beside the arm, to mix obstacle contacts with self ones
  scene.obstacles.push_back(Obstacle{"post", "post", Shape(Box(0.12, 0.12, 1.0)),
                                     Eigen::Isometry3d(Eigen::Translation3d(0.3, 0.15, 0.5)),
                                     "box"});
  const CollisionChecker checker(model, matrix, scene);
  ASSERT_EQ(RigidBodyTestAccess::clusters(checker), 2);
  dense_fcl_check(model, matrix, scene, checker, test::sample_count(400), "tool arm");
}

// A U-shaped prism (the polygon below extruded along z by `height`), as an OBJ file: concave,
// so loading decomposes it into pieces.
void write_u_prism(const std::string& path, double unit, double height) {
  // Counter-clockwise, with the inner corners' projections on the bar's top edge as vertices
  // so that the caps' triangles meet edge to edge.
  const double xy[][2] = {{0, 0}, {3, 0}, {3, 1}, {3, 3}, {2, 3},
                          {2, 1}, {1, 1}, {1, 3}, {0, 3}, {0, 1}};
  const int n = 10;
  std::FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr) << path;
  for (double z : {0.0, height}) {
    for (const auto& p : xy) std::fprintf(f, "v %.6f %.6f %.6f\n", p[0] * unit, p[1] * unit, z);
  }
  // Caps: the bar (0 1 2 5 6 9 as a fan from 0, its top edge 9-6-5-2) and the two walls.
  const int cap[][3] = {{0, 1, 2}, {0, 2, 5}, {0, 5, 6}, {0, 6, 9},
                        {9, 6, 7}, {9, 7, 8}, {5, 2, 3}, {5, 3, 4}};
  for (const auto& t : cap) {
    std::fprintf(f, "f %d %d %d\n", t[0] + 1, t[2] + 1, t[1] + 1);              // bottom, facing -z
    std::fprintf(f, "f %d %d %d\n", t[0] + n + 1, t[1] + n + 1, t[2] + n + 1);  // top
  }
  for (int i = 0; i < n; ++i) {  // sides
    const int j = (i + 1) % n;
    std::fprintf(f, "f %d %d %d\nf %d %d %d\n", i + 1, j + 1, j + n + 1, i + 1, j + n + 1,
                 i + n + 1);
  }
  std::fclose(f);
}

TEST(RigidBodyClusters, ConcaveLinksSplitIntoLinesAgreeWithDenseFcl) {
  const test::TempDir dir("lines");
  write_u_prism((dir.path() / "u.obj").string(), 0.04, 0.04);
  const std::string urdf = R"(<robot name="cups">
  <link name="base"><collision><origin xyz="-0.06 -0.06 0"/><geometry><mesh filename="u.obj"/>
    </geometry></collision></link>
  <link name="post"><collision><origin xyz="0 0 0.06"/><geometry>
    <cylinder radius="0.012" length="0.12"/></geometry></collision></link>
  <link name="beam"><collision><origin xyz="0 0 0.06"/><geometry><box size="0.02 0.02 0.12"/>
    </geometry></collision></link>
  <link name="cup"><collision><origin xyz="-0.06 -0.06 0.01"/><geometry>
    <mesh filename="u.obj"/></geometry></collision></link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="post"/>
    <origin xyz="0.09 0 0.05"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="lift" type="revolute"><parent link="post"/><child link="beam"/>
    <origin xyz="0 0 0.12"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="twist" type="revolute"><parent link="beam"/><child link="cup"/>
    <origin xyz="0 0 0.12"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>)";
  const auto model = std::make_shared<const RobotModel>(
      RobotModel::from_urdf_string(urdf, dir.str(), {}, "cups.urdf"));
  AllowedCollisionMatrix matrix(static_cast<int>(model->links().size()));
  const auto id = [&](const char* name) { return model->link_index(name); };
  matrix.allow(id("base"), id("post"), CollisionAllowance::kAdjacent);
  matrix.allow(id("post"), id("beam"), CollisionAllowance::kAdjacent);
  matrix.allow(id("beam"), id("cup"), CollisionAllowance::kAdjacent);
  const CollisionChecker checker(model, matrix);
  ASSERT_GT(model->link(id("cup")).shapes.size(), 1u) << "the U was not decomposed";
  ASSERT_EQ(RigidBodyTestAccess::line_blocks(checker), 1);  // base / cup
  dense_fcl_check(model, matrix, PlanningScene{}, checker, test::sample_count(400), "cups");
}

}  // namespace
}  // namespace hullcheck
