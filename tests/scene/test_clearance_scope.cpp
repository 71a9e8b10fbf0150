// CollisionChecker::clearance with a scope (obstacles only, self only, both) against brute
// force over the same pairs, each query cold: the own arm in its table-and-wall scene.
#include <gtest/gtest.h>

#include <cmath>
#include <hullcheck/scene.hpp>
#include <memory>
#include <random>
#include <vector>

#include "robot_test_support.hpp"
#include "scene_test_support.hpp"

namespace hullcheck {
namespace {

using test::arm_in_scene;
using test::ArmInScene;

TEST(ClearanceScope, EachScopeEqualsBruteForceOverItsPairs) {
  const ArmInScene w = arm_in_scene();
  ASSERT_FALSE(w.scene.obstacles.empty());
  ASSERT_TRUE(w.scene.allowed_pairs.empty());  // the obstacle brute force checks every pair
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  std::mt19937_64 rng(23);
  std::vector<Eigen::Isometry3d> poses;
  int obstacle_closer = 0, self_closer = 0, overlapping = 0;
  const int states = test::sample_count(400);
  for (int n = 0; n < states; ++n) {
    const Eigen::VectorXd q = test::random_configuration(*w.model, rng);
    w.model->compute_link_poses(q, poses);
    const ClearanceResult all = checker.clearance(q);
    const ClearanceResult obstacles = checker.clearance(q, ClearanceScope::kObstacles);
    const ClearanceResult self = checker.clearance(q, ClearanceScope::kSelf);
    Status self_status = Status::kConverged;
    const double brute_self =
        test::brute_force_self_clearance(*w.model, w.matrix, poses, &self_status);
    const double brute_obstacles = test::brute_force_obstacle_clearance(*w.model, w.scene, poses);
    // Deep overlaps of vertex-rich pieces may stop EPA at its cap (flagged): near, not equal.
    const double tolerance = self.status == Status::kConverged &&
                                     self_status == Status::kConverged &&
                                     obstacles.status == Status::kConverged
                                 ? 2e-10
                                 : 1e-3;
    ASSERT_NEAR(obstacles.distance, brute_obstacles, tolerance) << "q = " << q.transpose();
    ASSERT_NEAR(self.distance, brute_self, tolerance) << "q = " << q.transpose();
    EXPECT_FALSE(obstacles.self);
    EXPECT_TRUE(self.self);
    EXPECT_EQ(all.distance, std::min(obstacles.distance, self.distance));
    (obstacles.distance < self.distance ? obstacle_closer : self_closer) += 1;
    overlapping += all.distance < 0.0;
  }
  // Both kinds of pair are the closest on some states, and some states overlap.
  EXPECT_GT(obstacle_closer, states / 20);
  EXPECT_GT(self_closer, states / 20);
  EXPECT_GT(overlapping, states / 20);
}

// A cap `below`: the brute-force minimum where it is under the cap, +inf with no pair where it
// is over it; caps on both sides of each answer, at a fixed margin and at contact, for the
// scope enum and the PairScope overload.
TEST(ClearanceScope, CappedClearanceIsExactBelowTheCapAndInfiniteAbove) {
  const ArmInScene w = arm_in_scene();
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  const PairScope obstacles_only = checker.pair_scope(ClearanceScope::kObstacles);
  std::mt19937_64 rng(29);
  std::vector<Eigen::Isometry3d> poses;
  int below = 0, above = 0;
  const int states = test::sample_count(300);
  for (int n = 0; n < states; ++n) {
    const Eigen::VectorXd q = test::random_configuration(*w.model, rng);
    w.model->compute_link_poses(q, poses);
    Status status = Status::kConverged;
    const double brute_self = test::brute_force_self_clearance(*w.model, w.matrix, poses, &status);
    const double brute_obstacles = test::brute_force_obstacle_clearance(*w.model, w.scene, poses);
    const double brute_all = std::min(brute_self, brute_obstacles);
    const double tolerance = status == Status::kConverged ? 2e-10 : 1e-3;
    for (double cap : {brute_all - 0.01, brute_all + 0.01, 0.05, 0.0, brute_obstacles + 0.002}) {
      const ClearanceResult all = checker.clearance(q, ClearanceScope::kAll, cap);
      const ClearanceResult obstacles = checker.clearance(q, obstacles_only, cap);
      for (const auto& [r, truth] : {std::pair{&all, brute_all}, {&obstacles, brute_obstacles}}) {
        if (truth < cap - tolerance) {
          ASSERT_NEAR(r->distance, truth, tolerance) << "cap " << cap << ", q = " << q.transpose();
          EXPECT_GE(r->link_a, 0);
          ++below;
        } else if (truth > cap + tolerance) {
          ASSERT_TRUE(std::isinf(r->distance) && r->distance > 0)
              << "cap " << cap << ", truth " << truth << ", got " << r->distance;
          EXPECT_EQ(r->link_a, -1);
          EXPECT_TRUE(r->name_a.empty());
          ++above;
        }
      }
    }
  }
  EXPECT_GT(below, states);
  EXPECT_GT(above, states);
  const Eigen::VectorXd q = w.model->default_configuration();
  EXPECT_THROW(checker.clearance(q, ClearanceScope::kAll, std::nan("")), InputError);
}

TEST(ClearanceScope, NothingInScopeIsInfinite) {
  const ArmInScene w = arm_in_scene();
  const CollisionChecker no_scene(w.model, w.matrix, PlanningScene{});
  const Eigen::VectorXd q = w.model->default_configuration();
  const ClearanceResult r = no_scene.clearance(q, ClearanceScope::kObstacles);
  EXPECT_TRUE(std::isinf(r.distance) && r.distance > 0);
  EXPECT_TRUE(r.name_a.empty());
  EXPECT_EQ(no_scene.clearance(q, ClearanceScope::kSelf).distance, no_scene.clearance(q).distance);
  std::vector<Eigen::Isometry3d> poses;
  w.model->compute_link_poses(q, poses);
  // clearance_at starts its queries cold: the same answer to the query tolerance.
  EXPECT_NEAR(no_scene.clearance_at(poses, ClearanceScope::kSelf).distance,
              no_scene.clearance(q).distance, 1e-10);
}

}  // namespace
}  // namespace hullcheck
