// Planning groups: which configuration values a planner moves.
#pragma once

#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/robot/srdf.hpp>
#include <string>
#include <vector>

namespace hullcheck {

/// Configuration indices (RobotModel::variable_index) of the active joints named, in
/// configuration order. Fixed and mimic joints among the names are skipped (they follow).
/// Throws InputError naming the robot and the first unknown joint name.
std::vector<int> group_variables(const RobotModel& model, const std::vector<std::string>& joints);

/// Configuration indices of the active joints of the SRDF group `group`: its <joint>s, the
/// joints along each <chain> (from base_link down to tip_link), the parent joints of its
/// <link>s, and its subgroups, recursively; in configuration order. Throws InputError when the
/// group does not exist (listing the groups), names a joint or link the robot lacks, a chain
/// whose tip is not below its base, or subgroups that form a cycle.
std::vector<int> group_variables(const RobotModel& model, const Srdf& srdf,
                                 const std::string& group);

/// The configuration of the group state `state` of `group`: `base` with the state's joint
/// values written in. Throws InputError when the state does not exist or names an unknown
/// joint.
Eigen::VectorXd group_state_configuration(const RobotModel& model, const Srdf& srdf,
                                          const std::string& group, const std::string& state,
                                          const Eigen::VectorXd& base);

}  // namespace hullcheck
