// Planning scenes: MotionBenchMaker scenes and requests against an independent
// yaml-cpp reading composed by hand, constructed MoveIt YAML (every primitive, meshes, robot-link
// frames posed by KDL, map-style poses, multi-primitive objects, allowed-collision entries),
// error messages, and URDF environments placed where KDL's forward kinematics says.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <initializer_list>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/tree.hpp>
#include <kdl/treefksolverpos_recursive.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "scene_test_support.hpp"

namespace hullcheck {
namespace {

// ------------------------------------------------------------------------------------------
// Independent helpers: rotation from [x, y, z, w] written out, KDL forward kinematics.

// Rotation of the unit quaternion (x, y, z, w) (normalised here), by the textbook formula.
Eigen::Matrix3d rotation_xyzw(double x, double y, double z, double w) {
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  x /= n;
  y /= n;
  z /= n;
  w /= n;
  Eigen::Matrix3d r;
  r << 1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),  //
      2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),   //
      2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y);
  return r;
}

// A pose read from MBM YAML by hand: position [x y z], orientation [x y z w].
Eigen::Isometry3d yaml_pose(const YAML::Node& n) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  if (!n) return p;
  const YAML::Node pos = n["position"];
  const YAML::Node ori = n["orientation"];
  p.translation() << pos[0].as<double>(), pos[1].as<double>(), pos[2].as<double>();
  p.linear() = rotation_xyzw(ori[0].as<double>(), ori[1].as<double>(), ori[2].as<double>(),
                             ori[3].as<double>());
  return p;
}

double pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

// Link poses by KDL (kdl_parser's tree of the URDF file), joints by name (others 0).
class KdlPoses {
 public:
  explicit KdlPoses(const std::string& urdf) { EXPECT_TRUE(kdl_parser::treeFromFile(urdf, tree_)); }
  Eigen::Isometry3d operator()(const std::map<std::string, double>& q,
                               const std::string& link) const {
    if (tree_.getRootSegment()->first == link) return Eigen::Isometry3d::Identity();
    KDL::JntArray values(tree_.getNrOfJoints());
    for (const auto& [segment, element] : tree_.getSegments()) {
      const KDL::Joint& joint = GetTreeElementSegment(element).getJoint();
      if (joint.getType() == KDL::Joint::None) continue;
      const auto it = q.find(joint.getName());
      values(GetTreeElementQNr(element)) = it == q.end() ? 0.0 : it->second;
    }
    KDL::TreeFkSolverPos_recursive solver(tree_);
    KDL::Frame f;
    EXPECT_GE(solver.JntToCart(values, f, link), 0) << link;
    Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r) {
      out.translation()[r] = f.p(r);
      for (int c = 0; c < 3; ++c) out.linear()(r, c) = f.M(r, c);
    }
    return out;
  }

 private:
  KDL::Tree tree_;
};

std::shared_ptr<const RobotModel> own_model() { return test::cached_model(test::own_arm().urdf); }

// ------------------------------------------------------------------------------------------
// MotionBenchMaker scenes and requests.

