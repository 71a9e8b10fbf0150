#include <algorithm>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/pose.hpp>
#include <string>

#include "detail/checks.hpp"

namespace hullcheck {

Eigen::Matrix3d rotation_from_xyz_angles(double gx, double gy, double gz) {
  return (Eigen::AngleAxisd(gx, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(gy, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(gz, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

Eigen::Isometry3d pose_from_xyz_angles(const Eigen::Vector3d& position,
                                       const Eigen::Vector3d& angles) {
  if (!position.allFinite() || !angles.allFinite()) {
    throw InputError("pose_from_xyz_angles: position and angles must be finite");
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation_from_xyz_angles(angles.x(), angles.y(), angles.z());
  pose.translation() = position;
  return pose;
}

void validate_pose(const Eigen::Isometry3d& pose, const char* what) {
  if (detail::pose_is_rigid(pose)) return;
  // Rejected: say why (this path is not hot).
  const auto& m = pose.matrix();
  if (!m.topRows<3>().allFinite()) {
    throw InputError(std::string(what) + ": pose contains NaN or infinity");
  }
  const Eigen::Vector3d t = pose.translation();
  if (t.cwiseAbs().maxCoeff() > kMaxLength) {
    throw InputError(std::string(what) + ": pose translation component " +
                     std::to_string(t.cwiseAbs().maxCoeff()) + " m exceeds 1e6 m");
  }
  const Eigen::Matrix3d r = pose.linear();
  const double error = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  throw InputError(std::string(what) +
                   ": pose rotation is not a proper rotation matrix (orthonormality error " +
                   std::to_string(error) + ", det " + std::to_string(r.determinant()) +
                   "; scaled, sheared and reflected matrices are not rigid)");
}

}  // namespace hullcheck
