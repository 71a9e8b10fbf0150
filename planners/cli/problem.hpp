// A planning problem as the command line describes it: robot, SRDF, scene, group, start, goal.
#pragma once

#include <CLI/CLI.hpp>
#include <hullcheck/ompl.hpp>
#include <memory>
#include <string>
#include <vector>

#include "robot_options.hpp"

namespace hullcheck::cli {

/// Robot + collision matrix + scene, ready to check configurations.
struct LoadedWorld {
  std::shared_ptr<RobotModel> model;
  Srdf srdf;
  std::shared_ptr<const CollisionChecker> checker;
};

/// --robot/--package/--padding/--srdf and --scene; loads them into a LoadedWorld.
struct WorldOptions {
  RobotOptions robot;
  std::string scene;  // empty: no obstacles

  void add_to(CLI::App& command, bool scene_required);
  LoadedWorld load() const;
};

/// Start, goal and group of a problem, from a MotionPlanRequest or from --start/--goal.
struct ProblemOptions {
  std::string request;
  std::string start;
  std::string goal;
  std::string group;

  void add_to(CLI::App& command);
  /// Resolves the group (--group, else the request's, else every active joint) and the start
  /// and goal configurations (full vectors). --start/--goal take an SRDF group state name or
  /// comma-separated values of the group's joints in configuration order.
  void resolve(const LoadedWorld& world, std::vector<int>* variables, Eigen::VectorXd* start,
               Eigen::VectorXd* goal) const;
};

/// "link_a - name_b (signed distance X m)" for reports.
std::string describe_pair(const ClearanceResult& r);

}  // namespace hullcheck::cli
