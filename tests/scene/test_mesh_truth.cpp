// Ground truth on the links' triangle meshes (oracles/fcl_mesh_checker: FCL 0.7 on the meshes
// themselves, read from the URDF independently of hullcheck) against hullcheck's convex
// representation of each link:
//  - the oracle itself against analytic distances of boxes written as STL meshes;
//  - the start and goal states of the MotionBenchMaker problems (UR5, Panda): hullcheck must
//    reject every state whose meshes collide (its shapes cover the meshes); how many states
//    with free meshes it rejects is measured and printed (hulls of concave links over-report).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fcl_mesh_checker.hpp"
#include "fcl_mesh_model.hpp"
#include "mesh_test_support.hpp"
#include "robot_test_support.hpp"
#include "scene_test_support.hpp"

namespace hullcheck {
namespace {

using Clock = std::chrono::steady_clock;

// Seconds since `t0`.
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// ------------------------------------------------------------------------------------------
// The oracle on boxes written as meshes.

// An ASCII STL of the axis-aligned box with half extents `h` centred at the origin (12
// triangles; the normals are left to the reader).
std::string box_stl(const Eigen::Vector3d& h) {
  std::ostringstream out;
  out.precision(17);
  out << "solid box\n";
  // Each face: the axis it is normal to, its side, and two in-plane axes.
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      Eigen::Vector3d corner[4];
      const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
      for (int k = 0; k < 4; ++k) {
        corner[k][axis] = side * h[axis];
        corner[k][u] = su[k] * h[u];
        corner[k][v] = sv[k] * h[v];
      }
      for (const auto& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
        out << " facet normal 0 0 0\n  outer loop\n";
        for (int k : tri) {
          out << "   vertex " << corner[k].x() << ' ' << corner[k].y() << ' ' << corner[k].z()
              << '\n';
        }
        out << "  endloop\n endfacet\n";
      }
    }
  }
  out << "endsolid box\n";
  return out.str();
}

// A robot of two links on fixed joints: `small` is box.stl (half extents 0.1 x 0.05 x 0.05),
// `large` the same file scaled by (2, 3, 3) and lifted by 0.5 m in its link frame (so its
// geometry has half extents 0.2 x 0.15 x 0.15 about (0, 0, 0.5)). The base has no geometry.
constexpr const char* kTwoBoxUrdf = R"(<?xml version="1.0"?>
<robot name="two_boxes">
  <link name="base"/>
  <link name="small">
    <collision><geometry><mesh filename="box.stl"/></geometry></collision>
  </link>
  <link name="large">
    <collision>
      <origin xyz="0 0 0.5" rpy="0 0 0"/>
      <geometry><mesh filename="box.stl" scale="2 3 3"/></geometry>
    </collision>
  </link>
  <joint name="j_small" type="fixed"><parent link="base"/><child link="small"/></joint>
  <joint name="j_large" type="fixed"><parent link="base"/><child link="large"/></joint>
</robot>
)";

// A translation with a rotation about z by `yaw`.
Eigen::Isometry3d pose_of(double x, double y, double z, double yaw = 0.0) {
  Eigen::Isometry3d p = test::translation(x, y, z);
  p.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return p;
}

// Distance error allowed: assimp holds mesh vertices in single precision.
constexpr double kFloat = 1e-7;

