// Planning with hullcheck in OMPL: RRTConnect on MotionBenchMaker problems (Panda, UR5) set up
// from their request files, every returned path re-validated (guaranteed motion check of every
// segment and a dense re-check); clearance objectives; objective-aware simplification; pushing
// waypoints away from obstacles; multi-threaded planning (OmplThreads*, run under TSan by CI).
#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/tools/multiplan/ParallelPlan.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <hullcheck/ompl.hpp>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "ompl_test_support.hpp"

namespace hullcheck {
namespace {

namespace ob = ::ompl::base;
namespace og = ::ompl::geometric;
using test::LoadedRobot;

// OMPL's informational messages would drown the test output.
struct QuietOmpl {
  QuietOmpl() { ::ompl::msg::setLogLevel(::ompl::msg::LOG_WARN); }
};
const QuietOmpl quiet_ompl;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Time limits in CPU seconds of the planning thread: a loaded CI machine (tests run in
// parallel) must not turn a solvable problem into a failure.
ob::PlannerTerminationCondition cpu_time_limit(double seconds) {
  const double end = thread_cpu_seconds() + seconds;
  return ob::PlannerTerminationCondition([end] { return thread_cpu_seconds() > end; });
}

// Every segment passes the guaranteed motion check again and a dense re-check (one state per
// `resolution` of the space's distance, at least 20 per segment); returns the smallest
// clearance seen.
double expect_path_valid(const PlanningSetup& setup, const og::PathGeometric& path,
                         double resolution = 0.005) {
  const ob::SpaceInformationPtr& si = setup.setup->getSpaceInformation();
  const auto* mv = dynamic_cast<const GuaranteedMotionValidator*>(si->getMotionValidator().get());
  EXPECT_NE(mv, nullptr);
  double min_clearance = std::numeric_limits<double>::infinity();
  EXPECT_GE(path.getStateCount(), 2u);
  for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
    const ob::State* a = path.getState(i);
    const ob::State* b = path.getState(i + 1);
    EXPECT_TRUE(si->satisfiesBounds(b)) << "state " << i + 1;
    EXPECT_TRUE(mv != nullptr && mv->checkMotion(a, b)) << "segment " << i;
    const int samples =
        std::clamp(static_cast<int>(std::ceil(si->distance(a, b) / resolution)), 20, 2000);
    const test::DenseCheck d = test::dense_check(*si, *setup.validity, a, b, samples);
    EXPECT_TRUE(d.valid) << "segment " << i << " collides at t = " << d.first_invalid;
    min_clearance = std::min(min_clearance, d.min_clearance);
  }
  return min_clearance;
}

using test::reseed_ompl;

// ---------------------------------------------------------------------------- MBM problems

struct Problem {
  std::string family;
  int index = 0;
  bool solved = false;
  double seconds = 0.0, cpu_seconds = 0.0;
  std::size_t states = 0;
  double cost_before = 0.0, cost_after = 0.0;
  double length = 0.0, min_clearance = 0.0;
  int skipped = 0;  // problems of the family passed over (invalid start or goal)
};

class MbmPlanning : public ::testing::TestWithParam<const char*> {};

// The fixed sample: per family, the problems tried in order; the first whose start and goal
// are valid under our collision model is planned (the others are counted as skipped; UR5
// table_under_pick 1 has an invalid start). Problem 1 of each family, except where RRTConnect
// with the guaranteed validator needs over a second of CPU for it (seed 1): Panda
// bookshelf_tall 1 and cage 1 (1.2-1.5 s) and UR5 cage 1 (over 5 s; with OMPL's discrete
// validator it takes 0.05-0.3 s, and those paths pass the guaranteed check).
struct FamilySample {
  const char* family;
  std::vector<int> problems;
};

const std::vector<FamilySample>& mbm_sample(const std::string& robot) {
  static const std::vector<FamilySample> panda = {{"bookshelf_small", {1, 2}},
                                                  {"bookshelf_tall", {4, 3}},
                                                  {"bookshelf_thin", {1, 2}},
                                                  {"box", {1, 2}},
                                                  {"cage", {7, 4}},
                                                  {"table_pick", {1, 2}},
                                                  {"table_under_pick", {1, 2}}};
  static const std::vector<FamilySample> ur5 = {{"bookshelf_small", {1, 2}},
                                                {"bookshelf_tall", {1, 2}},
                                                {"bookshelf_thin", {1, 2}},
                                                {"box", {1, 2}},
                                                {"cage", {3, 5}},
                                                {"table_pick", {1, 2}},
                                                {"table_under_pick", {1, 2}}};
  return robot == "panda" ? panda : ur5;
}

// RRTConnect, 5 s of planning-thread CPU time per problem, set up from the request file: the
// group from its group name through the SRDF, the other joints held at its start.
TEST_P(MbmPlanning, RrtConnectSolvesOneProblemPerFamily) {
  const std::string robot_name = GetParam();
  const auto file = test::mbm_robot(robot_name);
  if (!file) GTEST_SKIP() << "shared benchmarks absent";
  const LoadedRobot robot = test::load_robot(*file);
  const RobotModel& model = *robot.model;
  std::vector<FamilySample> families = mbm_sample(robot_name);
  families.resize(static_cast<std::size_t>(test::scaled(7, 2)));
  std::vector<Problem> problems;
  for (const FamilySample& family : families) {
    SCOPED_TRACE(family.family);
    Problem p;
    p.family = family.family;
    for (int index : family.problems) {
      const MotionPlanRequest request =
          read_motion_plan_request(test::mbm_file(robot_name, p.family, index, "request"), model);
      // The goal constrains exactly the group's joints.
      const std::vector<int> group = group_variables(model, robot.srdf, request.group);
      std::vector<int> goal_vars = request.goal_variables;
      std::sort(goal_vars.begin(), goal_vars.end());
      EXPECT_EQ(goal_vars, group);
      auto checker = test::make_checker(
          robot, read_planning_scene(test::mbm_file(robot_name, p.family, index, "scene"), model));
      reseed_ompl(1);  // each problem planned the same way, whatever ran before
      PlanningSetup setup = make_planning_setup(checker, group, request.start);
      const ob::SpaceInformationPtr& si = setup.setup->getSpaceInformation();
      const auto start = setup.state(request.start), goal = setup.state(request.goal);
      if (!si->isValid(start.get()) || !si->isValid(goal.get()) ||
          !si->satisfiesBounds(start.get()) || !si->satisfiesBounds(goal.get())) {
        ++p.skipped;
        continue;
      }
      p.index = index;
      setup.setup->setStartAndGoalStates(start, goal);
      setup.setup->setPlanner(std::make_shared<og::RRTConnect>(si));
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = thread_cpu_seconds();
      const ob::PlannerStatus status = setup.setup->solve(cpu_time_limit(test::scaled(5, 50)));
      p.cpu_seconds = thread_cpu_seconds() - c0;
      p.seconds = seconds_since(t0);
      p.solved = status == ob::PlannerStatus::EXACT_SOLUTION;
      EXPECT_TRUE(p.solved) << robot_name << " " << p.family << " problem " << index << ": "
                            << status.asString();
      if (!p.solved) break;
      og::PathGeometric& path = setup.setup->getSolutionPath();
      p.states = path.getStateCount();
      p.length = path.length();
      EXPECT_EQ(setup.configuration(path.getState(0)), request.start);
      EXPECT_TRUE(si->equalStates(path.getState(path.getStateCount() - 1), goal.get()));
      p.min_clearance = expect_path_valid(setup, path);
      EXPECT_GT(p.min_clearance, 0.0);
      // Objective-aware simplification of a real path: not worse for its objective, valid.
      const ob::OptimizationObjectivePtr objective =
          make_length_clearance_objective(si, 1.0, 1.0, 0.05);
      const ob::Cost before = path.cost(objective);
      simplify_with_objective(si, path, objective, 0.2);
      p.cost_before = before.value();
      p.cost_after = path.cost(objective).value();
      EXPECT_FALSE(objective->isCostBetterThan(before, path.cost(objective)))
          << "simplification made the cost worse: " << p.cost_before << " -> " << p.cost_after;
      expect_path_valid(setup, path);
      break;
    }
    EXPECT_GT(p.index, 0) << "no problem of the sample has a valid start and goal";
    problems.push_back(p);
  }
  double total = 0.0;
  int solved = 0;
  for (const Problem& p : problems) {
    std::printf(
        "[%s %-16s] problem %2d (%d skipped): %s in %.3f s CPU (%.3f s wall), %zu "
        "states, length %.3f, min clearance %.4f m; simplified cost %.3f -> %.3f\n",
        robot_name.c_str(), p.family.c_str(), p.index, p.skipped,
        p.solved ? "solved" : "NOT solved", p.cpu_seconds, p.seconds, p.states, p.length,
        p.min_clearance, p.cost_before, p.cost_after);
    total += p.cpu_seconds;
    solved += p.solved ? 1 : 0;
  }
  std::printf("[%s] %d / %zu solved, %.2f s CPU planning in total\n", robot_name.c_str(), solved,
              problems.size(), total);
}

INSTANTIATE_TEST_SUITE_P(Robots, MbmPlanning, ::testing::Values("panda", "ur5"));

// ---------------------------------------------------------------------------- own arm problem

// The own arm's table_wall scene: the tool between the wall and a bottle on one side, to the
// same place on the other side; the path goes over the wall.
class OwnArmPlanning : public ::testing::Test {
 protected:
  void SetUp() override {
    robot_ = test::load_robot(test::own_arm());
    const RobotModel& model = *robot_.model;
    checker_ = test::make_checker(robot_, read_planning_scene(test::own_arm_scene(), model));
    group_ = group_variables(model, robot_.srdf, "arm");
    start_ = goal_ = model.default_configuration();
    const double pose[] = {0.5, 0.5, 0.0, -1.3, 0.0, 1.2, 0.0};
    for (int i = 0; i < 7; ++i) start_[group_[static_cast<std::size_t>(i)]] = pose[i];
    goal_ = start_;
    goal_[group_[0]] = -0.5;
    reseed_ompl(7);
    setup_ = make_planning_setup(checker_, group_, start_);
  }

