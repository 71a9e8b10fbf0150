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
  const auto& m = pose.matrix();
  if (!m.topRows<3>().allFinite()) {
    throw InputError(std::string(what) + ": pose contains NaN or infinity");
  }
  const Eigen::Matrix3d r = pose.linear();
  const double orthogonality_error =
      (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthogonality_error > 1e-6 || r.determinant() < 0.0) {
    throw InputError(
        std::string(what) + ": pose rotation is not a proper rotation matrix (|R^T R - I| = " +
        std::to_string(orthogonality_error) + ", det = " + std::to_string(r.determinant()) + ")");
  }
}

}  // namespace hullcheck