// Scenes 1, 50 and 100 of every family: the obstacles (names, types, sizes, world poses), the
// allowed pairs and the robot state against yaml-cpp read here, poses composed by hand.
TEST(PlanningSceneMbm, ObstaclesMatchIndependentReading) {
  const auto robots = test::mbm_robots();
  if (robots.empty()) GTEST_SKIP() << "MotionBenchMaker data absent";
  int scenes = 0, obstacles = 0, with_object_pose = 0;
  for (const test::MbmRobot& robot : robots) {
    const auto model = test::cached_model(robot.urdf);
    for (const std::string& family : robot.families) {
      for (const int number : {1, 50, 100}) {
        const std::string path = test::mbm_file(robot, family, "scene", number);
        SCOPED_TRACE(path);
        const PlanningScene scene = read_planning_scene(path, *model);
        const YAML::Node root = YAML::LoadFile(path);
        const YAML::Node objects = root["world"]["collision_objects"];
        ASSERT_TRUE(objects.IsSequence());
        std::size_t k = 0;  // next obstacle
        for (const YAML::Node& o : objects) {
          const std::string id = o["id"].as<std::string>();
          SCOPED_TRACE(id);
          ASSERT_FALSE(o["header"] && o["header"]["frame_id"] &&
                       !o["header"]["frame_id"].as<std::string>().empty())
              << "MBM objects are in the root frame";
          const Eigen::Isometry3d object_pose = yaml_pose(o["pose"]);
          with_object_pose += o["pose"] ? 1 : 0;
          const YAML::Node prims = o["primitives"];
          const YAML::Node prim_poses = o["primitive_poses"];
          ASSERT_EQ(prims.size(), prim_poses.size());
          for (std::size_t i = 0; i < prims.size(); ++i, ++k) {
            ASSERT_LT(k, scene.obstacles.size());
            const Obstacle& ob = scene.obstacles[k];
            EXPECT_EQ(ob.name, prims.size() == 1 ? id : id + "/" + std::to_string(i));
            EXPECT_EQ(ob.object, id);
            const std::string type = prims[i]["type"].as<std::string>();
            EXPECT_EQ(ob.source, type);
            const YAML::Node dims = prims[i]["dimensions"];
            const Eigen::Isometry3d expected = object_pose * yaml_pose(prim_poses[i]);
            EXPECT_LE(pose_error(ob.pose, expected), 1e-12);
            EXPECT_EQ(ob.shape.margin(), 0.0);
            if (type == "box") {
              ASSERT_EQ(ob.shape.kind(), ShapeKind::kBox);
              const Box& box = std::get<Box>(ob.shape.geometry());
              ASSERT_EQ(dims.size(), 3u);
              for (int a = 0; a < 3; ++a) {
                EXPECT_DOUBLE_EQ(2.0 * box.half_extents[a],
                                 dims[static_cast<std::size_t>(a)].as<double>());
              }
            } else if (type == "cylinder") {
              ASSERT_EQ(ob.shape.kind(), ShapeKind::kCylinder);
              const Cylinder& c = std::get<Cylinder>(ob.shape.geometry());
              ASSERT_EQ(dims.size(), 2u);
              EXPECT_DOUBLE_EQ(2.0 * c.half_length, dims[0].as<double>());  // [height, radius]
              EXPECT_DOUBLE_EQ(c.radius, dims[1].as<double>());
            } else {
              ADD_FAILURE() << "unexpected MBM primitive " << type;
            }
            ++obstacles;
          }
        }
        EXPECT_EQ(scene.obstacles.size(), k);
        // Allowed pairs: the true entries of the matrix's upper triangle.
        std::set<std::pair<std::string, std::string>> expected_allowed, got_allowed;
        const YAML::Node acm = root["allowed_collision_matrix"];
        if (acm) {
          const YAML::Node names = acm["entry_names"];
          for (std::size_t i = 0; i < names.size(); ++i) {
            for (std::size_t j = i + 1; j < names.size(); ++j) {
              if (acm["entry_values"][i][j].as<bool>()) {
                expected_allowed.insert(
                    std::minmax(names[i].as<std::string>(), names[j].as<std::string>()));
              }
            }
          }
        }
        for (const auto& [a, b] : scene.allowed_pairs) got_allowed.insert(std::minmax(a, b));
        EXPECT_EQ(got_allowed, expected_allowed);
        EXPECT_FALSE(expected_allowed.empty());
        // Robot state as listed.
        const YAML::Node js = root["robot_state"]["joint_state"];
        ASSERT_EQ(scene.robot_joint_values.size(), js["name"].size());
        for (std::size_t i = 0; i < js["name"].size(); ++i) {
          EXPECT_EQ(scene.robot_joint_values[i].first, js["name"][i].as<std::string>());
          EXPECT_EQ(scene.robot_joint_values[i].second, js["position"][i].as<double>());
        }
        ++scenes;
      }
    }
  }
  EXPECT_GT(with_object_pose, 0) << "the sample should hold objects with a pose (ur5 table_pick)";
  std::printf("[ scenes   ] %d MBM scenes, %d obstacles (%d objects with a pose) as read by hand\n",
              scenes, obstacles, with_object_pose);
}

