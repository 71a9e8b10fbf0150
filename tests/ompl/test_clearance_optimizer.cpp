// optimize_clearance and what it stands on: the validity checker's clearance scope,
// ClearanceMarginObjective's density and cost, and the optimizer's contract on random problems
// (never a higher cost, never an uncertified path, start and goal kept) on the own arm and, when
// ../shared is present, on MotionBenchMaker Panda problems; on the demo problem it must buy
// obstacle clearance.
#include <gtest/gtest.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <hullcheck/ompl.hpp>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "ompl_test_support.hpp"

namespace hullcheck {
namespace {

namespace ob = ::ompl::base;
namespace og = ::ompl::geometric;

/// A robot in a scene with a planning setup whose clearance scope is optimization_scope's.
struct Problem {
  test::LoadedRobot robot;
  std::shared_ptr<const CollisionChecker> checker;
  std::vector<int> group;
  PlanningSetup setup;
  std::shared_ptr<const PairScope> obstacles;  // the robot against the obstacles only
};

Problem make_problem(const test::LoadedRobot& robot, PlanningScene scene, const std::string& group,
                     const Eigen::VectorXd& fixed, double margin) {
  Problem p;
  p.robot = robot;
  p.checker = test::make_checker(robot, std::move(scene));
  p.group = group_variables(*robot.model, robot.srdf, group);
  p.setup = make_planning_setup(p.checker, p.group, fixed);
  p.setup.validity->set_clearance_scope(
      std::make_shared<PairScope>(optimization_scope(*p.checker, p.group, fixed, margin)));
  p.obstacles = std::make_shared<PairScope>(p.checker->pair_scope(ClearanceScope::kObstacles));
  return p;
}

/// RRTConnect from a to b (full configurations); empty path when not solved in `seconds`.
og::PathGeometric plan(Problem& p, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                       double seconds = 2.0) {
  og::SimpleSetup& ss = *p.setup.setup;
  ss.clear();
  ss.setStartAndGoalStates(p.setup.state(a), p.setup.state(b));
  ss.setPlanner(std::make_shared<og::RRTConnect>(ss.getSpaceInformation()));
  if (ss.solve(seconds) != ob::PlannerStatus::EXACT_SOLUTION) {
    return og::PathGeometric(ss.getSpaceInformation());
  }
  return ss.getSolutionPath();
}

/// Minimum obstacle clearance over the middle 80% of the path (start and goal cannot move):
/// states 20 .. 180 of 201 evenly spaced along its length.
double middle_obstacle_clearance(const Problem& p, const og::PathGeometric& path) {
  og::PathGeometric dense(path);
  dense.interpolate(201);
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 20; i <= 180; ++i) {
    m = std::min(
        m, p.checker->clearance(p.setup.configuration(dense.getState(i)), *p.obstacles).distance);
  }
  return m;
}

/// The optimizer's contract on one run (gtest failures when broken).
void expect_contract(const Problem& p, const og::PathGeometric& input,
                     const og::PathGeometric& output, const ClearanceOptimizationResult& r,
                     const ClearanceOptimizationOptions& options) {
  const ob::SpaceInformationPtr& si = p.setup.setup->getSpaceInformation();
  // The cost recomputed with a fresh objective of the same settings: never higher.
  const auto objective =
      std::make_shared<ClearanceMarginObjective>(si, options.margin, options.length_weight);
  const double before = input.cost(objective).value(), after = output.cost(objective).value();
  EXPECT_EQ(r.cost_before, before);
  EXPECT_EQ(r.cost_after, after);
  EXPECT_LE(after, before);
  EXPECT_EQ(r.length_before, input.length());
  EXPECT_EQ(r.length_after, output.length());
  EXPECT_GE(r.seconds, 0.0);
  // Start and goal kept.
  ASSERT_GE(output.getStateCount(), 2u);
  EXPECT_TRUE(si->equalStates(output.getState(0), input.getState(0)));
  EXPECT_TRUE(si->equalStates(output.getState(output.getStateCount() - 1),
                              input.getState(input.getStateCount() - 1)));
  if (!r.changed) {
    ASSERT_EQ(output.getStateCount(), input.getStateCount());
    for (std::size_t i = 0; i < output.getStateCount(); ++i) {
      EXPECT_TRUE(si->equalStates(output.getState(i), input.getState(i)));
    }
    return;
  }
  // Changed: every motion certified, and free at dense exact re-checks (5 mm of joint space).
  for (std::size_t i = 0; i + 1 < output.getStateCount(); ++i) {
    const ob::State* a = output.getState(i);
    const ob::State* b = output.getState(i + 1);
    EXPECT_TRUE(si->satisfiesBounds(b)) << "state " << i + 1;
    EXPECT_TRUE(si->checkMotion(a, b)) << "motion " << i;
    const int samples = std::clamp(static_cast<int>(std::ceil(si->distance(a, b) / 0.005)), 8, 400);
    EXPECT_TRUE(test::dense_check(*si, *p.setup.validity, a, b, samples).valid) << "motion " << i;
  }
}

/// One seeded run of the demo pipeline: RRTConnect from a to b, shortcuts, optimize_clearance
/// (its contract checked); the middle obstacle clearance of the path before and after.
struct SeededRun {
  ClearanceOptimizationResult result;
  double before = 0.0, after = 0.0;
};
void plan_and_optimize(Problem& p, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                       unsigned seed, const ClearanceOptimizationOptions& options,
                       const char* label, SeededRun& run) {
  test::reseed_ompl(seed);
  og::PathGeometric path = plan(p, a, b, 5.0);
  ASSERT_GE(path.getStateCount(), 2u);
  p.setup.setup->getPathSimplifier()->simplifyMax(path);
  const og::PathGeometric input(path);
  const ClearanceOptimizationResult& r = run.result =
      optimize_clearance(p.setup.setup->getSpaceInformation(), *p.setup.validity, path, options);
  expect_contract(p, input, path, r, options);
  run.before = middle_obstacle_clearance(p, input);
  run.after = middle_obstacle_clearance(p, path);
  std::printf(
      "[%s seed %u] middle obstacle clearance %.4f -> %.4f m, length %.3f -> %.3f, %d rounds, "
      "%d moves, %d added, %.1f ms\n",
      label, seed, run.before, run.after, r.length_before, r.length_after, r.rounds, r.moves,
      r.refined, 1e3 * r.seconds);
}

// ---------------------------------------------------------------------------- scope, objective

class OwnArm : public ::testing::Test {
 protected:
  void SetUp() override {
    robot_ = test::load_robot(test::own_arm());
    start_ = robot_.model->default_configuration();
    const std::vector<int> group = group_variables(*robot_.model, robot_.srdf, "arm");
    const double pose[] = {0.5, 0.5, 0.0, -1.3, 0.0, 1.2, 0.0};
    for (int i = 0; i < 7; ++i) start_[group[static_cast<std::size_t>(i)]] = pose[i];
    goal_ = start_;
    goal_[group[0]] = -0.5;
    p_ = make_problem(robot_, read_planning_scene(test::own_arm_scene(), *robot_.model), "arm",
                      start_, 0.05);
  }