TEST(MeshTruth, OracleAgreesWithAnalyticBoxes) {
  const test::TempDir dir("mesh_truth");
  dir.write("box.stl", box_stl(Eigen::Vector3d(0.1, 0.05, 0.05)));
  const std::string urdf = dir.write("two_boxes.urdf", kTwoBoxUrdf).string();
  const RobotModel model = RobotModel::from_urdf_file(urdf);
  auto meshes = std::make_shared<const test::FclMeshModel>(urdf);
  ASSERT_EQ(meshes->triangle_count(), 24u);

  // A scene box with half extents 0.1 at (0, 2, 0).
  PlanningScene scene;
  scene.obstacles.push_back(
      Obstacle{"wall", "wall", Shape(Box(0.2, 0.2, 0.2)), test::translation(0, 2, 0), "box"});
  const AllowedCollisionMatrix matrix(static_cast<int>(model.links().size()));
  test::FclMeshChecker oracle(meshes, model, matrix, scene);
  ASSERT_EQ(oracle.pairs().size(), 3u);  // small / wall, large / wall, small / large

  const auto small = static_cast<std::size_t>(model.link_index("small"));
  const auto large = static_cast<std::size_t>(model.link_index("large"));
  std::vector<Eigen::Isometry3d> poses(model.links().size(), Eigen::Isometry3d::Identity());
  // Places the small box and the large box's geometry (its link frame is 0.5 below it).
  const auto place = [&](const Eigen::Isometry3d& small_box, const Eigen::Isometry3d& large_box) {
    poses[small] = small_box;
    poses[large] = large_box * test::translation(0, 0, -0.5);
    oracle.set_link_poses(poses);
  };

  // Side by side along x: gap 1.0 - 0.1 - 0.2 (the wall is farther: 2 - 0.1 - 0.05).
  place(pose_of(0, 0, 0), pose_of(1.0, 0, 0));
  test::FclMeshDistance d = oracle.min_distance();
  EXPECT_FALSE(d.collision);
  EXPECT_NEAR(d.distance, 0.7, kFloat);
  ASSERT_GE(d.pair, 0);
  EXPECT_EQ(oracle.pair_name(static_cast<std::size_t>(d.pair)), "small / large");
  EXPECT_FALSE(oracle.in_collision());

  // The large box turned by 90 degrees about z: its half extent along x is now 0.15.
  place(pose_of(0, 0, 0), pose_of(0.5, 0, 0, M_PI / 2));
  EXPECT_NEAR(oracle.min_distance().distance, 0.5 - 0.1 - 0.15, kFloat);

  // Corner to corner: gaps 0.1 in x, 0.2 in y, 0.3 in z.
  place(pose_of(0, 0, 0), pose_of(0.1 + 0.2 + 0.1, 0.05 + 0.15 + 0.2, 0.05 + 0.15 + 0.3));
  EXPECT_NEAR(oracle.min_distance().distance, std::sqrt(0.01 + 0.04 + 0.09), kFloat);

  // A cutoff below the distance gives the cutoff back (a lower bound).
  d = oracle.min_distance(0.1);
  EXPECT_FALSE(d.collision);
  EXPECT_DOUBLE_EQ(d.distance, 0.1);

  // The small box 0.03 from the wall (the large one far away).
  place(pose_of(0, 2 - 0.1 - 0.05 - 0.03, 0), pose_of(5, 0, 0));
  d = oracle.min_distance();
  EXPECT_NEAR(d.distance, 0.03, kFloat);
  ASSERT_GE(d.pair, 0);
  EXPECT_EQ(oracle.pair_name(static_cast<std::size_t>(d.pair)), "small / wall");

  // Overlapping boxes whose surfaces cross: a collision for both queries.
  place(pose_of(0, 0, 0), pose_of(0.25, 0.02, 0));
  EXPECT_TRUE(oracle.in_collision());
  d = oracle.min_distance();
  EXPECT_TRUE(d.collision);
  EXPECT_EQ(d.distance, 0.0);
  ASSERT_GE(d.pair, 0);
  EXPECT_EQ(oracle.pair_name(static_cast<std::size_t>(d.pair)), "small / large");
  EXPECT_TRUE(oracle.min_distance(0.0).collision);  // the collision test alone

  // A mesh inside an obstacle collides (FCL tests each triangle against the solid box)...
  place(pose_of(0, 2, 0), pose_of(5, 0, 0));
  EXPECT_TRUE(oracle.in_collision());
  // ... but a mesh wholly inside another mesh does not (surfaces only, as documented): its
  // distance is the 0.1 to the enclosing surface.
  place(pose_of(0, 0, 0), pose_of(0, 0, 0));
  EXPECT_FALSE(oracle.in_collision());
  d = oracle.min_distance();
  EXPECT_FALSE(d.collision);
  EXPECT_NEAR(d.distance, 0.1, kFloat);
}

// ------------------------------------------------------------------------------------------
// MotionBenchMaker start and goal states: hullcheck against the meshes.

// One state where hullcheck and the meshes disagree.
struct MbmExample {
  std::string problem;  // "family/requestNNNN.yaml"
  std::string state;    // "start" or "goal"
  std::string hull_pair;
  double hull_clearance = 0.0;  // hullcheck's signed clearance, m (its closest or deepest pair)
  double mesh_same_pair = 0.0;  // FCL's mesh distance of that pair, m (0: collide)
  std::string mesh_pair;
  double mesh_distance = 0.0;  // FCL's mesh distance, m (0: the meshes collide)
};