// Requests 1, 50 and 100 of every family: group, start (every joint the robot has as a
// variable) and goal values equal the YAML's.
TEST(PlanningSceneMbm, RequestsMatchYaml) {
  const auto robots = test::mbm_robots();
  if (robots.empty()) GTEST_SKIP() << "MotionBenchMaker data absent";
  int requests = 0;
  for (const test::MbmRobot& robot : robots) {
    const auto model = test::cached_model(robot.urdf);
    for (const std::string& family : robot.families) {
      for (const int number : {1, 50, 100}) {
        const std::string path = test::mbm_file(robot, family, "request", number);
        SCOPED_TRACE(path);
        const MotionPlanRequest request = read_motion_plan_request(path, *model);
        const YAML::Node root = YAML::LoadFile(path);
        EXPECT_EQ(request.group, root["group_name"].as<std::string>());
        EXPECT_EQ(request.allowed_planning_time, root["allowed_planning_time"].as<double>());
        ASSERT_EQ(request.start.size(), model->variable_count());
        ASSERT_EQ(request.goal.size(), model->variable_count());
        Eigen::VectorXd start = model->default_configuration();
        const YAML::Node js = root["start_state"]["joint_state"];
        int named = 0;
        for (std::size_t i = 0; i < js["name"].size(); ++i) {
          const int v = model->variable_index(js["name"][i].as<std::string>());
          if (v < 0) continue;
          start[v] = js["position"][i].as<double>();
          ++named;
        }
        EXPECT_GE(named, 6);
        for (int v = 0; v < model->variable_count(); ++v) EXPECT_EQ(request.start[v], start[v]);
        Eigen::VectorXd goal = start;
        std::vector<int> goal_variables;
        for (const YAML::Node& c : root["goal_constraints"][0]["joint_constraints"]) {
          const int v = model->variable_index(c["joint_name"].as<std::string>());
          ASSERT_GE(v, 0);
          goal[v] = c["position"].as<double>();
          goal_variables.push_back(v);
        }
        for (int v = 0; v < model->variable_count(); ++v) EXPECT_EQ(request.goal[v], goal[v]);
        std::vector<int> got = request.goal_variables;
        std::sort(got.begin(), got.end());
        std::sort(goal_variables.begin(), goal_variables.end());
        EXPECT_EQ(got, goal_variables);
        ++requests;
      }
    }
  }
  std::printf("[ requests ] %d MBM requests equal their YAML\n", requests);
}

// The MoveIt Panda (prismatic fingers, one a mimic) with an MBM request: the fingers' start
// value 0.065 lies beyond the limit 0.04 and is kept, not clamped.
TEST(PlanningSceneMbm, RequestStartNotClamped) {
  const auto robots = test::mbm_robots();
  const std::string urdf =
      test::shared_dir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf";
  if (robots.empty() || robots[0].id != "panda" || !std::filesystem::exists(urdf)) {
    GTEST_SKIP() << "Panda data absent";
  }
  const auto model = test::cached_model(urdf);
  const MotionPlanRequest request = read_motion_plan_request(
      test::mbm_file(robots[0], robots[0].families[0], "request", 1), *model);
  const int finger = model->variable_index("panda_finger_joint1");
  ASSERT_GE(finger, 0);
  EXPECT_EQ(request.start[finger], 0.065);
  EXPECT_GT(request.start[finger], model->upper_limits()[finger]);
  EXPECT_EQ(model->variable_index("panda_finger_joint2"), -1);  // mimic: follows
}

// ------------------------------------------------------------------------------------------
// Constructed scenes for the own arm.

PlanningScene parse(const std::string& yaml) {
  return parse_planning_scene(yaml, *own_model(), "constructed.yaml");
}

