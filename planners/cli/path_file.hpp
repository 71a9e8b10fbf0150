// Joint-space paths on disk: CSV with a joint-name header, or JSON (by extension).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace hullcheck::cli {

/// Waypoints of a path over named joints (rad or m).
struct JointPath {
  std::vector<std::string> joint_names;
  std::vector<Eigen::VectorXd> waypoints;
};

/// Writes `path` to `file`: JSON {"joint_names": [...], "waypoints": [[...], ...]} when the
/// name ends in .json, else CSV (header of joint names, one waypoint per line), values with 17
/// significant digits. Throws InputError when the file cannot be written.
void write_joint_path(const std::string& file, const JointPath& path);

/// Reads what write_joint_path writes (JSON by extension, else CSV). Throws InputError naming
/// the file, line or waypoint, joint and problem: unreadable file, no header, a joint named
/// twice, a row of the wrong length, a value that is not a finite number, no waypoints.
JointPath read_joint_path(const std::string& file);

}  // namespace hullcheck::cli
