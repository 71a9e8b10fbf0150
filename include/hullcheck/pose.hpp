// Poses: rigid transforms from a shape's local frame to the world frame.
#pragma once

#include <Eigen/Geometry>

namespace hullcheck {

/// Rotation from X-Y-Z angles (radians): R = Rx(gx) * Ry(gy) * Rz(gz), i.e. rotate about x, then
/// about the new y, then about the new z (seed appendix B, eq. 38).
Eigen::Matrix3d rotation_from_xyz_angles(double gx, double gy, double gz);

/// Pose with translation `position` (metres) and rotation_from_xyz_angles(angles).
Eigen::Isometry3d pose_from_xyz_angles(const Eigen::Vector3d& position,
                                       const Eigen::Vector3d& angles);

/// Throws InputError naming `what` when `pose` has a non-finite entry or its linear part is not a
/// rotation (|R^T R - I| > 1e-6 or det R < 0). ProximityPair calls it on every pose it is
/// given; the free queries check only finiteness (a few instructions instead of ~100).
void validate_pose(const Eigen::Isometry3d& pose, const char* what);

}  // namespace hullcheck