TEST(PlanningSceneYaml, SphereBoxCylinderAndComposedPoses) {
  const PlanningScene scene = parse(R"(
name: primitives
world:
  collision_objects:
    - id: ball
      primitives:
        - type: sphere
          dimensions: [0.125]
      primitive_poses:
        - position: [0.5, -0.25, 0.75]
          orientation: [0, 0, 0, 1]
    - id: crate
      pose:
        position: [1.0, 2.0, 3.0]
        orientation: [0.0, 0.0, 0.3826834323650898, 0.9238795325112867]
      primitives:
        - type: box
          dimensions: [0.1, 0.2, 0.3]
      primitive_poses:
        - position: [0.1, 0.0, -0.2]
          orientation: [0.2705980500730985, 0.2705980500730985, 0.0, 0.9238795325112867]
    - id: can
      primitives:
        - type: cylinder
          dimensions: [0.4, 0.05]
      primitive_poses:
        - position: [0, 0, 0]
          orientation: [0, 0, 0, 1]
)");
  EXPECT_EQ(scene.name, "primitives");
  ASSERT_EQ(scene.obstacles.size(), 3u);
  const Obstacle& ball = scene.obstacles[0];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_EQ(ball.source, "sphere");
  ASSERT_EQ(ball.shape.kind(), ShapeKind::kSphere);
  EXPECT_EQ(std::get<Sphere>(ball.shape.geometry()).radius, 0.125);
  EXPECT_LE(pose_error(ball.pose, test::translation(0.5, -0.25, 0.75)), 1e-15);

  const Obstacle& crate = scene.obstacles[1];
  ASSERT_EQ(crate.shape.kind(), ShapeKind::kBox);
  EXPECT_LE((std::get<Box>(crate.shape.geometry()).half_extents - Eigen::Vector3d(0.05, 0.1, 0.15))
                .norm(),
            1e-15);
  // Object pose (45 deg about z at (1,2,3)) times the primitive pose.
  Eigen::Isometry3d object = test::translation(1, 2, 3);
  object.linear() = rotation_xyzw(0.0, 0.0, 0.3826834323650898, 0.9238795325112867);
  Eigen::Isometry3d primitive = test::translation(0.1, 0.0, -0.2);
  primitive.linear() =
      rotation_xyzw(0.2705980500730985, 0.2705980500730985, 0.0, 0.9238795325112867);
  EXPECT_LE(pose_error(crate.pose, object * primitive), 1e-12);
  // A point check of the composition: the primitive's origin in the world.
  const double h = std::sqrt(0.5);
  EXPECT_LE((crate.pose.translation() - Eigen::Vector3d(1 + 0.1 * h, 2 + 0.1 * h, 2.8)).norm(),
            1e-12);

  const Obstacle& can = scene.obstacles[2];
  ASSERT_EQ(can.shape.kind(), ShapeKind::kCylinder);
  EXPECT_EQ(std::get<Cylinder>(can.shape.geometry()).radius, 0.05);
  EXPECT_EQ(std::get<Cylinder>(can.shape.geometry()).half_length, 0.2);
}

// A cone [height, radius]: apex at +height/2 on z, base circle at -height/2. The hull must
// contain the true cone (apex and base circle) and exceed it by at most 0.13% of the radius.
TEST(PlanningSceneYaml, ConeHullContainsTheConeWithinTolerance) {
  const double height = 0.3, radius = 0.1;
  const PlanningScene scene = parse(R"(
world:
  collision_objects:
    - id: lampshade
      primitives:
        - type: cone
          dimensions: [0.3, 0.1]
      primitive_poses:
        - position: [0.2, 0.0, 1.0]
          orientation: [0, 0, 0, 1]
)");
  ASSERT_EQ(scene.obstacles.size(), 1u);
  const Obstacle& cone = scene.obstacles[0];
  EXPECT_EQ(cone.source, "cone");
  ASSERT_EQ(cone.shape.kind(), ShapeKind::kConvexHull);
  EXPECT_LE(pose_error(cone.pose, test::translation(0.2, 0.0, 1.0)), 1e-15);
  const ConvexHull& hull = std::get<ConvexHull>(cone.shape.geometry());
  ASSERT_EQ(hull.dimension(), 3);
  // Containment through the hull's facet planes (outward triangles).
  const auto outside = [&](const Eigen::Vector3d& p) {
    double worst = -INFINITY;
    for (const auto& t : hull.triangles()) {
      const Eigen::Vector3d& a = hull.vertices()[static_cast<std::size_t>(t[0])];
      const Eigen::Vector3d& b = hull.vertices()[static_cast<std::size_t>(t[1])];
      const Eigen::Vector3d& c = hull.vertices()[static_cast<std::size_t>(t[2])];
      const Eigen::Vector3d n = (b - a).cross(c - a);
      if (n.norm() < 1e-14) continue;
      worst = std::max(worst, n.normalized().dot(p - a));
    }
    return worst;
  };
  EXPECT_LE(outside(Eigen::Vector3d(0, 0, height / 2)), 1e-15);
  for (int i = 0; i < 720; ++i) {
    const double a = 2 * M_PI * i / 720.0 + 0.001;
    EXPECT_LE(outside(Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), -height / 2)),
              1e-15)
        << "base circle point at angle " << a;
  }
  // Support functions: hull >= true cone (contains it) and <= true cone + 0.13% radius.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  double worst_excess = 0.0;
  for (int i = 0; i < 5000; ++i) {
    Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    if (i < 64) d = Eigen::Vector3d(std::cos(i * 0.1), std::sin(i * 0.1), -0.1 * (i % 7));
    d.normalize();
    const double truth =
        std::max(d.z() * height / 2, -d.z() * height / 2 + radius * d.head<2>().norm());
    const double got = hull.support(d).dot(d);
    EXPECT_GE(got, truth - 1e-15);
    worst_excess = std::max(worst_excess, got - truth);
  }
  EXPECT_LE(worst_excess, 0.0013 * radius);
  EXPECT_GT(worst_excess, 0.0);  // a polygonal base: some excess exists
  // Nothing above the apex or below the base.
  for (const Eigen::Vector3d& v : hull.vertices()) {
    EXPECT_LE(v.z(), height / 2 + 1e-15);
    EXPECT_GE(v.z(), -height / 2 - 1e-15);
  }
}

