// URDF poses as Eigen transforms, for the URDF loader's parts.
#pragma once

#include <urdf_model/pose.h>

#include <Eigen/Geometry>

namespace hullcheck::detail {

/// The transform of a URDF <origin>; the rotation is normalised (a zero quaternion: identity).
inline Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  const double norm = q.norm();
  if (norm > 0.0) q.coeffs() /= norm;
  out.linear() = q.toRotationMatrix();
  out.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return out;
}

}  // namespace hullcheck::detail
