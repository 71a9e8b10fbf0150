#include "problem.hpp"

#include <cstdio>
#include <sstream>

namespace hullcheck::cli {

void WorldOptions::add_to(CLI::App& command, bool scene_required) {
  robot.add_to(command, true);
  CLI::Option* option = command.add_option(
      "--scene", scene, "MoveIt PlanningScene YAML (obstacles, allowed collisions)");
  if (scene_required) option->required();
}

LoadedWorld WorldOptions::load() const {
  LoadedWorld world;
  world.model = robot.load();
  world.srdf = robot.load_srdf();
  std::vector<std::string> warnings;
  AllowedCollisionMatrix acm =
      AllowedCollisionMatrix::from_srdf(*world.model, world.srdf, &warnings);
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  PlanningScene planning_scene;
  if (!scene.empty()) planning_scene = read_planning_scene(scene, *world.model);
  world.checker =
      std::make_shared<const CollisionChecker>(world.model, std::move(acm), planning_scene);
  return world;
}

void ProblemOptions::add_to(CLI::App& command) {
  command.add_option("--request", request, "MoveIt MotionPlanRequest YAML (start, goal, group)");
  command.add_option("--start", start, "Start: SRDF group state or values q1,q2,... of the group");
  command.add_option("--goal", goal, "Goal: SRDF group state or values q1,q2,... of the group");
  command.add_option("--group", group, "Planning group (SRDF group name)");
}

namespace {

Eigen::VectorXd configuration(const std::string& text, const LoadedWorld& world,
                              const std::string& group, const std::vector<int>& variables,
                              const Eigen::VectorXd& base, const char* what) {
  if (!group.empty() && world.srdf.group_state(group, text) != nullptr) {
    return group_state_configuration(*world.model, world.srdf, group, text, base);
  }
  Eigen::VectorXd q = base;
  std::vector<double> values;
  std::string bad;
  if (!parse_number_list(text, &values, &bad)) {
    throw InputError(std::string(what) + " '" + text + "': neither a group state of '" + group +
                     "' nor a list of numbers (item '" + bad + "')");
  }
  if (values.size() != variables.size()) {
    throw InputError(std::string(what) + ": " + std::to_string(values.size()) +
                     " values given, the group has " + std::to_string(variables.size()) +
                     " joints");
  }
  for (std::size_t i = 0; i < variables.size(); ++i) q[variables[i]] = values[i];
  world.model->check_configuration(q);
  try {
    for (int v : variables) world.model->check_joint_range(v, q[v]);
  } catch (const InputError& e) {
    throw InputError(std::string(what) + ": " + e.what());
  }
  return q;
}

}  // namespace

void ProblemOptions::resolve(const LoadedWorld& world, std::vector<int>* variables,
                             Eigen::VectorXd* start_q, Eigen::VectorXd* goal_q) const {
  const RobotModel& model = *world.model;
  std::string group_name = group;
  Eigen::VectorXd base = model.default_configuration();
  MotionPlanRequest req;
  if (!request.empty()) {
    if (!start.empty() || !goal.empty()) {
      throw InputError("give either --request or --start/--goal, not both");
    }
    req = read_motion_plan_request(request, model);
    if (group_name.empty()) group_name = req.group;
  } else if (start.empty() || goal.empty()) {
    throw InputError("give --request, or both --start and --goal");
  }
  if (!group_name.empty()) {
    *variables = group_variables(model, world.srdf, group_name);
  } else if (!req.goal_variables.empty()) {
    *variables = req.goal_variables;
    std::sort(variables->begin(), variables->end());
  } else {
    variables->clear();
    for (int i = 0; i < model.variable_count(); ++i) variables->push_back(i);
  }
  if (!request.empty()) {
    *start_q = req.start;
    *goal_q = req.goal;
    return;
  }
  *start_q = configuration(start, world, group_name, *variables, base, "--start");
  *goal_q = configuration(goal, world, group_name, *variables, *start_q, "--goal");
}

std::string describe_pair(const ClearanceResult& r) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "%s - %s (signed distance %.6g m)",
                std::string(r.name_a).c_str(), std::string(r.name_b).c_str(), r.distance);
  return buffer;
}

}  // namespace hullcheck::cli
