#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/pose.hpp>
#include <hullcheck/core/queries.hpp>
#include <string>

#include "detail/checks.hpp"
#include "detail/fast_paths.hpp"
#include "detail/query_engine.hpp"
#include "detail/result_conversion.hpp"

namespace hullcheck {

namespace {

/// Every public query checks both poses with validate_pose's test (finite, translation within
/// kMaxLength, rotation rigid to kRotationTolerance), both at once; the diagnosis is built only
/// when it fails.
void require_rigid(const Eigen::Isometry3d& pose_a, const Eigen::Isometry3d& pose_b) {
  if (!detail::poses_are_rigid(pose_a, pose_b)) {
    validate_pose(pose_a, "pose_a");
    validate_pose(pose_b, "pose_b");
  }
}

detail::Answer checked_query(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                             const Eigen::Isometry3d& pose_b, detail::QueryKind kind,
                             const QueryOptions& options, double cutoff = INFINITY,
                             WarmStart* warm = nullptr) {
  require_rigid(pose_a, pose_b);
  return detail::query(a, pose_a, b, pose_b, kind, options, warm, cutoff);
}

}  // namespace

bool intersect(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
               const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  require_rigid(pose_a, pose_b);
  return detail::intersect_query(a, pose_a, b, pose_b, options);
}

bool within_distance(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                     const Eigen::Isometry3d& pose_b, double distance,
                     const QueryOptions& options) {
  detail::require_length(distance, "within_distance: distance");
  detail::require_length(a.margin() + distance, "within_distance: distance plus A's margin");
  require_rigid(pose_a, pose_b);
  return detail::within_distance_query(a, pose_a, b, pose_b, distance, options);
}

DistanceResult distance(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                        const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  return detail::to_distance_result(
      checked_query(a, pose_a, b, pose_b, detail::QueryKind::kDistance, options));
}

PenetrationResult penetration(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                              const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  require_rigid(pose_a, pose_b);
  return detail::to_penetration_result(detail::penetration_query(a, pose_a, b, pose_b, options));
}

SignedDistanceResult signed_distance(const Shape& a, const Eigen::Isometry3d& pose_a,
                                     const Shape& b, const Eigen::Isometry3d& pose_b,
                                     const QueryOptions& options) {
  return detail::to_signed_distance_result(
      checked_query(a, pose_a, b, pose_b, detail::QueryKind::kSignedDistance, options));
}

SignedDistanceResult signed_distance_below(const Shape& a, const Eigen::Isometry3d& pose_a,
                                           const Shape& b, const Eigen::Isometry3d& pose_b,
                                           double cutoff, const QueryOptions& options) {
  if (std::isnan(cutoff)) throw InputError("signed_distance_below: cutoff is NaN");
  return detail::to_signed_distance_result(
      checked_query(a, pose_a, b, pose_b, detail::QueryKind::kSignedDistance, options, cutoff));
}

SignedDistanceResult signed_distance_below(const Shape& a, const Eigen::Isometry3d& pose_a,
                                           const Shape& b, const Eigen::Isometry3d& pose_b,
                                           double cutoff, WarmStart& warm,
                                           const QueryOptions& options) {
  if (std::isnan(cutoff)) throw InputError("signed_distance_below: cutoff is NaN");
  return detail::to_signed_distance_result(checked_query(
      a, pose_a, b, pose_b, detail::QueryKind::kSignedDistance, options, cutoff, &warm));
}

}  // namespace hullcheck