  // The own arm's links 1 and 3 are a checked pair that stays 0.020 m apart in every
  // configuration, so with self pairs checked no state is clearer than that. Clearance
  // objectives are exercised with the robot against the obstacles only.
  void obstacles_only() {
    checker_ = test::make_checker(robot_, read_planning_scene(test::own_arm_scene(), *robot_.model),
                                  false);
    setup_ = make_planning_setup(checker_, group_, start_);
  }

  // A fresh RRTConnect path (not simplified).
  og::PathGeometric plan(double seconds = 5.0) {
    og::SimpleSetup& ss = *setup_.setup;
    ss.clear();
    ss.setStartAndGoalStates(setup_.state(start_), setup_.state(goal_));
    ss.setPlanner(std::make_shared<og::RRTConnect>(ss.getSpaceInformation()));
    const ob::PlannerStatus status = ss.solve(seconds);
    EXPECT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION);
    return ss.getSolutionPath();
  }

  LoadedRobot robot_;
  std::shared_ptr<const CollisionChecker> checker_;
  std::vector<int> group_;
  Eigen::VectorXd start_, goal_;
  PlanningSetup setup_;
};

TEST_F(OwnArmPlanning, OverTheWall) {
  const og::PathGeometric path = plan();
  ASSERT_GE(path.getStateCount(), 2u);
  EXPECT_GT(expect_path_valid(setup_, path), 0.0);
  // The straight motion goes through the wall.
  const ob::SpaceInformationPtr& si = setup_.setup->getSpaceInformation();
  EXPECT_FALSE(si->checkMotion(setup_.state(start_).get(), setup_.state(goal_).get()));
}

TEST_F(OwnArmPlanning, ClearanceCostObjectiveFallsWithClearance) {
  obstacles_only();
  const ob::SpaceInformationPtr& si = setup_.setup->getSpaceInformation();
  const double scale = 0.05;
  ClearanceCostObjective objective(si, scale);
  EXPECT_EQ(objective.scale(), scale);
  EXPECT_THROW(ClearanceCostObjective(si, 0.0), InputError);
  EXPECT_THROW(ClearanceCostObjective(si, -1.0), InputError);
  EXPECT_THROW(ClearanceCostObjective(si, std::numeric_limits<double>::quiet_NaN()), InputError);
  // States of all clearances (colliding ones included): the cost is exp(-clearance / scale),
  // strictly decreasing in clearance.
  test::StateSampler sampler(*setup_.joints, 41);
  std::vector<std::pair<double, double>> samples;  // (clearance, cost)
  ob::ScopedState<> s(si->getStateSpace());
  const int count = test::scaled(150, 60);
  for (int k = 0; k <= count; ++k) {
    if (k < count) {
      sampler.uniform(s.get());
    } else {  // and one that surely penetrates: the tool in the wall
      Eigen::VectorXd in_wall = start_;
      const double pose[] = {0.0, 0.3, 0.0, -1.6, 0.0, 1.2416, 0.0};
      for (int i = 0; i < 7; ++i) in_wall[group_[static_cast<std::size_t>(i)]] = pose[i];
      setup_.joints->from_configuration(in_wall, s.get());
    }
    const double d = setup_.validity->clearance(s.get());
    const double c = objective.stateCost(s.get()).value();
    EXPECT_DOUBLE_EQ(c, std::exp(-d / scale));
    samples.emplace_back(d, c);
  }
  std::sort(samples.begin(), samples.end());
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].first > samples[i - 1].first) {
      EXPECT_LT(samples[i].second, samples[i - 1].second);
    }
  }
  EXPECT_LT(samples.front().first, 0.0) << "penetrating states should be among the samples";
  EXPECT_GT(samples.front().second, 1.0);
  EXPECT_GT(samples.back().first, 0.1);
  // Cheaper further from obstacles: the start (between wall and bottle) costs more than a
  // raised pose.
  Eigen::VectorXd up = start_;
  up[group_[1]] = 0.0;
  up[group_[3]] = -0.3;
  EXPECT_GT(setup_.validity->clearance(setup_.state(up).get()),
            setup_.validity->clearance(setup_.state(start_).get()));
  EXPECT_LT(objective.stateCost(setup_.state(up).get()).value(),
            objective.stateCost(setup_.state(start_).get()).value());
  // The motion cost integrates the state cost along the motion (trapezoids at OMPL's segment
  // resolution): compare with a fine integral (400 steps).
  const auto a = setup_.state(start_);
  Eigen::VectorXd q = start_;
  q[group_[1]] = 0.1;
  const auto b = setup_.state(q);
  double fine = 0.0;
  const int n = 400;
  ob::ScopedState<> p(si->getStateSpace()), r(si->getStateSpace());
  for (int i = 0; i < n; ++i) {
    si->getStateSpace()->interpolate(a.get(), b.get(), static_cast<double>(i) / n, p.get());
    si->getStateSpace()->interpolate(a.get(), b.get(), static_cast<double>(i + 1) / n, r.get());
    fine += 0.5 * (objective.stateCost(p.get()).value() + objective.stateCost(r.get()).value()) *
            si->distance(p.get(), r.get());
  }
  // Within 10%: the clearance of a decomposed link has kinks where its closest piece changes,
  // which trapezoids at the segment resolution follow less closely than a smooth hull's.
  EXPECT_NEAR(objective.motionCost(a.get(), b.get()).value(), fine, 0.10 * fine);
  EXPECT_EQ(objective.motionCost(a.get(), a.get()).value(), 0.0);
}

