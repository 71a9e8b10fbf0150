#include "plan_command.hpp"

#include <ompl/util/Console.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <tuple>

#include "exit_codes.hpp"
#include "html_viewer.hpp"
#include "number_options.hpp"
#include "optimization_options.hpp"
#include "path_file.hpp"
#include "planner_factory.hpp"
#include "problem.hpp"

namespace hullcheck::cli {
namespace {

struct PlanSettings {
  WorldOptions world;
  ProblemOptions problem;
  std::string planner = "RRTConnect";
  std::string objective = "length";
  double time = 10.0;
  bool simplify = false;
  OptimizationOptions optimization;
  std::string out;
  std::string plot;
  std::string viewer;
  bool discrete = false;
  bool verbose = false;
};

// Reports an invalid start or goal with its deepest colliding pair; true when valid.
bool check_endpoint(const CollisionChecker& checker, const Eigen::VectorXd& q, const char* what) {
  if (checker.is_valid(q)) return true;
  const ClearanceResult r = checker.clearance(q);
  std::printf("%s state is in collision: %s\n", what, describe_pair(r).c_str());
  return false;
}

void run(const PlanSettings& s) {
  if (!s.verbose) ::ompl::msg::setLogLevel(::ompl::msg::LOG_WARN);
  const LoadedWorld world = s.world.load();
  std::vector<int> variables;
  Eigen::VectorXd start, goal;
  s.problem.resolve(world, &variables, &start, &goal);
  const bool start_ok = check_endpoint(*world.checker, start, "start");
  const bool goal_ok = check_endpoint(*world.checker, goal, "goal");
  if (!start_ok || !goal_ok) throw ExitWith{kExitInvalidProblem};

  if (s.discrete) {
    std::fprintf(stderr,
                 "warning: --discrete: motions are checked at sampled states only; the path is "
                 "not certified between them\n");
  }
  PlanningSetup planning =
      make_planning_setup(world.checker, variables, start,
                          s.discrete ? MotionChecking::kDiscrete : MotionChecking::kGuaranteed);
  ::ompl::geometric::SimpleSetup& ss = *planning.setup;
  const auto si = ss.getSpaceInformation();
  // The clearance scope of the objectives, the optimizer and the reports below.
  const std::shared_ptr<const PairScope> scope =
      s.optimization.make_scope(*world.checker, variables, start);
  planning.validity->set_clearance_scope(scope);
  if (scope && s.optimization.scope == "auto") {
    std::printf(
        "clearance scope auto: obstacles and %zu of %zu self pairs (those the group moves and "
        "can take %g m apart)\n",
        scope->self_link_pairs().size(), world.checker->checked_link_pairs().size(),
        s.optimization.settings.margin);
  }
  ss.setStartAndGoalStates(planning.state(start), planning.state(goal));
  ss.setOptimizationObjective(make_objective(s.objective, si));
  ss.setPlanner(make_planner(s.planner, si));
  ss.setup();
  const auto t0 = std::chrono::steady_clock::now();
  const ::ompl::base::PlannerStatus status = ss.solve(s.time);
  const double solve_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const bool solved = status == ::ompl::base::PlannerStatus::EXACT_SOLUTION;
  std::printf("planner %s, objective %s: %s in %.3f s (%lu state checks",
              ss.getPlanner()->getName().c_str(), s.objective.c_str(),
              solved ? "solved" : status.asString().c_str(), solve_time,
              planning.validity->check_count());
  if (const auto guaranteed =
          std::dynamic_pointer_cast<GuaranteedMotionValidator>(si->getMotionValidator())) {
    std::printf(", %lu certified motion checks evaluating %lu states",
                guaranteed->valid_motion_count() + guaranteed->invalid_motion_count(),
                guaranteed->step_count());
  }
  std::printf(")\n");
  if (!solved) throw ExitWith{kExitNotSolved};

  ::ompl::geometric::PathGeometric& path = ss.getSolutionPath();
  if (s.simplify) {
    const auto t1 = std::chrono::steady_clock::now();
    simplify_with_objective(si, path, ss.getOptimizationObjective(), 1.0,
                            ss.getProblemDefinition()->getGoal());
    std::printf("simplified (objective-aware) in %.3f s\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count());
  }
  const ::ompl::geometric::PathGeometric before(path);
  if (s.optimization.enabled()) {
    const ClearanceOptimizationResult r =
        optimize_clearance(si, *planning.validity, path, s.optimization.settings);
    std::printf(
        "optimized for clearance (scope %s, margin %g m, length weight %g) in %.3f s: %s; "
        "objective %.4f -> %.4f, length %.4f -> %.4f (%+.1f%%), %d rounds, %d waypoint moves, "
        "%d waypoints added\n",
        s.optimization.scope.c_str(), s.optimization.settings.margin,
        s.optimization.settings.length_weight, r.seconds,
        r.changed ? "path replaced" : "input kept (no certified improvement)", r.cost_before,
        r.cost_after, r.length_before, r.length_after,
        100.0 * (r.length_after / r.length_before - 1.0), r.rounds, r.moves, r.refined);
  }
  // Per-scope minima over the waypoints and 19 states inside each motion, before and after.
  const PairScope obstacles = world.checker->pair_scope(ClearanceScope::kObstacles);
  const PairScope self_pairs = world.checker->pair_scope(ClearanceScope::kSelf);
  std::vector<ClearanceCurve> curves;
  for (const auto& [pairs, name, color, faded] :
       {std::tuple{&obstacles, "obstacles", "#1f77b4", "#9ecae1"},
        std::tuple{&self_pairs, "self", "#ff7f0e", "#fdd0a2"}}) {
    const std::vector<ClearanceSample> after = clearance_profile(planning, path, pairs, 20);
    if (s.optimization.enabled()) {
      const std::vector<ClearanceSample> old = clearance_profile(planning, before, pairs, 20);
      std::printf("  min %-9s clearance %.4f -> %.4f m (%+.4f m)\n", name, profile_minimum(old),
                  profile_minimum(after), profile_minimum(after) - profile_minimum(old));
      curves.push_back({std::string(name) + " before", faded, true, old});
      curves.push_back({std::string(name) + " after", color, false, after});
    } else {
      std::printf("  min %-9s clearance %.4f m\n", name, profile_minimum(after));
      curves.push_back({name, color, false, after});
    }
  }
  if (!s.plot.empty()) {
    write_clearance_svg(s.plot,
                        "clearance per scope along the path" +
                            std::string(s.optimization.enabled() ? ", before and after "
                                                                   "optimization"
                                                                 : ""),
                        curves);
    std::printf("clearance profiles written to %s\n", s.plot.c_str());
  }
  double min_clearance = INFINITY;
  ClearanceResult closest;
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    const ClearanceResult r = planning.validity->closest(path.getState(i));
    if (r.distance < min_clearance) {
      min_clearance = r.distance;
      closest = r;
    }
  }
  std::printf("path: %zu waypoints, length %.4f, min waypoint clearance (scope %s) %.4f m (%s)\n",
              path.getStateCount(), path.length(), s.optimization.scope.c_str(), min_clearance,
              describe_pair(closest).c_str());
  JointPath out;
  for (int v : variables)
    out.joint_names.push_back(world.model->joint(world.model->variable_joint(v)).name);
  // The joints planning held fixed, at their values, so that validate checks the same states.
  const std::vector<std::string> names = world.model->variable_names();
  for (int v = 0; v < world.model->variable_count(); ++v) {
    if (std::find(variables.begin(), variables.end(), v) == variables.end()) {
      out.held.emplace_back(names[static_cast<std::size_t>(v)], start[v]);
    }
  }
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    const Eigen::VectorXd q = planning.configuration(path.getState(i));
    Eigen::VectorXd row(static_cast<Eigen::Index>(variables.size()));
    for (std::size_t k = 0; k < variables.size(); ++k)
      row[static_cast<Eigen::Index>(k)] = q[variables[k]];
    out.waypoints.push_back(row);
  }
  if (!s.out.empty()) {
    write_joint_path(s.out, out);
    std::printf("path written to %s\n", s.out.c_str());
  }
  if (!s.viewer.empty()) {
    const auto frames_of = [&](const ::ompl::geometric::PathGeometric& p) {
      ::ompl::geometric::PathGeometric dense(p);
      dense.interpolate(static_cast<unsigned>(std::max<std::size_t>(120, 4 * p.getStateCount())));
      std::vector<Eigen::VectorXd> frames;
      for (std::size_t i = 0; i < dense.getStateCount(); ++i) {
        frames.push_back(planning.configuration(dense.getState(i)));
      }
      return frames;
    };
    write_html_viewer(
        s.viewer,
        "hullcheck plan: " + world.model->name() +
            (s.optimization.enabled() ? " (grey: before optimization)" : ""),
        *world.model, world.checker->scene(), frames_of(path),
        s.optimization.enabled() ? frames_of(before) : std::vector<Eigen::VectorXd>{});
    std::printf("viewer written to %s\n", s.viewer.c_str());
  }
}

}  // namespace

