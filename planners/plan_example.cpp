// The smallest complete planning program with hullcheck and OMPL; copy it to start your own.
// Loads a robot and a MoveIt scene, plans with RRTConnect between two configurations (SRDF
// group states or comma-separated joint values of the group), optimizes the path for clearance,
// and prints its length and minimum clearance.
//   hullcheck_plan_example URDF SRDF GROUP SCENE.yaml START GOAL [SECONDS]
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <cstdio>
#include <hullcheck/ompl.hpp>
#include <sstream>

using namespace hullcheck;

// A group state name of the SRDF, or comma-separated values for the group's joints.
Eigen::VectorXd configuration(const std::string& text, const RobotModel& model, const Srdf& srdf,
                              const std::string& group, const std::vector<int>& variables) {
  Eigen::VectorXd q = model.default_configuration();
  if (srdf.group_state(group, text) != nullptr) {
    return group_state_configuration(model, srdf, group, text, q);
  }
  std::stringstream in(text);
  std::string item;
  for (int v : variables) {
    if (!std::getline(in, item, ',')) throw InputError("'" + text + "': too few joint values");
    q[v] = std::stod(item);
  }
  return q;
}

int main(int argc, char** argv) try {
  if (argc < 7) {
    std::fprintf(stderr, "usage: %s URDF SRDF GROUP SCENE.yaml START GOAL [SECONDS]\n", argv[0]);
    return 2;
  }
  const double seconds = argc > 7 ? std::stod(argv[7]) : 5.0;
  // Robot, its collision matrix, the scene: one thread-safe checker.
  auto model = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(argv[1]));
  const Srdf srdf = read_srdf_file(argv[2]);
  const std::vector<int> group = group_variables(*model, srdf, argv[3]);
  auto checker = std::make_shared<const CollisionChecker>(
      model, AllowedCollisionMatrix::from_srdf(*model, srdf), read_planning_scene(argv[4], *model));

  const Eigen::VectorXd start = configuration(argv[5], *model, srdf, argv[3], group);
  const Eigen::VectorXd goal = configuration(argv[6], *model, srdf, argv[3], group);
  // OMPL SimpleSetup with hullcheck's state space, validity checker and guaranteed motions.
  PlanningSetup planning = make_planning_setup(checker, group, start);
  // Clearance (reported and optimized) over the obstacles and the self pairs the group moves
  // and can take 5 cm apart; validity always checks every pair.
  ClearanceOptimizationOptions options;
  options.margin = 0.05;
  planning.validity->set_clearance_scope(
      std::make_shared<PairScope>(optimization_scope(*checker, group, start, options.margin)));
  auto& ss = *planning.setup;
  ss.setStartAndGoalStates(planning.state(start), planning.state(goal));
  ss.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(ss.getSpaceInformation()));
  if (!ss.solve(seconds) || !ss.haveExactSolutionPath()) {
    std::fprintf(stderr, "no path found in %.1f s\n", seconds);
    return 1;
  }
  ompl::geometric::PathGeometric& path = ss.getSolutionPath();
  const auto si = ss.getSpaceInformation();
  const auto min_clearance = [&] {
    double m = INFINITY;
    for (std::size_t i = 0; i < path.getStateCount(); ++i) {
      m = std::min(m, planning.validity->clearance(path.getState(i)));
    }
    return m;
  };
  std::printf("RRTConnect: %zu states, length %.3f, min clearance %.4f m\n", path.getStateCount(),
              path.length(), min_clearance());

  // Optimize for clearance: a hinge at 5 cm against path length, every motion certified, never
  // worse than the planner's path.
  const ClearanceOptimizationResult optimized =
      optimize_clearance(si, *planning.validity, path, options);
  std::printf(
      "optimized: %zu states, length %.3f -> %.3f, min clearance %.4f -> %.4f m (%d waypoint "
      "moves, %.1f ms)\n",
      path.getStateCount(), optimized.length_before, optimized.length_after,
      optimized.min_clearance_before, optimized.min_clearance_after, optimized.moves,
      1e3 * optimized.seconds);
  const ClearanceResult closest = planning.validity->closest(path.getState(0));
  std::printf("closest pair at the start: %s - %s, %.4f m\n", std::string(closest.name_a).c_str(),
              std::string(closest.name_b).c_str(), closest.distance);
  return path.check() ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 1;
}