TEST_F(OwnArmPlanning, LengthClearanceObjectiveIsTheWeightedSum) {
  const ob::SpaceInformationPtr& si = setup_.setup->getSpaceInformation();
  EXPECT_THROW(make_length_clearance_objective(si, -1.0, 1.0), InputError);
  EXPECT_THROW(make_length_clearance_objective(si, 1.0, -1.0), InputError);
  EXPECT_THROW(make_length_clearance_objective(si, 1.0, 1.0, 0.0), InputError);
  ClearanceCostObjective clearance(si, 0.08);
  test::StateSampler sampler(*setup_.joints, 43);
  ob::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace());
  for (const auto& [wl, wc] :
       {std::pair{1.0, 1.0}, std::pair{2.0, 0.5}, std::pair{0.0, 3.0}, std::pair{1.0, 0.0}}) {
    const ob::OptimizationObjectivePtr objective =
        make_length_clearance_objective(si, wl, wc, 0.08);
    for (int k = 0; k < 5; ++k) {
      sampler.uniform(a.get());
      sampler.near(a.get(), 0.3, b.get());
      const double want =
          wl * si->distance(a.get(), b.get()) + wc * clearance.motionCost(a.get(), b.get()).value();
      EXPECT_NEAR(objective->motionCost(a.get(), b.get()).value(), want, 1e-9 * (1.0 + want))
          << "weights " << wl << ", " << wc;
    }
  }
  // More clearance at the same length is cheaper; a path's cost sums its motions.
  const ob::OptimizationObjectivePtr objective = make_length_clearance_objective(si, 1.0, 1.0);
  const og::PathGeometric path = plan();
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
    sum += objective->motionCost(path.getState(i), path.getState(i + 1)).value();
  }
  EXPECT_NEAR(path.cost(objective).value(), sum, 1e-9 * sum);
  // The max-min clearance objective: state cost is the exact clearance, larger is better.
  const ob::OptimizationObjectivePtr maxmin = make_max_min_clearance_objective(si);
  const auto s = setup_.state(start_);
  EXPECT_EQ(maxmin->stateCost(s.get()).value(), setup_.validity->clearance(s.get()));
  EXPECT_TRUE(maxmin->isCostBetterThan(ob::Cost(0.2), ob::Cost(0.1)));
}

