// CollisionChecker::is_valid_batch against is_valid, column by column: random states of every
// MotionBenchMaker family (Panda, UR5) and states within a hair of contact (the two ends of a
// bisection between a valid and an invalid state), blocks of every size, on the best SIMD
// target and with the SIMD forced down to scalar code (a CPU without AVX2).
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <chrono>
#include <cstdio>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "scene_test_support.hpp"

namespace hullcheck {
namespace {

using Clock = std::chrono::steady_clock;

struct BatchStats {
  long states = 0, valid = 0, near_contact = 0, mismatches = 0;
  double batch_seconds = 0.0, scalar_seconds = 0.0;
};

// `states` random configurations of the request's group (the rest from its start state), then
// 2 x `boundary` states straddling contact, checked both ways.
void compare(const CollisionChecker& checker, const MotionPlanRequest& request,
             const std::vector<int>& group, int states, int boundary, std::uint64_t seed,
             BatchStats* stats) {
  const RobotModel& model = checker.model();
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd q(model.variable_count(), states + 2 * boundary);
  for (int k = 0; k < states; ++k) {
    q.col(k) = test::random_configuration(model, request.start, group, rng);
  }
  // Near contact: bisect between a valid and an invalid random state down to 1e-12 of the
  // segment; both ends are within a hair of touching.
  const int filled = test::append_near_contact_states(checker, states, states, 100 * boundary, q);
  q.conservativeResize(Eigen::NoChange, filled);
  stats->near_contact += filled - states;
  std::vector<char> scalar(static_cast<std::size_t>(filled));
  auto t0 = Clock::now();
  for (int k = 0; k < filled; ++k) scalar[static_cast<std::size_t>(k)] = checker.is_valid(q.col(k));
  stats->scalar_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
  std::unique_ptr<bool[]> batch(new bool[static_cast<std::size_t>(filled)]);
  // Not timed: the first call builds the checker's batch tables (once per checker).
  checker.is_valid_batch(q.leftCols(1), batch.get());
  t0 = Clock::now();
  checker.is_valid_batch(q, batch.get());
  stats->batch_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
  for (int k = 0; k < filled; ++k) {
    stats->valid += scalar[static_cast<std::size_t>(k)] ? 1 : 0;
    if (batch[static_cast<std::size_t>(k)] !=
        static_cast<bool>(scalar[static_cast<std::size_t>(k)])) {
      if (stats->mismatches++ < 5) {
        ADD_FAILURE() << "column " << k << ": batch " << batch[static_cast<std::size_t>(k)]
                      << ", is_valid " << static_cast<bool>(scalar[static_cast<std::size_t>(k)])
                      << "\nq = " << q.col(k).transpose();
      }
    }
  }
  // Blocks of every size: a batch of one to kPoseBlockLanes + 1 columns.
  for (int n = 1; n <= kPoseBlockLanes + 1 && n <= filled; ++n) {
    checker.is_valid_batch(q.leftCols(n), batch.get());
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(batch[static_cast<std::size_t>(k)],
                static_cast<bool>(scalar[static_cast<std::size_t>(k)]));
    }
  }
  stats->states += filled;
}

void batch_agrees(const char* id, int per_family) {
  test::MbmRobot found;
  if (!test::find_mbm_robot(id, &found)) GTEST_SKIP() << "MotionBenchMaker " << id << " absent";
  const test::MbmRobot* robot = &found;
  const auto model = test::cached_model(robot->urdf);
  const Srdf srdf = read_srdf_file(robot->srdf);
  const AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_srdf(*model, srdf);
  // Under ASan a fiftieth (the UR5's exact tests dominate there: 39 s at a tenth).
  const int states = test::sample_count(per_family / (test::kSanitizerDivisor > 1 ? 5 : 1),
                                        "HULLCHECK_BATCH_STATES");
  BatchStats best, scalar_only;
  std::uint64_t seed = 1;
  for (const std::string& family : robot->families) {
    const PlanningScene scene =
        read_planning_scene(test::mbm_file(*robot, family, "scene", 5), *model);
    const MotionPlanRequest request =
        read_motion_plan_request(test::mbm_file(*robot, family, "request", 5), *model);
    const CollisionChecker checker(model, matrix, scene);
    const std::vector<int> group = group_variables(*model, srdf, request.group);
    compare(checker, request, group, states, std::max(1, states / 100), seed++, &best);
    // The same with the SIMD forced down to plain scalar code.
    hwy::SetSupportedTargetsForTest(HWY_SCALAR);
    compare(checker, request, group, std::max(1, states / 20), std::max(1, states / 1000), seed++,
            &scalar_only);
    hwy::SetSupportedTargetsForTest(0);
  }
  std::printf(
      "[ %-8s ] %ld states (%ld valid, %ld within a hair of contact) in %zu families: %ld "
      "mismatches; is_valid %.0f ns/state, is_valid_batch %.0f ns/state. Scalar SIMD target: "
      "%ld states, %ld mismatches\n",
      id, best.states, best.valid, best.near_contact, robot->families.size(), best.mismatches,
      1e9 * best.scalar_seconds / best.states, 1e9 * best.batch_seconds / best.states,
      scalar_only.states, scalar_only.mismatches);
  EXPECT_EQ(best.mismatches, 0);
  EXPECT_EQ(scalar_only.mismatches, 0);
  EXPECT_GT(best.valid, 0);
  EXPECT_LT(best.valid, best.states);
}

TEST(BatchValidity, PandaEqualsIsValid) { batch_agrees("panda", 100000); }
TEST(BatchValidity, Ur5EqualsIsValid) { batch_agrees("ur5", 100000); }

TEST(BatchValidity, BadInputNamesTheColumn) {
  const auto robots = test::mbm_robots();
  if (robots.empty()) GTEST_SKIP() << "MotionBenchMaker absent";
  const auto model = test::cached_model(robots.front().urdf);
  const CollisionChecker checker(model,
                                 AllowedCollisionMatrix(static_cast<int>(model->links().size())));
  Eigen::MatrixXd q = Eigen::MatrixXd::Zero(model->variable_count(), 3);
  q(0, 2) = std::nan("");
  bool out[3];
  const std::string message = test::input_error_of([&] { checker.is_valid_batch(q, out); });
  EXPECT_NE(message.find("column 2"), std::string::npos) << message;
  EXPECT_THROW(checker.is_valid_batch(Eigen::MatrixXd::Zero(model->variable_count() + 1, 2), out),
               InputError);
  checker.is_valid_batch(Eigen::MatrixXd::Zero(model->variable_count(), 0), out);  // nothing
}

}  // namespace
}  // namespace hullcheck
