// CollisionChecker's warm-start grids (self pairs moved by at most two configuration values):
// clearance(q), which starts those pairs' GJK from the grid, against a brute force over every
// checked self pair with hullcheck::signed_distance (cold), on the own arm with only adjacent
// links allowed: its wrist pairs are keyed by a revolute and a continuous joint, its fingers by
// one prismatic value (the second finger mimics the first). States within the limits, beyond
// them (edge cells), and with the continuous joint turned by whole turns (wrap-around).
#include <gtest/gtest.h>

#include <cmath>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <memory>
#include <random>
#include <vector>

#include "robot_test_support.hpp"
#include "scene_test_support.hpp"

namespace hullcheck {
namespace {

struct OwnArm {
  std::shared_ptr<const RobotModel> model;
  AllowedCollisionMatrix matrix;
};

OwnArm own_arm_adjacent_allowed() {
  OwnArm arm;
  arm.model = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(test::own_arm().urdf));
  arm.matrix = AllowedCollisionMatrix::from_adjacency(*arm.model);
  return arm;
}

// Every value drawn within its limits (continuous in [-pi, pi]), then pushed beyond them by up
// to `beyond` of the range (0: within), the continuous ones turned by `turns` whole turns.
Eigen::VectorXd draw(const RobotModel& model, std::mt19937_64& rng, double beyond, int turns) {
  Eigen::VectorXd q = test::random_configuration(model, rng);
  const Eigen::VectorXd lo = model.lower_limits(), hi = model.upper_limits();
  std::uniform_real_distribution<double> push(-beyond, beyond);
  for (int v = 0; v < model.variable_count(); ++v) {
    if (std::isfinite(lo[v]) && std::isfinite(hi[v])) {
      const double range = hi[v] - lo[v];
      const double p = push(rng) * range;
      q[v] = p < 0.0 ? lo[v] + p : p > 0.0 ? hi[v] + p : q[v];
    } else {
      q[v] += 2.0 * M_PI * turns;
    }
  }
  return q;
}

TEST(ClearanceWarmStart, AgreesWithColdBruteForce) {
  const OwnArm arm = own_arm_adjacent_allowed();
  const CollisionChecker checker(arm.model, arm.matrix, PlanningScene{});
  std::mt19937_64 rng(17);
  std::vector<Eigen::Isometry3d> poses;
  int overlapping = 0, apart = 0, flagged_states = 0;
  struct Set {
    double beyond;
    int turns;
  };
  for (const Set set : {Set{0.0, 0}, Set{0.3, 0}, Set{0.0, 3}, Set{0.0, -2}}) {
    for (int n = 0; n < 300; ++n) {
      const Eigen::VectorXd q = draw(*arm.model, rng, set.beyond, set.turns);
      arm.model->compute_link_poses(q, poses);
      const ClearanceResult c = checker.clearance(q);
      Status brute_status = Status::kConverged;
      const double brute =
          test::brute_force_self_clearance(*arm.model, arm.matrix, poses, &brute_status);
      // Both within the query tolerance (1e-10 x size, the arm is about 1 m) of the truth when
      // both converged. EPA may stop at its storage cap on deep overlaps of vertex-rich pieces
      // of decomposed links (flagged kIterationCap, the best depth so far): then both are
      // lower bounds on the depth, and near each other.
      const bool flagged = c.status != Status::kConverged || brute_status != Status::kConverged;
      flagged_states += flagged;
      ASSERT_NEAR(c.distance, brute, flagged ? 1e-3 : 2e-10)
          << "beyond " << set.beyond << ", turns " << set.turns << ", q = " << q.transpose();
      ASSERT_NEAR((c.point_b - c.point_a).dot(c.normal), c.distance, 1e-9);
      (c.distance < 0.0 ? overlapping : apart) += 1;
    }
  }
  EXPECT_LT(flagged_states, overlapping / 10);
  EXPECT_GT(overlapping, 50);  // both signs, so EPA from a grid simplex is exercised too
  EXPECT_GT(apart, 50);
}

// The grid is what makes clearance(q) cheaper than clearance_at(poses), which has no
// configuration to look up and starts cold: fewer GJK/EPA iterations over the same states,
// with turned continuous joints finding the same cells as unturned ones.
TEST(ClearanceWarmStart, SavesIterations) {
  const OwnArm arm = own_arm_adjacent_allowed();
  const CollisionChecker checker(arm.model, arm.matrix, PlanningScene{});
  std::mt19937_64 rng(23);
  std::vector<Eigen::Isometry3d> poses;
  long warm = 0, cold = 0, turned = 0;
  int turned_differs = 0;  // states whose turned twin took another number of iterations
  for (int n = 0; n < 1000; ++n) {
    const Eigen::VectorXd q = draw(*arm.model, rng, 0.0, 0);
    Eigen::VectorXd q_turned = q;
    for (int v = 0; v < arm.model->variable_count(); ++v) {
      if (!std::isfinite(arm.model->lower_limits()[v])) q_turned[v] += 4.0 * M_PI;
    }
    arm.model->compute_link_poses(q, poses);
    const int w = checker.clearance(q).iterations;
    const int t = checker.clearance(q_turned).iterations;
    warm += w;
    turned += t;
    turned_differs += w != t ? 1 : 0;
    cold += checker.clearance_at(poses).iterations;
  }
  std::printf(
      "[ warm     ] iterations per state: grid %.2f, cold %.2f, turned by 2 turns %.2f (%d "
      "states differ)\n",
      warm / 1000.0, cold / 1000.0, turned / 1000.0, turned_differs);
  EXPECT_LT(warm, 0.8 * cold);
  // The same cell, so the same start: the poses differ by rounding only, which changes the
  // count now and then.
  EXPECT_LE(turned_differs, 20);  // measured: 0 (a grid without wrap-around: 43)
}

}  // namespace
}  // namespace hullcheck