TEST_F(OwnArmPlanning, SimplifyWithObjectiveDoesNotWorsenItsCost) {
  obstacles_only();
  const ob::SpaceInformationPtr& si = setup_.setup->getSpaceInformation();
  EXPECT_THROW(
      {
        og::PathGeometric p(si);
        simplify_with_objective(si, p, nullptr, 0.1);
      },
      InputError);
  struct Case {
    double wl, wc, scale;
  };
  const Case cases[] = {{1.0, 1.0, 0.05}, {0.0, 1.0, 0.05}, {1.0, 5.0, 0.1}, {1.0, 0.0, 0.05}};
  const int rounds = test::scaled(3, 1);
  for (const Case& c : cases) {
    for (int round = 0; round < rounds; ++round) {
      SCOPED_TRACE(std::to_string(c.wl) + " " + std::to_string(c.wc) + " round " +
                   std::to_string(round));
      og::PathGeometric path = plan();
      path.interpolate(std::max<unsigned>(path.getStateCount(), 12));
      const ob::OptimizationObjectivePtr objective =
          make_length_clearance_objective(si, c.wl, c.wc, c.scale);
      const ob::Cost before = path.cost(objective);
      const std::size_t states_before = path.getStateCount();
      const bool changed = simplify_with_objective(si, path, objective, 0.5,
                                                   setup_.setup->getProblemDefinition()->getGoal());
      const ob::Cost after = path.cost(objective);
      EXPECT_FALSE(objective->isCostBetterThan(before, after))
          << "cost " << before.value() << " -> " << after.value();
      EXPECT_TRUE(changed || path.getStateCount() == states_before);
      if (!changed) {
        EXPECT_EQ(after.value(), before.value());
      }
      expect_path_valid(setup_, path);
      EXPECT_EQ(setup_.configuration(path.getState(0)), start_);
      EXPECT_TRUE(
          si->equalStates(path.getState(path.getStateCount() - 1), setup_.state(goal_).get()));
      std::printf("[simplify %.1f/%.1f/%.2f] cost %.3f -> %.3f, %zu -> %zu states\n", c.wl, c.wc,
                  c.scale, before.value(), after.value(), states_before, path.getStateCount());
    }
  }
}