// hullcheck's verdicts on the start and goal states of MBM problems against the meshes'.
struct MbmAgreement {
  std::string robot;
  double tolerance = 0.0;  // m: mesh distances up to it may go either way
  int problems = 0;
  int states = 0;                 // 2 per problem
  int mesh_colliding = 0;         // states whose meshes collide (FCL)
  int mesh_beyond = 0;            // states whose meshes are apart by at least the tolerance
  int hull_invalid = 0;           // states hullcheck's is_valid rejects
  int problems_hull_invalid = 0;  // problems whose start or goal hullcheck rejects
  int problems_mesh_colliding = 0;
  int accepted_colliding = 0;  // hullcheck accepts, the meshes collide: never allowed
  int rejected_beyond = 0;     // hullcheck rejects, the meshes are apart by >= the tolerance
  // hullcheck rejects, its deepest pair's meshes are apart by >= the tolerance (a state whose
  // gripper is millimetres from its grasp target has a small state distance, whichever pair
  // hullcheck rejects it for: this count looks at that pair only).
  int rejected_pair_beyond = 0;
  // FCL mesh distances of the states hullcheck rejects whose meshes do not collide (sorted).
  std::vector<double> rejected_free_distances;
  // hullcheck's deepest pair in those states -> the meshes' distance for that pair in each.
  std::map<std::string, std::vector<double>> rejected_free_pairs;
  std::map<std::string, int> mesh_colliding_pairs;      // FCL's pair in mesh-colliding states
  std::vector<MbmExample> accepted_colliding_examples;  // the first few
  std::vector<MbmExample> rejected_beyond_examples;
  // Seconds: in all; loading the robot and reading the problems; building hullcheck's checkers
  // and the oracles; hullcheck's queries; the oracle's.
  double seconds = 0.0, load_seconds = 0.0, build_seconds = 0.0, hull_seconds = 0.0;
  double mesh_seconds = 0.0;
};

constexpr std::size_t kExamples = 5;

// "a / b" of a hullcheck clearance result.
std::string pair_of(const ClearanceResult& c) {
  return std::string(c.name_a) + " / " + std::string(c.name_b);
}

// Pairs by count, most frequent first: "a / b: n, ...".
std::string pair_counts(const std::map<std::string, int>& counts) {
  std::vector<std::pair<int, std::string>> sorted;
  for (const auto& [name, n] : counts) sorted.emplace_back(-n, name);
  std::sort(sorted.begin(), sorted.end());
  std::string out;
  for (const auto& [n, name] : sorted) {
    out += (out.empty() ? "" : ", ") + name + ": " + std::to_string(-n);
  }
  return out.empty() ? "none" : out;
}

// "min x mm, median y mm, max z mm, within 1/2/3/6/10/20 mm: a/b/c/d/e/f" of sorted distances (m).
std::string distance_summary(const std::vector<double>& d) {
  if (d.empty()) return "none";
  std::ostringstream out;
  out.precision(3);
  out << "min " << d.front() * 1e3 << " mm, median " << d[d.size() / 2] * 1e3 << " mm, max "
      << d.back() * 1e3 << " mm, within 1/2/3/6/10/20 mm:";
  const char* separator = " ";
  for (const double x : {1e-3, 2e-3, 3e-3, 6e-3, 1e-2, 2e-2}) {
    out << separator << std::upper_bound(d.begin(), d.end(), x) - d.begin();
    separator = "/";
  }
  return out.str();
}

// Pairs with the distances seen for them, most frequent first, one per line: "a / b: n
// states, " and their distance_summary.
std::string pair_distances(std::map<std::string, std::vector<double>> pairs) {
  std::vector<std::pair<std::size_t, std::string>> sorted;
  for (auto& [name, d] : pairs) {
    std::sort(d.begin(), d.end());
    sorted.emplace_back(d.size(), name);
  }
  std::sort(sorted.begin(), sorted.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first > y.first : x.second < y.second;
  });
  std::string out;
  for (const auto& [n, name] : sorted) {
    const std::vector<double>& d = pairs[name];
    out += "\n    " + name + ": " + std::to_string(d.size()) + " states, " + distance_summary(d);
  }
  return pairs.empty() ? " none" : out;
}

