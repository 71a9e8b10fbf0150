#include <algorithm>
#include <cmath>
#include <hullcheck/errors.hpp>
#include <hullcheck/pose.hpp>
#include <string>

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
  // Hand-written: this runs twice per query, so no temporaries and no transcendental calls.
  const auto& m = pose.matrix();
  // x * 0 is 0 for every finite x and NaN for NaN or infinity: one branch for all 12 entries.
  if (!((m.topRows<3>() * 0.0).sum() == 0.0)) {
    throw InputError(std::string(what) + ": pose contains NaN or infinity");
  }
  const Eigen::Vector3d x = m.block<3, 1>(0, 0), y = m.block<3, 1>(0, 1), z = m.block<3, 1>(0, 2);
  const double error = std::max({std::abs(x.squaredNorm() - 1.0), std::abs(y.squaredNorm() - 1.0),
                                 std::abs(z.squaredNorm() - 1.0), std::abs(x.dot(y)),
                                 std::abs(x.dot(z)), std::abs(y.dot(z))});
  if (error > 1e-6 || x.cross(y).dot(z) < 0.0) {
    throw InputError(std::string(what) +
                     ": pose rotation is not a proper rotation matrix (orthonormality error " +
                     std::to_string(error) + ", det " + std::to_string(x.cross(y).dot(z)) + ")");
  }
}

}  // namespace hullcheck