// A mesh (vertices and triangles, positions as maps) becomes the convex hull of its vertices;
// orientations as maps too; numeric primitive types name the primitive in `source`.
TEST(PlanningSceneYaml, MeshAndMapStylePoses) {
  const PlanningScene scene = parse(R"(
world:
  collision_objects:
    - id: wedge
      meshes:
        - vertices:
            - {x: 0.0, y: 0.0, z: 0.0}
            - {x: 0.2, y: 0.0, z: 0.0}
            - {x: 0.0, y: 0.3, z: 0.0}
            - {x: 0.0, y: 0.0, z: 0.4}
            - {x: 0.05, y: 0.05, z: 0.05}
          triangles:
            - vertex_indices: [0, 2, 1]
            - vertex_indices: [0, 1, 3]
            - vertex_indices: [0, 3, 2]
            - vertex_indices: [1, 2, 3]
      mesh_poses:
        - position: {x: 1.5, y: -0.5, z: 0.25}
          orientation: {x: 0.0, y: 0.0, z: 0.7071067811865476, w: 0.7071067811865476}
    - id: numbered
      primitives:
        - type: 1
          dimensions: [0.1, 0.1, 0.1]
      primitive_poses:
        - position: {x: 1.0, z: 2.0}
)");
  ASSERT_EQ(scene.obstacles.size(), 2u);
  const Obstacle& wedge = scene.obstacles[0];
  EXPECT_EQ(wedge.source, "mesh");
  ASSERT_EQ(wedge.shape.kind(), ShapeKind::kConvexHull);
  const ConvexHull& hull = std::get<ConvexHull>(wedge.shape.geometry());
  EXPECT_EQ(hull.vertex_count(), 4u);  // the interior point is not a hull vertex
  Eigen::Isometry3d expected = test::translation(1.5, -0.5, 0.25);
  expected.linear() = rotation_xyzw(0, 0, std::sqrt(0.5), std::sqrt(0.5));
  EXPECT_LE(pose_error(wedge.pose, expected), 1e-15);
  // The tip (0, 0, 0.4) and (0.2, 0, 0) in the world: rotated 90 deg about z.
  EXPECT_LE((wedge.pose * Eigen::Vector3d(0.2, 0, 0) - Eigen::Vector3d(1.5, -0.3, 0.25)).norm(),
            1e-15);

  const Obstacle& numbered = scene.obstacles[1];
  ASSERT_EQ(numbered.shape.kind(), ShapeKind::kBox);
  EXPECT_EQ(numbered.source, "box") << "Obstacle::source names the primitive (box, sphere, ...)";
  EXPECT_LE(pose_error(numbered.pose, test::translation(1.0, 0.0, 2.0)), 1e-15);
}