// One line of an example.
std::string describe(const MbmExample& e) {
  std::ostringstream out;
  out << e.problem << " " << e.state << ": hullcheck " << e.hull_pair << " clearance "
      << e.hull_clearance << " m (meshes: " << e.mesh_same_pair << " m); FCL meshes " << e.mesh_pair
      << " distance " << e.mesh_distance << " m";
  return out.str();
}

// Prints the counts and records them as test properties ("<robot>_t<tolerance in um>_...").
void report(const MbmAgreement& a) {
  std::cout << "[ " << a.robot << ", tolerance " << a.tolerance * 1e3 << " mm ] " << a.problems
            << " problems, " << a.states << " start/goal states. Meshes (FCL): collide in "
            << a.mesh_colliding << " (problems: " << a.problems_mesh_colliding
            << "), apart by at least the tolerance in " << a.mesh_beyond << ". hullcheck rejects "
            << a.hull_invalid << " (problems: " << a.problems_hull_invalid << ")\n"
            << "  accepted but the meshes collide: " << a.accepted_colliding
            << "; rejected but the meshes are apart by at least the tolerance: "
            << a.rejected_beyond
            << " (by its deepest pair's mesh distance: " << a.rejected_pair_beyond << ")\n"
            << "  rejected, meshes free: " << a.rejected_free_distances.size()
            << "; the state's mesh distance: " << distance_summary(a.rejected_free_distances)
            << "\n"
            << "  hullcheck's deepest pair there, with the meshes' distance for that pair:"
            << pair_distances(a.rejected_free_pairs) << "\n"
            << "  FCL's pairs where the meshes collide: " << pair_counts(a.mesh_colliding_pairs)
            << "\n"
            << "  time " << a.seconds << " s (loading " << a.load_seconds
            << " s, building checkers " << a.build_seconds << " s, hullcheck " << a.hull_seconds
            << " s, FCL meshes " << a.mesh_seconds << " s)\n";
  for (const MbmExample& e : a.accepted_colliding_examples) {
    std::cout << "  accepted, meshes collide: " << describe(e) << "\n";
  }
  for (const MbmExample& e : a.rejected_beyond_examples) {
    std::cout << "  rejected, meshes apart: " << describe(e) << "\n";
  }
  const std::string p = a.robot + "_t" + std::to_string(std::lround(a.tolerance * 1e6)) + "_";
  testing::Test::RecordProperty(p + "states", a.states);
  testing::Test::RecordProperty(p + "mesh_colliding", a.mesh_colliding);
  testing::Test::RecordProperty(p + "hull_invalid", a.hull_invalid);
  testing::Test::RecordProperty(p + "rejected_free",
                                static_cast<int>(a.rejected_free_distances.size()));
  testing::Test::RecordProperty(p + "rejected_beyond_tolerance", a.rejected_beyond);
  testing::Test::RecordProperty(p + "rejected_pair_beyond_tolerance", a.rejected_pair_beyond);
  if (!a.rejected_free_distances.empty()) {
    testing::Test::RecordProperty(
        p + "min_rejected_free_distance_um",
        static_cast<int>(std::floor(a.rejected_free_distances.front() * 1e6)));
  }
}

// hullcheck's CollisionChecker for one scene as two checkers that together check the pairs of
// CollisionChecker(model, matrix, scene): the self pairs, in a checker shared by every scene
// with the same allowed link/link names (building the self pairs' warm-start grids takes 8 ms
// for the Panda and 18 ms for the UR5: four fifths of this test's time when done for each
// problem), and the environment pairs, in a checker for the scene with every self pair allowed.
class SceneChecker {
 public:
  SceneChecker(std::shared_ptr<const CollisionChecker> self,
               std::shared_ptr<const RobotModel> model, const AllowedCollisionMatrix& none,
               const PlanningScene& scene)
      : self_(std::move(self)), environment_(std::move(model), none, scene) {}

  const RobotModel& model() const { return environment_.model(); }
  /// CollisionChecker::is_valid over both pair sets.
  bool is_valid(const Eigen::VectorXd& q) const {
    return self_->is_valid(q) && environment_.is_valid(q);
  }
  /// CollisionChecker::clearance over both pair sets.
  ClearanceResult clearance(const Eigen::VectorXd& q) const {
    const ClearanceResult self = self_->clearance(q);
    const ClearanceResult environment = environment_.clearance(q);
    return self.distance <= environment.distance ? self : environment;
  }

 private:
  std::shared_ptr<const CollisionChecker> self_;
  CollisionChecker environment_;
};

