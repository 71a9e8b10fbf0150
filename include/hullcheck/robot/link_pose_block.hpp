// LinkPoseBlock: the link poses of several configurations at once, laid out for SIMD.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace hullcheck {

/// Configurations per block of the batch queries (RobotModel::compute_link_poses_block,
/// CollisionChecker::is_valid_batch): a multiple of every SIMD width in use (2 to 8 doubles).
inline constexpr int kPoseBlockLanes = 8;

/// Link poses (model frame <- link frame) of kPoseBlockLanes configurations, structure of
/// arrays: entry e of link l holds one value per lane, e = 0..8 the rotation row by row, 9..11
/// the translation (m). Sized by RobotModel::compute_link_poses_block; reuse one block to avoid
/// allocating.
struct LinkPoseBlock {
  std::vector<double> values;  ///< links x 12 x kPoseBlockLanes

  const double* entry(int link, int e) const {
    return values.data() +
           (static_cast<std::size_t>(link) * 12 + static_cast<std::size_t>(e)) * kPoseBlockLanes;
  }
  /// The pose of `link` in lane `lane`.
  Eigen::Isometry3d pose(int link, int lane) const {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) p.linear()(r, c) = entry(link, 3 * r + c)[lane];
      p.translation()[r] = entry(link, 9 + r)[lane];
    }
    return p;
  }
};

}  // namespace hullcheck
