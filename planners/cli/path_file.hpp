// Joint-space paths on disk: CSV with a joint-name header, or JSON (by extension).
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace hullcheck::cli {

/// Waypoints of a path over named joints (rad or m), and the values of the joints the path holds
/// fixed (the robot's other active joints, as planning held them), so that a path file alone
/// says which configurations it passes through.
struct JointPath {
  std::vector<std::string> joint_names;
  std::vector<Eigen::VectorXd> waypoints;
  std::vector<std::pair<std::string, double>> held;  ///< (joint, value), none in joint_names
};

/// Writes `path` to `file`: JSON {"held": {name: value, ...}, "joint_names": [...],
/// "waypoints": [[...], ...]} when the name ends in .json, else CSV: a comment line
/// "# held: name=value,..." (when joints are held), the header of joint names, one waypoint per
/// line; values with 17 significant digits. Throws InputError when the file cannot be written.
void write_joint_path(const std::string& file, const JointPath& path);

/// Reads what write_joint_path writes (JSON by extension, else CSV; "held" is optional, other
/// CSV lines starting with '#' are comments). Throws InputError naming the file, line or
/// waypoint, joint and problem: unreadable file, no header, a joint named twice (among the
/// header and the held joints), a row of the wrong length, a value that is not a finite number,
/// a malformed held item, no waypoints.
JointPath read_joint_path(const std::string& file);

}  // namespace hullcheck::cli
