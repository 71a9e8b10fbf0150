#include <hullcheck/pose.hpp>
#include <hullcheck/queries.hpp>

#include "detail/query_engine.hpp"

namespace hullcheck {

namespace {

detail::Answer checked_query(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                             const Eigen::Isometry3d& pose_b, detail::QueryKind kind,
                             const QueryOptions& options) {
  validate_pose(pose_a, "pose_a");
  validate_pose(pose_b, "pose_b");
  return detail::query(a, pose_a, b, pose_b, kind, options, nullptr);
}

}  // namespace

bool intersect(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
               const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  return checked_query(a, pose_a, b, pose_b, detail::QueryKind::kIntersect, options).overlapping;
}

DistanceResult distance(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                        const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  return detail::to_distance_result(
      checked_query(a, pose_a, b, pose_b, detail::QueryKind::kDistance, options));
}

PenetrationResult penetration(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                              const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  return detail::to_penetration_result(
      checked_query(a, pose_a, b, pose_b, detail::QueryKind::kPenetration, options));
}

SignedDistanceResult signed_distance(const Shape& a, const Eigen::Isometry3d& pose_a,
                                     const Shape& b, const Eigen::Isometry3d& pose_b,
                                     const QueryOptions& options) {
  return detail::to_signed_distance_result(
      checked_query(a, pose_a, b, pose_b, detail::QueryKind::kSignedDistance, options));
}

}  // namespace hullcheck