// ---------------------------------------------------------------------------- threads

// Several threads share one checker, validity checker and motion validator: OMPL's parallel
// planners (two PRMs, each with its roadmap and solution threads, through ParallelPlan; three
// RRTConnects), then plain threads whose answers must equal the sequential ones. CI runs these
// under ThreadSanitizer (scripts/test.sh, filter OmplThreads.*).
using OmplThreads = OwnArmPlanning;

TEST_F(OmplThreads, ParallelPrm) {
  const ob::SpaceInformationPtr& si = setup_.setup->getSpaceInformation();
  setup_.setup->setStartAndGoalStates(setup_.state(start_), setup_.state(goal_));
  // With a path-length objective (threshold 0: never satisfied) PRM keeps growing its roadmap
  // for the whole time instead of stopping at the first solution.
  setup_.setup->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));
  setup_.setup->setup();
  const ob::ProblemDefinitionPtr& pdef = setup_.setup->getProblemDefinition();
  ::ompl::tools::ParallelPlan parallel(pdef);
  parallel.addPlanner(std::make_shared<og::PRM>(si));
  parallel.addPlanner(std::make_shared<og::PRM>(si));
  const auto t0 = std::chrono::steady_clock::now();
  const ob::PlannerStatus status = parallel.solve(test::kSanitized ? 3.0 : 1.0, false);
  const double seconds = seconds_since(t0);
  EXPECT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION);
  ASSERT_TRUE(pdef->hasExactSolution());
  const auto path = std::dynamic_pointer_cast<og::PathGeometric>(pdef->getSolutionPath());
  ASSERT_NE(path, nullptr);
  EXPECT_GT(expect_path_valid(setup_, *path), 0.0);
  const auto* mv = dynamic_cast<const GuaranteedMotionValidator*>(si->getMotionValidator().get());
  ASSERT_NE(mv, nullptr);
  std::printf("[parallel PRM] %.2f s, %lu motions accepted, %lu rejected, path of %zu states\n",
              seconds, mv->valid_motion_count(), mv->invalid_motion_count(), path->getStateCount());
  EXPECT_GT(mv->valid_motion_count() + mv->invalid_motion_count(), 10u);
}