// The self-pair checkers of one robot, by the scene's allowed link/link names.
class SelfCheckers {
 public:
  SelfCheckers(std::shared_ptr<const RobotModel> model, AllowedCollisionMatrix matrix)
      : model_(std::move(model)), matrix_(std::move(matrix)) {}

  /// The checker of `scene`'s self pairs (no obstacles), built on first use.
  std::shared_ptr<const CollisionChecker> of(const PlanningScene& scene) {
    PlanningScene links_only;
    for (const auto& [a, b] : scene.allowed_pairs) {
      if (model_->link_index(a) >= 0 && model_->link_index(b) >= 0) {
        links_only.allowed_pairs.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
    auto& pairs = links_only.allowed_pairs;
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    auto& checker = checkers_[pairs];
    if (!checker) checker = std::make_shared<const CollisionChecker>(model_, matrix_, links_only);
    return checker;
  }

 private:
  std::shared_ptr<const RobotModel> model_;
  AllowedCollisionMatrix matrix_;
  std::map<std::vector<std::pair<std::string, std::string>>,
           std::shared_ptr<const CollisionChecker>>
      checkers_;
};

// The split checker answers as one CollisionChecker(model, matrix, scene) does, at the start
// and goal states of `request`.
void expect_same_as_one_checker(const SceneChecker& split, std::shared_ptr<const RobotModel> model,
                                const AllowedCollisionMatrix& matrix, const PlanningScene& scene,
                                const MotionPlanRequest& request) {
  const CollisionChecker one(std::move(model), matrix, scene);
  for (const Eigen::VectorXd* q : {&request.start, &request.goal}) {
    EXPECT_EQ(split.is_valid(*q), one.is_valid(*q)) << scene.name;
    EXPECT_NEAR(split.clearance(*q).distance, one.clearance(*q).distance, 1e-9) << scene.name;
  }
}

// A matrix allowing every link pair of `model` (no self pairs checked).
AllowedCollisionMatrix allow_all(const RobotModel& model) {
  const int n = static_cast<int>(model.links().size());
  AllowedCollisionMatrix out(n);
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) out.allow(a, b, CollisionAllowance::kUser);
  }
  return out;
}

// Compares one state: hullcheck's is_valid against the meshes; adds it to `a`. Returns
// {hullcheck rejects, the meshes collide}.
std::pair<bool, bool> compare_state(const SceneChecker& checker, test::FclMeshChecker& oracle,
                                    const Eigen::VectorXd& q, const std::string& problem,
                                    const char* state, std::vector<Eigen::Isometry3d>& poses,
                                    MbmAgreement* a) {
  auto t = Clock::now();
  const bool valid = checker.is_valid(q);
  a->hull_seconds += seconds_since(t);
  t = Clock::now();
  checker.model().compute_link_poses(q, poses);
  oracle.set_link_poses(poses);
  // Exact distances only where hullcheck rejects (to report them); elsewhere only whether the
  // meshes are apart beyond the tolerance (no distance at all for a tolerance of 0).
  const test::FclMeshDistance d =
      oracle.min_distance(valid ? a->tolerance : std::numeric_limits<double>::infinity());
  a->mesh_seconds += seconds_since(t);
  const std::string mesh_pair =
      d.pair >= 0 ? oracle.pair_name(static_cast<std::size_t>(d.pair)) : "-";
  const bool beyond = !d.collision && d.distance >= a->tolerance;
  ++a->states;
  a->hull_invalid += valid ? 0 : 1;
  a->mesh_colliding += d.collision ? 1 : 0;
  a->mesh_beyond += beyond ? 1 : 0;
  if (d.collision) ++a->mesh_colliding_pairs[mesh_pair];
  const bool accepted_colliding = valid && d.collision;
  const bool rejected_beyond = !valid && beyond;
  a->accepted_colliding += accepted_colliding ? 1 : 0;
  a->rejected_beyond += rejected_beyond ? 1 : 0;
  auto& examples =
      accepted_colliding ? a->accepted_colliding_examples : a->rejected_beyond_examples;
  const bool example = (accepted_colliding || rejected_beyond) && examples.size() < kExamples;
  if ((!valid && !d.collision) || example) {
    // hullcheck's closest (or deepest) pair, and the meshes' distance for that pair.
    t = Clock::now();
    const ClearanceResult c = checker.clearance(q);
    a->hull_seconds += seconds_since(t);
    t = Clock::now();
    const double same =
        oracle.named_pair_distance(std::string(c.name_a), std::string(c.name_b)).distance;
    a->mesh_seconds += seconds_since(t);
    if (!valid && !d.collision) {
      a->rejected_free_distances.push_back(d.distance);
      a->rejected_free_pairs[pair_of(c)].push_back(same);
      a->rejected_pair_beyond += same >= a->tolerance ? 1 : 0;
    }
    if (example) {
      examples.push_back({problem, state, pair_of(c), c.distance, same, mesh_pair, d.distance});
    }
  }
  return {!valid, d.collision};
}

