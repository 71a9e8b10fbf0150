// Poses: rigid transforms from a shape's local frame to the world frame.
#pragma once

#include <Eigen/Geometry>
#include <hullcheck/core/limits.hpp>

namespace hullcheck {

/// Rotation from X-Y-Z angles (radians): R = Rx(gx) * Ry(gy) * Rz(gz), i.e. rotate about x, then
/// about the new y, then about the new z (Casalino appendix B, eq. 38).
Eigen::Matrix3d rotation_from_xyz_angles(double gx, double gy, double gz);

/// Pose with translation `position` (metres) and rotation_from_xyz_angles(angles).
Eigen::Isometry3d pose_from_xyz_angles(const Eigen::Vector3d& position,
                                       const Eigen::Vector3d& angles);

/// Throws InputError naming `what` when `pose` is not a rigid placement hullcheck accepts: a
/// non-finite entry, a translation component beyond kMaxLength (1e6 m), or a linear part that is
/// not a rotation to kRotationTolerance (1e-6: scaled, sheared, reflected or zero matrices).
/// Every public query and ProximityPair check their poses with the same test (~30 flops).
void validate_pose(const Eigen::Isometry3d& pose, const char* what);

}  // namespace hullcheck