TEST_F(OmplThreads, ParallelRrtConnect) {
  const ob::SpaceInformationPtr& si = setup_.setup->getSpaceInformation();
  setup_.setup->setStartAndGoalStates(setup_.state(start_), setup_.state(goal_));
  setup_.setup->setup();
  const ob::ProblemDefinitionPtr& pdef = setup_.setup->getProblemDefinition();
  ::ompl::tools::ParallelPlan parallel(pdef);
  for (int i = 0; i < 3; ++i) parallel.addPlanner(std::make_shared<og::RRTConnect>(si));
  // Keep going until every planner found one (then hybridization is skipped).
  const ob::PlannerStatus status =
      parallel.solve(test::kSanitized ? 20.0 : 5.0, 3, 3, /*hybridize=*/false);
  EXPECT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION);
  EXPECT_GE(pdef->getSolutionCount(), 1u);
  for (const ob::PlannerSolution& solution : pdef->getSolutions()) {
    const auto path = std::dynamic_pointer_cast<og::PathGeometric>(solution.path_);
    ASSERT_NE(path, nullptr);
    EXPECT_GT(expect_path_valid(setup_, *path), 0.0);
  }
}

TEST_F(OmplThreads, ConcurrentQueriesMatchSequential) {
  const ob::SpaceInformationPtr& si = setup_.setup->getSpaceInformation();
  setup_.setup->getSpaceInformation()->setup();
  const int n = test::scaled(300, 60);
  test::StateSampler sampler(*setup_.joints, 47);
  std::vector<ob::State*> a(static_cast<std::size_t>(n)), b(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    a[static_cast<std::size_t>(i)] = si->allocState();
    b[static_cast<std::size_t>(i)] = si->allocState();
    sampler.uniform(a[static_cast<std::size_t>(i)]);
    sampler.near(a[static_cast<std::size_t>(i)], 0.3, b[static_cast<std::size_t>(i)]);
  }
  struct Answer {
    bool valid = false, valid_with_distance = false, motion = false;
    double clearance = 0.0, distance = 0.0;
    bool operator==(const Answer& o) const {
      return valid == o.valid && valid_with_distance == o.valid_with_distance &&
             motion == o.motion && clearance == o.clearance && distance == o.distance;
    }
  };
  const auto answer = [&](int i) {
    Answer r;
    const ob::State* s = a[static_cast<std::size_t>(i)];
    r.valid = si->isValid(s);
    r.valid_with_distance = setup_.validity->isValid(s, r.distance);
    r.clearance = setup_.validity->clearance(s);
    r.motion = r.valid && si->checkMotion(s, b[static_cast<std::size_t>(i)]);
    return r;
  };
  std::vector<Answer> sequential;
  for (int i = 0; i < n; ++i) sequential.push_back(answer(i));
  const auto* mv = dynamic_cast<const GuaranteedMotionValidator*>(si->getMotionValidator().get());
  ASSERT_NE(mv, nullptr);
  const unsigned long motions_before = mv->valid_motion_count() + mv->invalid_motion_count();
  const int threads = 4;
  std::atomic<int> mismatches{0};
  std::atomic<int> motions{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      // Each thread walks the states from a different offset.
      for (int k = 0; k < n; ++k) {
        const int i = (k + t * n / threads) % n;
        const Answer r = answer(i);
        if (r.valid) motions.fetch_add(1);
        if (!(r == sequential[static_cast<std::size_t>(i)])) mismatches.fetch_add(1);
      }
    });
  }
  for (std::thread& th : pool) th.join();
  EXPECT_EQ(mismatches.load(), 0);
  EXPECT_EQ(mv->valid_motion_count() + mv->invalid_motion_count() - motions_before,
            static_cast<unsigned long>(motions.load()));
  for (int i = 0; i < n; ++i) {
    si->freeState(a[static_cast<std::size_t>(i)]);
    si->freeState(b[static_cast<std::size_t>(i)]);
  }
}

}  // namespace
}  // namespace hullcheck