// Loads `robot` with `options` and compares hullcheck's CollisionChecker::is_valid with the
// FCL mesh oracle at the start and goal states of its MBM problems (100 per family; fewer under
// sanitizers, or HULLCHECK_MESH_TRUTH_PROBLEMS per family), and prints the counts (report). A
// state whose meshes collide must be rejected; one whose meshes are apart by at least
// `tolerance` (m) should be accepted (both counted here, asserted by the callers).
MbmAgreement check_mbm_states(const test::MbmRobot& robot, const RobotLoadOptions& options,
                              double tolerance) {
  const auto t0 = Clock::now();
  MbmAgreement a;
  a.robot = robot.id;
  a.tolerance = tolerance;
  const auto model =
      std::make_shared<const RobotModel>(RobotModel::from_urdf_file(robot.urdf, options));
  const AllowedCollisionMatrix matrix =
      AllowedCollisionMatrix::from_srdf(*model, read_srdf_file(robot.srdf));
  const AllowedCollisionMatrix none = allow_all(*model);
  SelfCheckers self_checkers(model, matrix);
  const auto meshes = test::cached_meshes(robot.urdf, options.packages);
  a.load_seconds = seconds_since(t0);
  const int per_family = test::sample_count(100, "HULLCHECK_MESH_TRUTH_PROBLEMS");
  std::vector<Eigen::Isometry3d> poses;
  for (const std::string& family : robot.families) {
    for (int number = 1; number <= per_family; ++number) {
      auto t = Clock::now();
      const std::string problem = test::mbm_file(robot, family, "request", number);
      const PlanningScene scene =
          read_planning_scene(test::mbm_file(robot, family, "scene", number), *model);
      const MotionPlanRequest request = read_motion_plan_request(problem, *model);
      a.load_seconds += seconds_since(t);
      t = Clock::now();
      const SceneChecker checker(self_checkers.of(scene), model, none, scene);
      test::FclMeshChecker oracle(meshes, *model, matrix, scene);
      a.build_seconds += seconds_since(t);
      if (number == 1) expect_same_as_one_checker(checker, model, matrix, scene, request);
      ++a.problems;
      const std::string name = family + "/" + std::filesystem::path(problem).filename().string();
      const auto start = compare_state(checker, oracle, request.start, name, "start", poses, &a);
      const auto goal = compare_state(checker, oracle, request.goal, name, "goal", poses, &a);
      a.problems_hull_invalid += (start.first || goal.first) ? 1 : 0;
      a.problems_mesh_colliding += (start.second || goal.second) ? 1 : 0;
    }
  }
  std::sort(a.rejected_free_distances.begin(), a.rejected_free_distances.end());
  a.seconds = seconds_since(t0);
  report(a);
  return a;
}

// What every convex representation must give: the meshes collide => hullcheck rejects (the
// shapes cover the meshes). Also checks that the states were compared at all.
void expect_covers_meshes(const MbmAgreement& a) {
  EXPECT_GT(a.states, 0) << a.robot;
  EXPECT_EQ(a.accepted_colliding, 0) << a.robot << ": states the meshes say collide";
  for (const MbmExample& e : a.accepted_colliding_examples) ADD_FAILURE() << describe(e);
}

// Full agreement beyond the tolerance: also no state rejected whose meshes are apart by at
// least it (for pieces within t of the meshes: t for link/obstacle pairs, 2t for self pairs).
void expect_agrees_beyond_tolerance(const MbmAgreement& a) {
  expect_covers_meshes(a);
  EXPECT_EQ(a.rejected_beyond, 0) << a.robot << ": rejected states with meshes apart by at least "
                                  << a.tolerance << " m";
  for (const MbmExample& e : a.rejected_beyond_examples) ADD_FAILURE() << describe(e);
}

