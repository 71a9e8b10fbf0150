// CollisionChecker::clearance_lower_bound_batch: never above the clearance, exact below the
// threshold asked for, and the bound path taken where the spheres leave room. Truth: brute force
// over every checked pair on the own arm's scene; on the MotionBenchMaker Panda and UR5 (when
// ../shared is present) clearance(), itself checked against brute force elsewhere. Random
// states and states within a hair of contact, blocks of every size, with the self tables
// measured and with the SIMD forced down to scalar code.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <cstdio>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <random>
#include <string>
#include <vector>

#include "robot_test_support.hpp"
#include "scene_test_support.hpp"

namespace hullcheck {
namespace {

// `count` random states of `group` (others from `base`), then states within a hair of contact:
// both ends of a bisection between a valid and an invalid random state.
Eigen::MatrixXd states_with_contacts(const CollisionChecker& checker, const Eigen::VectorXd& base,
                                     const std::vector<int>& group, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd q(checker.model().variable_count(), count + count / 5);
  for (int k = 0; k < count; ++k) {
    q.col(k) = test::random_configuration(checker.model(), base, group, rng);
  }
  const int filled = test::append_near_contact_states(checker, count, count, 20 * count, q);
  q.conservativeResize(Eigen::NoChange, filled);
  return q;
}

// m: exact queries of one pair started differently agree to about 1e-12 m here.
constexpr double kQueryTolerance = 1e-9;

struct BoundStats {
  long columns = 0, bounded = 0, exact = 0;
};

// Checks lower against `truth` (per column) for threshold `exact_below`: never above the truth,
// min(truth, e) <= lower, and clearance()'s value wherever lower < e (to the exact queries'
// tolerance: the batch query warm-starts its pairs differently).
void check_bounds(const CollisionChecker& checker, const Eigen::MatrixXd& q,
                  const std::vector<double>& truth, double tolerance, double exact_below,
                  BoundStats* stats) {
  std::vector<double> lower(static_cast<std::size_t>(q.cols()));
  checker.clearance_lower_bound_batch(q, exact_below, lower.data());
  const double e = std::max(exact_below, 0.0);
  for (Eigen::Index k = 0; k < q.cols(); ++k) {
    const double l = lower[static_cast<std::size_t>(k)], t = truth[static_cast<std::size_t>(k)];
    ASSERT_LE(l, t + tolerance) << "column " << k << ", q = " << q.col(k).transpose();
    ASSERT_GE(l, std::min(t, e) - tolerance) << "column " << k << ", q = " << q.col(k).transpose();
    if (l < e) {
      ASSERT_NEAR(l, checker.clearance(q.col(k)).distance, kQueryTolerance) << "column " << k;
      ++stats->exact;
    } else if (l < t - 1e-6) {
      ++stats->bounded;
    }
    ++stats->columns;
  }
  // Blocks of every size give the same bounds for their columns.
  for (int n = 1; n <= kPoseBlockLanes + 1 && n <= q.cols(); ++n) {
    std::vector<double> part(static_cast<std::size_t>(n));
    checker.clearance_lower_bound_batch(q.leftCols(n), exact_below, part.data());
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(part[static_cast<std::size_t>(k)], lower[static_cast<std::size_t>(k)]);
    }
  }
}

TEST(ClearanceBoundBatch, OwnArmAgainstBruteForce) {
  const test::ArmInScene w = test::arm_in_scene();
  ASSERT_TRUE(w.scene.allowed_pairs.empty());  // the obstacle brute force checks every pair
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  const Eigen::MatrixXd q =
      states_with_contacts(checker, w.model->default_configuration(), test::all_variables(*w.model),
                           test::sample_count(1500), 31);
  std::vector<double> truth(static_cast<std::size_t>(q.cols()));
  std::vector<Eigen::Isometry3d> poses;
  bool converged = true;
  for (Eigen::Index k = 0; k < q.cols(); ++k) {
    w.model->compute_link_poses(q.col(k), poses);
    Status status = Status::kConverged;
    truth[static_cast<std::size_t>(k)] =
        std::min(test::brute_force_self_clearance(*w.model, w.matrix, poses, &status),
                 test::brute_force_obstacle_clearance(*w.model, w.scene, poses));
    converged = converged && status == Status::kConverged;
  }
  // Deep overlaps may stop EPA at its cap (flagged): near, not equal, there.
  const double tolerance = converged ? kQueryTolerance : 1e-3;
  for (double exact_below : {0.0, 0.01, -1.0}) {
    BoundStats stats;
    check_bounds(checker, q, truth, tolerance, exact_below, &stats);
    std::printf(
        "[ own arm  ] exact_below %g: %ld columns, %ld bounded below the clearance, %ld exact\n",
        exact_below, stats.columns, stats.bounded, stats.exact);
    EXPECT_GT(stats.bounded, stats.columns / 10) << "exact_below " << exact_below;
    EXPECT_GT(stats.exact, stats.columns / 20) << "exact_below " << exact_below;
  }
  // With the SIMD forced down to scalar code: the same bounds to rounding.
  std::vector<double> best(static_cast<std::size_t>(q.cols())),
      scalar(static_cast<std::size_t>(q.cols()));
  checker.clearance_lower_bound_batch(q, 0.0, best.data());
  hwy::SetSupportedTargetsForTest(HWY_SCALAR);
  checker.clearance_lower_bound_batch(q, 0.0, scalar.data());
  hwy::SetSupportedTargetsForTest(0);
  for (std::size_t k = 0; k < best.size(); ++k) EXPECT_NEAR(scalar[k], best[k], 1e-12);
}

// With `tables`, also after measure_self_tables (0.1 s for the Panda, about 2 s for the UR5).
void mbm_bounds(const char* id, int per_family, bool tables) {
  test::MbmRobot found;
  if (!test::find_mbm_robot(id, &found)) GTEST_SKIP() << "MotionBenchMaker " << id << " absent";
  const test::MbmRobot* robot = &found;
  const auto model = test::cached_model(robot->urdf);
  const Srdf srdf = read_srdf_file(robot->srdf);
  const AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_srdf(*model, srdf);
  BoundStats stats;
  std::uint64_t seed = 41;
  for (const std::string& family : robot->families) {
    const PlanningScene scene =
        read_planning_scene(test::mbm_file(*robot, family, "scene", 3), *model);
    const MotionPlanRequest request =
        read_motion_plan_request(test::mbm_file(*robot, family, "request", 3), *model);
    const CollisionChecker checker(model, matrix, scene);
    const std::vector<int> group = group_variables(*model, srdf, request.group);
    const Eigen::MatrixXd q =
        states_with_contacts(checker, request.start, group, test::sample_count(per_family), seed++);
    std::vector<double> truth(static_cast<std::size_t>(q.cols()));
    for (Eigen::Index k = 0; k < q.cols(); ++k) {
      truth[static_cast<std::size_t>(k)] = checker.clearance(q.col(k)).distance;
    }
    check_bounds(checker, q, truth, kQueryTolerance, 0.0, &stats);
    check_bounds(checker, q, truth, kQueryTolerance, 0.02, &stats);
    if (tables) {
      checker.measure_self_tables();  // the tables' bounds join the spheres'
      check_bounds(checker, q, truth, kQueryTolerance, 0.0, &stats);
    }
  }
  std::printf("[ %-8s ] %ld columns, %ld bounded below the clearance, %ld exact\n", id,
              stats.columns, stats.bounded, stats.exact);
  EXPECT_GT(stats.bounded, stats.columns / 10);
  EXPECT_GT(stats.exact, stats.columns / 20);
}

TEST(ClearanceBoundBatch, PandaNeverAboveTheClearance) { mbm_bounds("panda", 300, true); }
TEST(ClearanceBoundBatch, Ur5NeverAboveTheClearance) { mbm_bounds("ur5", 60, false); }

TEST(ClearanceBoundBatch, BadInputIsNamed) {
  const test::ArmInScene w = test::arm_in_scene();
  const CollisionChecker checker(w.model, w.matrix, w.scene);
  Eigen::MatrixXd q = Eigen::MatrixXd::Zero(w.model->variable_count(), 3);
  q(0, 1) = std::nan("");
  double out[3];
  const std::string message =
      test::input_error_of([&] { checker.clearance_lower_bound_batch(q, 0.0, out); });
  EXPECT_NE(message.find("clearance_lower_bound_batch: column 1"), std::string::npos) << message;
  q(0, 1) = 0.0;
  EXPECT_THROW(checker.clearance_lower_bound_batch(q, std::nan(""), out), InputError);
  EXPECT_THROW(checker.clearance_lower_bound_batch(
                   Eigen::MatrixXd::Zero(w.model->variable_count() + 1, 2), 0.0, out),
               InputError);
  checker.clearance_lower_bound_batch(q.leftCols(0), 0.0, out);  // nothing
}

}  // namespace
}  // namespace hullcheck