// Several primitives (and meshes) in one object: named id/0, id/1, ..., object = id, each
// composed with the object's pose.
TEST(PlanningSceneYaml, MultiPrimitiveObjects) {
  const PlanningScene scene = parse(R"(
world:
  collision_objects:
    - id: shelf
      pose:
        position: [1, 0, 0]
        orientation: [0, 0, 1, 0]
      primitives:
        - type: box
          dimensions: [0.5, 0.5, 0.02]
        - type: box
          dimensions: [0.5, 0.5, 0.02]
        - type: cylinder
          dimensions: [1.0, 0.01]
      primitive_poses:
        - position: [0, 0, 0.2]
        - position: [0, 0, 0.6]
        - position: [0.2, 0.2, 0.5]
      meshes:
        - vertices: [[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]
          triangles: []
      mesh_poses:
        - position: [0.3, 0, 0]
    - id: single
      primitives:
        - type: sphere
          dimensions: [0.1]
      primitive_poses:
        - position: [0, 0, 0]
)");
  ASSERT_EQ(scene.obstacles.size(), 5u);
  const char* names[] = {"shelf/0", "shelf/1", "shelf/2", "shelf/3", "single"};
  const char* sources[] = {"box", "box", "cylinder", "mesh", "sphere"};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(scene.obstacles[i].name, names[i]);
    EXPECT_EQ(scene.obstacles[i].object, i < 4 ? "shelf" : "single");
    EXPECT_EQ(scene.obstacles[i].source, sources[i]);
  }
  // Rotated 180 deg about z at (1, 0, 0): local (0.2, 0.2, 0.5) -> (0.8, -0.2, 0.5).
  EXPECT_LE((scene.obstacles[2].pose.translation() - Eigen::Vector3d(0.8, -0.2, 0.5)).norm(),
            1e-15);
  EXPECT_LE((scene.obstacles[3].pose.translation() - Eigen::Vector3d(0.7, 0, 0)).norm(), 1e-15);
  EXPECT_LE((scene.obstacles[1].pose.linear() - rotation_xyzw(0, 0, 1, 0)).norm(), 1e-15);
}

// header.frame_id names a robot link: the object is posed by forward kinematics (here KDL's)
// at the scene's robot_state; the root link, "world", "/world" and "" are the model frame.
TEST(PlanningSceneYaml, RobotLinkFrames) {
  const std::string yaml = R"(
robot_state:
  joint_state:
    name: [joint1, joint2, joint3, joint4, joint5, joint6, joint7, virtual_joint_ignored]
    position: [0.3, -0.5, 0.7, 1.1, -0.4, 0.9, 2.5, 12.0]
world:
  collision_objects:
    - id: held
      header:
        frame_id: link6
      pose:
        position: [0.01, 0.02, 0.03]
        orientation: [0, 0.3826834323650898, 0, 0.9238795325112867]
      primitives:
        - type: box
          dimensions: [0.05, 0.05, 0.05]
      primitive_poses:
        - position: [0.0, 0.0, 0.1]
          orientation: [0, 0, 0, 1]
    - id: on_root
      header: {frame_id: base_link}
      primitives: [{type: sphere, dimensions: [0.1]}]
      primitive_poses: [{position: [1, 0, 0]}]
    - id: on_world
      header: {frame_id: world}
      primitives: [{type: sphere, dimensions: [0.1]}]
      primitive_poses: [{position: [0, 1, 0]}]
    - id: on_slash_world
      header: {frame_id: /world}
      primitives: [{type: sphere, dimensions: [0.1]}]
      primitive_poses: [{position: [0, 0, 1]}]
    - id: on_empty
      header: {frame_id: ""}
      primitives: [{type: sphere, dimensions: [0.1]}]
      primitive_poses: [{position: [1, 1, 0]}]
)";
  const PlanningScene scene = parse(yaml);
  ASSERT_EQ(scene.obstacles.size(), 5u);
  const std::map<std::string, double> q = {{"joint1", 0.3}, {"joint2", -0.5}, {"joint3", 0.7},
                                           {"joint4", 1.1}, {"joint5", -0.4}, {"joint6", 0.9},
                                           {"joint7", 2.5}};
  Eigen::Isometry3d object = test::translation(0.01, 0.02, 0.03);
  object.linear() = rotation_xyzw(0, 0.3826834323650898, 0, 0.9238795325112867);
  const KdlPoses kdl(test::own_arm().urdf);
  const Eigen::Isometry3d expected = kdl(q, "link6") * object * test::translation(0, 0, 0.1);
  EXPECT_LE(pose_error(scene.obstacles[0].pose, expected), 1e-12);
  EXPECT_GT(expected.translation().norm(), 0.3);  // far from the identity: a real check
  EXPECT_LE(pose_error(scene.obstacles[1].pose, test::translation(1, 0, 0)), 1e-15);
  EXPECT_LE(pose_error(scene.obstacles[2].pose, test::translation(0, 1, 0)), 1e-15);
  EXPECT_LE(pose_error(scene.obstacles[3].pose, test::translation(0, 0, 1)), 1e-15);
  EXPECT_LE(pose_error(scene.obstacles[4].pose, test::translation(1, 1, 0)), 1e-15);
  // robot_state is kept (all names, the robot's or not).
  ASSERT_EQ(scene.robot_joint_values.size(), 8u);
  EXPECT_EQ(scene.robot_joint_values[3], std::make_pair(std::string("joint4"), 1.1));

  // Without a robot_state: the default configuration (every joint 0 within its limits).
  const PlanningScene idle = parse(R"(
world:
  collision_objects:
    - id: held
      header: {frame_id: link6}
      primitives: [{type: sphere, dimensions: [0.1]}]
      primitive_poses: [{position: [0, 0, 0.1]}]
)");
  ASSERT_EQ(idle.obstacles.size(), 1u);
  EXPECT_LE(pose_error(idle.obstacles[0].pose, kdl({}, "link6") * test::translation(0, 0, 0.1)),
            1e-12);
}