TEST(MeshTruth, MbmStartAndGoalStates) {
  const std::vector<test::MbmRobot> robots = test::mbm_robots();
  if (robots.empty()) GTEST_SKIP() << "MotionBenchMaker data (../shared) absent";
  for (const test::MbmRobot& robot : robots) {
    SCOPED_TRACE(robot.id);
    // One convex hull per mesh: covers the meshes, and over-reports (the UR5's forearm).
    const MbmAgreement hulls = check_mbm_states(robot, test::hull_options(), 0.0);
    expect_covers_meshes(hulls);
    // MotionBenchMaker's start and goal states are valid for MoveIt, i.e. for FCL on these
    // meshes: the oracle must agree.
    EXPECT_EQ(hulls.mesh_colliding, 0);
    // Convex pieces (the default) within t of the meshes: they cover the meshes, and agree
    // with them wherever the meshes are apart by 2t (a self pair's two links each reach up to
    // t beyond their meshes).
    const RobotLoadOptions pieces;
    expect_agrees_beyond_tolerance(
        check_mbm_states(robot, pieces, 2.0 * pieces.decomposition.tolerance));
  }
}

// Random UR5 configurations (self pairs only; SRDF matrix): the pieces must reject every state
// whose meshes touch and accept every state whose meshes are more than twice the tolerance
// apart (the forearm's concave elbow end against the wrist is where its hull lied); the hulls
// must reject every touching state too, and are counted where they reject free meshes.
TEST(MeshTruth, Ur5RandomStatesAgreeBeyondTwiceTheTolerance) {
  const std::vector<test::MbmRobot> robots = test::mbm_robots();
  const auto ur5 = std::find_if(robots.begin(), robots.end(),
                                [](const test::MbmRobot& r) { return r.id == "ur5"; });
  if (ur5 == robots.end()) GTEST_SKIP() << "MotionBenchMaker UR5 (../shared) absent";
  const RobotLoadOptions pieces_options;
  const double tolerance = 2.0 * pieces_options.decomposition.tolerance;
  const auto pieces =
      std::make_shared<const RobotModel>(RobotModel::from_urdf_file(ur5->urdf, pieces_options));
  const auto hulls = std::make_shared<const RobotModel>(
      RobotModel::from_urdf_file(ur5->urdf, test::hull_options()));
  const Srdf srdf = read_srdf_file(ur5->srdf);
  const AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_srdf(*pieces, srdf);
  const CollisionChecker piece_checker(pieces, matrix, PlanningScene{});
  const CollisionChecker hull_checker(hulls, AllowedCollisionMatrix::from_srdf(*hulls, srdf),
                                      PlanningScene{});
  test::FclMeshChecker oracle(test::cached_meshes(ur5->urdf), *pieces, matrix, PlanningScene{});
  std::mt19937_64 rng(5);
  std::vector<Eigen::Isometry3d> poses;
  int touching = 0, apart = 0, near = 0, hull_lies = 0;
  const int states = test::sample_count(3000, "HULLCHECK_MESH_TRUTH_STATES");
  for (int n = 0; n < states; ++n) {
    const Eigen::VectorXd q = test::random_configuration(*pieces, rng);
    pieces->compute_link_poses(q, poses);
    oracle.set_link_poses(poses);
    const test::FclMeshDistance d = oracle.min_distance(0.05);
    const bool piece_valid = piece_checker.is_valid(q);
    const bool hull_valid = hull_checker.is_valid(q);
    if (d.collision) {
      ++touching;
      EXPECT_FALSE(piece_valid) << "meshes touch (" << oracle.pair_name(d.pair) << "), q "
                                << q.transpose();
      EXPECT_FALSE(hull_valid) << "meshes touch, q " << q.transpose();
    } else if (d.distance > tolerance) {
      ++apart;
      near += d.distance < 0.02 ? 1 : 0;
      EXPECT_TRUE(piece_valid) << "meshes " << d.distance << " m apart, q " << q.transpose();
      hull_lies += hull_valid ? 0 : 1;
    }
  }
  std::printf(
      "[ ur5 self ] %d random states: meshes touch in %d, apart by more than %.0f mm in "
      "%d (%d of them within 2 cm); the hulls reject %d of those\n",
      states, touching, 1e3 * tolerance, apart, near, hull_lies);
  EXPECT_GT(touching, 0);
  EXPECT_GT(near, 0);
}

}  // namespace
}  // namespace hullcheck