  test::LoadedRobot robot_;
  Eigen::VectorXd start_, goal_;
  Problem p_;
};

TEST_F(OwnArm, ValidityClearanceFollowsItsScopeValidityDoesNot) {
  StateValidityChecker& validity = *p_.setup.validity;
  ASSERT_NE(validity.clearance_scope(), nullptr);
  const PairScope& scope = *validity.clearance_scope();
  const ob::SpaceInformationPtr& si = p_.setup.setup->getSpaceInformation();
  test::StateSampler sampler(*p_.setup.joints, 5);
  ob::State* s = si->allocState();
  Eigen::VectorXd q;
  int narrower = 0, invalid = 0;
  for (int n = 0; n < 200; ++n) {
    sampler.uniform(s);
    q = p_.setup.configuration(s);
    const double scoped = p_.checker->clearance(q, scope).distance;
    EXPECT_EQ(validity.clearance(s), scoped);
    EXPECT_EQ(validity.closest(s).distance, scoped);
    double dist = 0.0;
    const bool valid = validity.isValid(s, dist);
    EXPECT_EQ(dist, scoped);
    // Validity over every checked pair, whatever the scope.
    EXPECT_EQ(valid, p_.checker->is_valid(q));
    EXPECT_EQ(validity.isValid(s), p_.checker->is_valid(q));
    narrower += scoped > p_.checker->clearance(q).distance;
    invalid += !valid;
  }
  // The scope leaves out pairs that are the closest somewhere (link1 - link3 among them).
  EXPECT_GT(narrower, 0);
  EXPECT_GT(invalid, 0);
  // Back to every pair.
  validity.set_clearance_scope(nullptr);
  EXPECT_EQ(validity.clearance(s), p_.checker->clearance(q).distance);
  si->freeState(s);
  // A scope of another checker is rejected when set.
  test::LoadedRobot other = test::load_robot(test::own_arm());
  const auto other_checker = test::make_checker(other, PlanningScene{});
  EXPECT_THROW(validity.set_clearance_scope(
                   std::make_shared<PairScope>(other_checker->pair_scope(ClearanceScope::kAll))),
               InputError);
}

TEST_F(OwnArm, ClearanceMarginObjectiveIsLengthPlusHinge) {
  const ob::SpaceInformationPtr& si = p_.setup.setup->getSpaceInformation();
  const double margin = 0.05, w = 0.1;
  ClearanceMarginObjective objective(si, margin, w);
  EXPECT_EQ(objective.margin(), margin);
  EXPECT_EQ(objective.length_weight(), w);
  EXPECT_DOUBLE_EQ(objective.density(1.0), w);
  EXPECT_DOUBLE_EQ(objective.density(margin), w);
  EXPECT_DOUBLE_EQ(objective.density(0.0), w + 1.0);
  EXPECT_DOUBLE_EQ(objective.density(0.02), w + 0.6);
  EXPECT_DOUBLE_EQ(objective.density(-0.01), w + 1.2);
  const auto a = p_.setup.state(start_);
  EXPECT_DOUBLE_EQ(objective.stateCost(a.get()).value(),
                   objective.density(p_.setup.validity->clearance(a.get())));
  // A motion's cost: the integral of the density over its length, approached by a dense sum.
  Eigen::VectorXd q = start_;
  q[p_.group[0]] += 0.3;
  const auto b = p_.setup.state(q);
  const double cost = objective.motionCost(a.get(), b.get()).value();
  const int n = 2000;
  double sum = 0.0;
  ob::State* s = si->allocState();
  for (int i = 0; i < n; ++i) {
    si->getStateSpace()->interpolate(a.get(), b.get(), (i + 0.5) / n, s);
    sum += objective.density(p_.setup.validity->clearance(s));
  }
  si->freeState(s);
  const double integral = sum / n * si->distance(a.get(), b.get());
  EXPECT_NEAR(cost, integral, 0.02 * integral);
  EXPECT_THROW(ClearanceMarginObjective(si, 0.0, w), InputError);
  EXPECT_THROW(ClearanceMarginObjective(si, -0.1, w), InputError);
  EXPECT_THROW(ClearanceMarginObjective(si, NAN, w), InputError);
  EXPECT_THROW(ClearanceMarginObjective(si, margin, -1.0), InputError);
  EXPECT_THROW(ClearanceMarginObjective(si, margin, INFINITY), InputError);
}

// ---------------------------------------------------------------------------- optimizer

TEST_F(OwnArm, RejectsBadOptionsAndForeignPaths) {
  const ob::SpaceInformationPtr& si = p_.setup.setup->getSpaceInformation();
  og::PathGeometric path(si, p_.setup.state(start_).get(), p_.setup.state(start_).get());
  const auto bad = [&](auto change) {
    ClearanceOptimizationOptions o;
    change(o);
    EXPECT_THROW(optimize_clearance(si, *p_.setup.validity, path, o), InputError);
  };
  bad([](auto& o) { o.margin = 0.0; });
  bad([](auto& o) { o.margin = NAN; });
  bad([](auto& o) { o.length_weight = -0.1; });
  bad([](auto& o) { o.time = 0.0; });
  bad([](auto& o) { o.time = INFINITY; });
  bad([](auto& o) { o.waypoint_spacing = 0.0; });
  bad([](auto& o) { o.max_waypoints = 2; });
  bad([](auto& o) { o.max_step = -1.0; });
  // A path of another space information.
  Problem other = make_problem(robot_, PlanningScene{}, "arm", start_, 0.05);
  og::PathGeometric foreign(other.setup.setup->getSpaceInformation(),
                            other.setup.state(start_).get(), other.setup.state(goal_).get());
  EXPECT_THROW(optimize_clearance(si, *p_.setup.validity, foreign), InputError);
  EXPECT_THROW(optimize_clearance(si, *other.setup.validity, path), InputError);
}

TEST_F(OwnArm, DemoProblemGainsObstacleClearance) {
  // RRTConnect + shortcuts over the wall, several seeds: wherever the shortened path comes
  // within the margin of an obstacle, the optimizer at least doubles that clearance or brings it
  // to 80% of the margin, for at most 1.3 times the length.
  const ClearanceOptimizationOptions options;
  int within_margin = 0;
  for (unsigned seed = 1; seed <= static_cast<unsigned>(test::scaled(6, 2)); ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    SeededRun run;
    ASSERT_NO_FATAL_FAILURE(plan_and_optimize(p_, start_, goal_, seed, options, "demo", run));
    EXPECT_GE(run.after, std::min(2.0 * run.before, 0.8 * options.margin));
    EXPECT_LE(run.result.length_after, 1.3 * run.result.length_before);
    within_margin += run.before < options.margin;
  }
  EXPECT_GT(within_margin, 0);
}

TEST(OwnArmShelf, DemoKeepsTheMarginAlongTheMiddle) {
  // The README demo (scene shelf.yaml, shelf_low -> shelf_high), several seeds, a budget long
  // enough that the optimizer stops because it converged: the path's middle 80% keeps 80% of
  // the margin from every obstacle in the median run and half of it in every run (or doubles a
  // clearance that was already higher), including between waypoints, where refinement splits
  // motions that dip.
  const test::LoadedRobot robot = test::load_robot(test::own_arm());
  const Eigen::VectorXd zero = robot.model->default_configuration();
  const Eigen::VectorXd low =
      group_state_configuration(*robot.model, robot.srdf, "arm", "shelf_low", zero);
  const Eigen::VectorXd high =
      group_state_configuration(*robot.model, robot.srdf, "arm", "shelf_high", zero);
  ClearanceOptimizationOptions options;
  options.time = 2.0;
  Problem p = make_problem(
      robot,
      read_planning_scene(test::robots_dir() + "/hullcheck_arm/scenes/shelf.yaml", *robot.model),
      "arm", low, options.margin);
  std::vector<double> middles;
  int refined = 0;
  for (unsigned seed = 1; seed <= static_cast<unsigned>(test::scaled(6, 2)); ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    SeededRun run;
    ASSERT_NO_FATAL_FAILURE(plan_and_optimize(p, low, high, seed, options, "shelf", run));
    EXPECT_LT(run.result.seconds, options.time);  // converged, not cut short
    EXPECT_GE(run.after, std::min(2.0 * run.before, 0.5 * options.margin));
    middles.push_back(run.after);
    refined += run.result.refined;
  }
  std::nth_element(middles.begin(), middles.begin() + middles.size() / 2, middles.end());
  EXPECT_GE(middles[middles.size() / 2], 0.8 * options.margin);
  EXPECT_GT(refined, 0);
}

TEST_F(OwnArm, NeverWorseNeverUncertifiedOnRandomProblems) {
  test::reseed_ompl(11);
  const ob::SpaceInformationPtr& si = p_.setup.setup->getSpaceInformation();
  test::StateSampler sampler(*p_.setup.joints, 17);
  std::mt19937_64& rng = sampler.rng();
  ob::State* a = si->allocState();
  ob::State* b = si->allocState();
  int optimised = 0, changed = 0, clearer = 0;
  const int problems = test::scaled(12, 3);
  for (int n = 0; n < problems; ++n) {
    if (!test::sample_valid(*si, sampler, a) || !test::sample_valid(*si, sampler, b)) continue;
    og::PathGeometric path = plan(p_, p_.setup.configuration(a), p_.setup.configuration(b));
    if (path.getStateCount() < 2) continue;
    // Raw and simplified RRTConnect paths, and options drawn at random.
    if (n % 2 == 1) p_.setup.setup->getPathSimplifier()->simplifyMax(path);
    ClearanceOptimizationOptions options;
    options.margin = std::uniform_real_distribution<double>(0.01, 0.15)(rng);
    options.length_weight = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    options.time = n % 3 == 0 ? 0.005 : 0.2;
    options.max_waypoints = 3 + static_cast<int>(rng() % 60);
    p_.setup.validity->set_clearance_scope(std::make_shared<PairScope>(
        optimization_scope(*p_.checker, p_.group, start_, options.margin)));
    const og::PathGeometric input(path);
    SCOPED_TRACE("problem " + std::to_string(n));
    const ClearanceOptimizationResult r = optimize_clearance(si, *p_.setup.validity, path, options);
    expect_contract(p_, input, path, r, options);
    ++optimised;
    changed += r.changed;
    clearer += r.min_clearance_after > r.min_clearance_before;
  }
  si->freeState(a);
  si->freeState(b);
  std::printf("[random] %d optimised, %d changed, %d with a clearer closest waypoint\n", optimised,
              changed, clearer);
  EXPECT_GE(optimised, problems / 2);
  EXPECT_GT(changed, 0);
}

TEST_F(OwnArm, InvalidInputIsNeverReturnedChangedAndUncertified) {
  // The straight motion goes through the wall: the optimizer may keep it (unchanged) or
  // return a path whose every motion is certified, never a changed uncertified one.
  const ob::SpaceInformationPtr& si = p_.setup.setup->getSpaceInformation();
  og::PathGeometric path(si, p_.setup.state(start_).get(), p_.setup.state(goal_).get());
  ASSERT_FALSE(si->checkMotion(path.getState(0), path.getState(1)));
  const og::PathGeometric input(path);
  const ClearanceOptimizationOptions options;
  const ClearanceOptimizationResult r = optimize_clearance(si, *p_.setup.validity, path, options);
  expect_contract(p_, input, path, r, options);
}

// ---------------------------------------------------------------------------- MotionBenchMaker

TEST(MbmClearanceOptimizer, PandaProblemsKeepTheContract) {
  const auto file = test::mbm_robot("panda");
  if (!file) GTEST_SKIP() << "shared benchmarks absent";
  const test::LoadedRobot robot = test::load_robot(*file);
  int optimised = 0, clearer = 0;
  for (const std::string& family : test::mbm_families()) {
    if (optimised >= test::scaled(4, 1)) break;
    const MotionPlanRequest request =
        read_motion_plan_request(test::mbm_file("panda", family, 1, "request"), *robot.model);
    Problem p = make_problem(
        robot, read_planning_scene(test::mbm_file("panda", family, 1, "scene"), *robot.model),
        request.group, request.start, 0.05);
    const ob::SpaceInformationPtr& si = p.setup.setup->getSpaceInformation();
    if (!si->isValid(p.setup.state(request.start).get()) ||
        !si->isValid(p.setup.state(request.goal).get())) {
      continue;
    }
    test::reseed_ompl(1);
    og::PathGeometric path = plan(p, request.start, request.goal, 5.0);
    if (path.getStateCount() < 2) continue;
    p.setup.setup->getPathSimplifier()->simplifyMax(path);
    const og::PathGeometric input(path);
    const ClearanceOptimizationOptions options;
    SCOPED_TRACE(family);
    const ClearanceOptimizationResult r = optimize_clearance(si, *p.setup.validity, path, options);
    expect_contract(p, input, path, r, options);
    const double before = middle_obstacle_clearance(p, input);
    const double after = middle_obstacle_clearance(p, path);
    std::printf(
        "[panda %s] middle obstacle clearance %.4f -> %.4f m, length %.3f -> %.3f, %.1f ms\n",
        family.c_str(), before, after, r.length_before, r.length_after, 1e3 * r.seconds);
    ++optimised;
    clearer += after > before;
  }
  EXPECT_GT(optimised, 0);
  EXPECT_GT(clearer, 0);
}

}  // namespace
}  // namespace hullcheck