TEST(PlanningSceneYaml, AllowedCollisionMatrixEntries) {
  const PlanningScene scene = parse(R"(
allowed_collision_matrix:
  entry_names: [link7, table, flange, wall]
  entry_values:
    - [false, true, false, true]
    - [true, false, false, false]
    - [false, false, false, true]
    - [true, false, true, false]
world:
  collision_objects:
    - id: table
      primitives: [{type: box, dimensions: [1, 1, 0.1]}]
      primitive_poses: [{position: [0, 0, -0.1]}]
)");
  std::set<std::pair<std::string, std::string>> got;
  for (const auto& [a, b] : scene.allowed_pairs) got.insert(std::minmax(a, b));
  const std::set<std::pair<std::string, std::string>> expected = {
      {"link7", "table"}, {"link7", "wall"}, {"flange", "wall"}};
  EXPECT_EQ(got, expected);
  // moveit_msgs/AllowedCollisionEntry rows: {enabled: [...]}.
  const PlanningScene entries = parse(R"(
allowed_collision_matrix:
  entry_names: [a, b]
  entry_values:
    - {enabled: [false, true]}
    - {enabled: [true, false]}
)");
  ASSERT_EQ(entries.allowed_pairs.size(), 1u);
  EXPECT_EQ(std::minmax(entries.allowed_pairs[0].first, entries.allowed_pairs[0].second),
            std::minmax(std::string("a"), std::string("b")));
}

// A quaternion off unit length by less than 1e-3 is normalised; more is an error (below).
TEST(PlanningSceneYaml, NearlyUnitQuaternionIsNormalised) {
  const PlanningScene scene = parse(R"(
world:
  collision_objects:
    - id: tilted
      primitives: [{type: box, dimensions: [0.1, 0.1, 0.1]}]
      primitive_poses:
        - position: [0, 0, 0]
          orientation: [0.0, 0.0, 0.38287, 0.92434]
)");
  ASSERT_EQ(scene.obstacles.size(), 1u);
  const Eigen::Matrix3d r = scene.obstacles[0].pose.linear();
  EXPECT_LE((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 1e-14);
  EXPECT_LE((r - rotation_xyzw(0.0, 0.0, 0.38287, 0.92434)).norm(), 1e-14);
}

// ------------------------------------------------------------------------------------------
// Errors: InputError, message naming the source, the object and the problem.

void expect_error(const std::string& yaml, std::initializer_list<const char*> parts) {
  try {
    parse(yaml);
    ADD_FAILURE() << "no error for:\n" << yaml;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const char* part : parts) {
      EXPECT_NE(msg.find(part), std::string::npos) << "'" << part << "' missing from: " << msg;
    }
  }
}

std::string one_object(const std::string& id, const std::string& primitive,
                       const std::string& pose = "{position: [0, 0, 0]}",
                       const std::string& header = "") {
  return "world:\n  collision_objects:\n    - id: " + id + "\n" + header + "      primitives: [" +
         primitive + "]\n      primitive_poses: [" + pose + "]\n";
}

