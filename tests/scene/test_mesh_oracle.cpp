// The FCL mesh oracle (oracles/fcl_mesh_checker) on the UR5 of MotionBenchMaker, whose
// forearm and wrist_2 meshes come within a millimetre of each other at some goal states:
//  - min_distance (culled, seeded, in cutoff passes) against the minimum of plain fcl::collide /
//    fcl::distance over every pair (pair_distance);
//  - FCL's forearm / wrist_2 mesh distance against a brute force over every triangle pair
//    (oracles/triangle_distance.hpp, no FCL code).
// Skipped when ../shared is absent.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fcl_mesh_checker.hpp"
#include "mesh_test_support.hpp"
#include "scene_test_support.hpp"
#include "triangle_distance.hpp"

namespace hullcheck {
namespace {

// The world triangles of every mesh element of link `name` at `link_pose`.
std::vector<test::Triangle3> world_triangles(const test::FclMeshModel& meshes,
                                             const std::string& name,
                                             const Eigen::Isometry3d& link_pose) {
  std::vector<test::Triangle3> out;
  const int l = meshes.link_index(name);
  EXPECT_GE(l, 0) << name;
  if (l < 0) return out;
  for (const test::FclMeshElement& e : meshes.links()[static_cast<std::size_t>(l)].elements) {
    const auto* bvh = dynamic_cast<const fcl::BVHModel<fcl::OBBRSSd>*>(e.geometry.get());
    if (bvh == nullptr) continue;
    const Eigen::Isometry3d pose = link_pose * e.origin;
    for (int t = 0; t < bvh->num_tris; ++t) {
      const fcl::Triangle& tri = bvh->tri_indices[t];
      out.push_back({pose * bvh->vertices[tri[0]], pose * bvh->vertices[tri[1]],
                     pose * bvh->vertices[tri[2]]});
    }
  }
  return out;
}

// The triangle's axis-aligned box: min and max corners.
std::pair<Eigen::Vector3d, Eigen::Vector3d> box_of(const test::Triangle3& t) {
  return {t[0].cwiseMin(t[1]).cwiseMin(t[2]), t[0].cwiseMax(t[1]).cwiseMax(t[2])};
}

// The smallest triangle_distance over every pair of triangles of `a` and `b` (pairs whose
// boxes are farther apart than the best so far are skipped: that cannot change the minimum).
double brute_force_distance(const std::vector<test::Triangle3>& a,
                            const std::vector<test::Triangle3>& b) {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes_b;
  for (const test::Triangle3& t : b) boxes_b.push_back(box_of(t));
  double best = INFINITY;
  for (const test::Triangle3& x : a) {
    const auto [lo, hi] = box_of(x);
    for (std::size_t j = 0; j < b.size(); ++j) {
      const Eigen::Vector3d gap =
          (boxes_b[j].first - hi).cwiseMax(lo - boxes_b[j].second).cwiseMax(0.0);
      if (gap.norm() >= best) continue;
      best = std::min(best, test::triangle_distance(x, b[j]));
    }
  }
  return best;
}

TEST(MeshOracle, Ur5MatchesUnculledFclAndBruteForce) {
  const test::MbmRobot* ur5 = nullptr;
  const std::vector<test::MbmRobot> robots = test::mbm_robots();
  for (const test::MbmRobot& r : robots) {
    if (r.id == "ur5") ur5 = &r;
  }
  if (ur5 == nullptr) GTEST_SKIP() << "MotionBenchMaker UR5 (../shared) absent";
  const auto model = test::cached_model(ur5->urdf);
  const AllowedCollisionMatrix matrix =
      AllowedCollisionMatrix::from_srdf(*model, read_srdf_file(ur5->srdf));
  const auto meshes = test::cached_meshes(ur5->urdf);
  const std::string family = "bookshelf_small_ur5";
  const PlanningScene scene = read_planning_scene(test::mbm_file(*ur5, family, "scene", 9), *model);
  test::FclMeshChecker oracle(meshes, *model, matrix, scene);

  // Goal states whose forearm and wrist_2 meshes are millimetres apart (hullcheck's hulls
  // overlap there), then random arm states in the same scene (some collide). Few: the
  // unculled, unseeded reference takes about 0.2 s a state (40k-triangle gripper meshes).
  std::vector<Eigen::VectorXd> states;
  for (const int number : {9, 10, 11, 12, 15}) {
    states.push_back(
        read_motion_plan_request(test::mbm_file(*ur5, family, "request", number), *model).goal);
  }
  const MotionPlanRequest request =
      read_motion_plan_request(test::mbm_file(*ur5, family, "request", 9), *model);
  const std::vector<int> arm = group_variables(*model, read_srdf_file(ur5->srdf), request.group);
  std::mt19937_64 rng(7);
  for (int n = test::sample_count(12, "HULLCHECK_MESH_ORACLE_STATES"); n > 0; --n) {
    states.push_back(test::random_configuration(*model, request.start, arm, rng));
  }

  std::vector<Eigen::Isometry3d> poses;
  const int forearm = model->link_index("forearm_link");
  const int wrist_2 = model->link_index("wrist_2_link");
  int collisions = 0, brute_forced = 0;
  for (std::size_t s = 0; s < states.size(); ++s) {
    SCOPED_TRACE("state " + std::to_string(s));
    model->compute_link_poses(states[s], poses);
    oracle.set_link_poses(poses);
    const test::FclMeshDistance d = oracle.min_distance();
    double reference = INFINITY;
    for (std::size_t i = 0; i < oracle.pairs().size(); ++i) {
      reference = std::min(reference, oracle.pair_distance(i));
    }
    EXPECT_EQ(d.collision, reference == 0.0) << reference;
    EXPECT_EQ(oracle.in_collision(), d.collision);
    if (!d.collision) {
      EXPECT_NEAR(d.distance, reference, 1e-9);
    }
    collisions += d.collision ? 1 : 0;

    // The brute force on the forearm / wrist_2 pair, for the MBM goals and a few random states.
    if (s >= 8) continue;
    const double fcl = oracle.named_pair_distance("forearm_link", "wrist_2_link").distance;
    const double brute = brute_force_distance(
        world_triangles(*meshes, "forearm_link", poses[static_cast<std::size_t>(forearm)]),
        world_triangles(*meshes, "wrist_2_link", poses[static_cast<std::size_t>(wrist_2)]));
    EXPECT_NEAR(fcl, brute, 1e-9);
    ++brute_forced;
  }
  std::printf(
      "[ ur5      ] %zu states, %d colliding; min_distance = min of unculled FCL pairs; "
      "forearm / wrist_2 brute-forced in %d\n",
      states.size(), collisions, brute_forced);
  EXPECT_GT(collisions, 0);
  EXPECT_LT(collisions, static_cast<int>(states.size()));
}

}  // namespace
}  // namespace hullcheck