void add_plan_command(CLI::App& app) {
  auto s = std::make_shared<PlanSettings>();
  CLI::App* command = app.add_subcommand(
      "plan", "Plan one problem (scene + request, or start and goal) with an OMPL planner");
  s->world.add_to(*command, false);
  s->problem.add_to(*command);
  command->add_option("--planner", s->planner, "OMPL geometric planner (default RRTConnect)");
  command->add_option("--objective", s->objective,
                      "length | clearance | clearance-cost | length+clearance (default length)");
  command->add_option("--time", s->time, "Planning time limit, s (default 10)")
      ->check(finite_in(0.0, 1e9, true));
  command->add_flag("--simplify", s->simplify, "Simplify the path with the objective");
  s->optimization.add_to(*command);
  command->add_option("--plot", s->plot,
                      "Write the clearance profiles per scope (before and after --optimize) as "
                      "an SVG plot");
  command->add_option("--out", s->out, "Write the path: CSV, or JSON when PATH ends in .json");
  command->add_option("--viewer", s->viewer,
                      "Write a self-contained HTML page animating the path in 3D");
  command->add_flag("--discrete", s->discrete,
                    "Check motions at OMPL's discrete resolution instead of the guaranteed mode");
  command->add_flag("--verbose", s->verbose, "Show OMPL's informational messages");
  command->footer(
      "Exit status: 0 solved, 1 bad input, 2 start or goal in collision, 3 not solved in time.");
  command->callback([s] { run(*s); });
}

}  // namespace hullcheck::cli
