// MotionPlanRequest: start and joint-space goal of a planning problem, from MoveIt YAML.
#pragma once

#include <Eigen/Core>
#include <hullcheck/robot/robot_model.hpp>
#include <string>
#include <vector>

namespace hullcheck {

/// A planning problem in joint space.
struct MotionPlanRequest {
  std::string group;      ///< group_name (may be empty).
  Eigen::VectorXd start;  ///< Full configuration: the model's default with start_state set.
  Eigen::VectorXd goal;   ///< `start` with the goal's joint constraints written in.
  std::vector<int> goal_variables;     ///< Configuration indices the goal constrains.
  double allowed_planning_time = 0.0;  ///< s, 0 when not given.
};

/// Reads a moveit_msgs/MotionPlanRequest in YAML (as MotionBenchMaker writes it):
/// `start_state.joint_state` (name and position lists; names the robot lacks, such as a
/// virtual joint, are ignored; mimic joints are ignored since they follow), one
/// `goal_constraints[0].joint_constraints` list (joint_name, position) and `group_name`.
/// Start values are not clamped into limits (data sets hold slightly outside values). Throws
/// InputError naming the file and problem: YAML errors, mismatched name/position lists, no
/// joint-space goal, a goal joint the robot lacks, non-finite values.
MotionPlanRequest read_motion_plan_request(const std::string& path, const RobotModel& model);
/// The same from YAML text.
MotionPlanRequest parse_motion_plan_request(const std::string& yaml, const RobotModel& model,
                                            const std::string& source_name = "<request string>");

}  // namespace hullcheck