TEST(PlanningSceneErrors, MessagesNameTheObjectAndProblem) {
  expect_error(one_object("donut", "{type: torus, dimensions: [0.1, 0.2]}"),
               {"constructed.yaml", "donut", "unknown primitive type", "torus"});
  expect_error(one_object("flat", "{type: box, dimensions: [0.1, 0.2]}"),
               {"constructed.yaml", "flat", "box", "3", "2"});
  expect_error(one_object("thin", "{type: cylinder, dimensions: [0.1]}"),
               {"thin", "cylinder", "2", "1"});
  expect_error(one_object("pointy", "{type: cone, dimensions: [0.1, 0.2, 0.3]}"),
               {"pointy", "cone", "2", "3"});
  expect_error(one_object("bubble", "{type: sphere, dimensions: [0.1, 0.2]}"),
               {"bubble", "sphere", "1", "2"});
  expect_error(one_object("inside_out", "{type: sphere, dimensions: [-0.1]}"),
               {"inside_out", "negative"});
  expect_error(one_object("crushed", "{type: box, dimensions: [0.1, -0.2, 0.3]}"),
               {"crushed", "negative"});
  expect_error(one_object("skewed", "{type: box, dimensions: [1, 1, 1]}",
                          "{position: [0, 0, 0], orientation: [0, 0, 0.5, 0.9]}"),
               {"skewed", "unit quaternion"});
  expect_error(one_object("stretched", "{type: box, dimensions: [1, 1, 1]}",
                          "{position: [0, 0, 0], orientation: [0, 0, 0, 1.0015]}"),
               {"stretched", "unit quaternion"});
  expect_error(one_object("lost", "{type: box, dimensions: [1, 1, 1]}", "{position: [0, 0, 0]}",
                          "      header: {frame_id: no_such_link}\n"),
               {"lost", "no_such_link", "hullcheck_arm"});
  expect_error("world: {collision_objects: [ {id: x, primitives: [}\n",
               {"constructed.yaml", "YAML"});
  expect_error("world:\n  collision_objects:\n    - id: a\n   bad_indent: [1, 2\n",
               {"constructed.yaml", "YAML"});
}

TEST(PlanningSceneErrors, MissingFileNamesThePath) {
  const std::string path = "/nonexistent/folder/scene0042.yaml";
  try {
    read_planning_scene(path, *own_model());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  try {
    read_motion_plan_request(path, *own_model());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------------------------------
// URDF environments.

// The own arm as an environment: every collision shape where KDL's forward kinematics (default
// configuration) puts it, then moved by the environment pose; names link or link/i.
TEST(PlanningSceneUrdf, OwnArmShapesWhereForwardKinematicsSays) {
  const std::string urdf = test::own_arm().urdf;
  std::mt19937_64 rng(11);
  const Eigen::Isometry3d placement = test::random_pose(rng, 1.0);
  const PlanningScene scene = planning_scene_from_urdf(urdf, placement);
  const RobotModel& model = *own_model();
  EXPECT_EQ(scene.name, model.name());
  const KdlPoses kdl(urdf);
  std::size_t k = 0;
  for (const Link& link : model.links()) {
    const Eigen::Isometry3d link_pose = placement * kdl({}, link.name);
    for (std::size_t s = 0; s < link.shapes.size(); ++s, ++k) {
      ASSERT_LT(k, scene.obstacles.size());
      const Obstacle& o = scene.obstacles[k];
      EXPECT_EQ(o.name, link.shapes.size() == 1 ? link.name : link.name + "/" + std::to_string(s));
      EXPECT_EQ(o.object, link.name);
      EXPECT_EQ(o.source, link.name);
      EXPECT_EQ(o.shape.kind(), link.shapes[s].shape.kind());
      EXPECT_LE(pose_error(o.pose, link_pose * link.shapes[s].origin), 1e-12) << o.name;
      // The same geometry: support points agree in a few directions.
      for (const Eigen::Vector3d& d :
           {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0.3, 0.4, 0.5)}) {
        EXPECT_LE((o.shape.support(d) - link.shapes[s].shape.support(d)).norm(), 1e-15);
      }
    }
  }
  EXPECT_EQ(scene.obstacles.size(), k);
  EXPECT_GE(k, 10u);
}

}  // namespace
}  // namespace hullcheck
