#include <cmath>
#include <hullcheck/errors.hpp>
#include <hullcheck/queries.hpp>
#include <string>

#include "detail/query_engine.hpp"

namespace hullcheck {

namespace {

/// Poses must be rigid (see validate_pose); per query only finiteness is checked, which is
/// what an upstream computation most often gets wrong, at a cost of a few instructions.
void require_finite(const Eigen::Isometry3d& pose, const char* what) {
  // x * 0 is 0 for every finite x and NaN for NaN or infinity: one branch for all entries
  // (the 16 contiguous ones; the last row is 0 0 0 1 in a valid pose).
  const Eigen::Map<const Eigen::Matrix<double, 16, 1>> entries(pose.data());
  if (!((entries * 0.0).sum() == 0.0)) {  // Eigen's reduction: vectorised
    throw InputError(std::string(what) + ": pose contains NaN or infinity");
  }
}

detail::Answer checked_query(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                             const Eigen::Isometry3d& pose_b, detail::QueryKind kind,
                             const QueryOptions& options, double cutoff = INFINITY) {
  require_finite(pose_a, "pose_a");
  require_finite(pose_b, "pose_b");
  return detail::query(a, pose_a, b, pose_b, kind, options, nullptr, cutoff);
}

}  // namespace

bool intersect(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
               const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  require_finite(pose_a, "pose_a");
  require_finite(pose_b, "pose_b");
  return detail::intersect_query(a, pose_a, b, pose_b, options);
}

DistanceResult distance(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                        const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  return detail::to_distance_result(
      checked_query(a, pose_a, b, pose_b, detail::QueryKind::kDistance, options));
}

PenetrationResult penetration(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                              const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  require_finite(pose_a, "pose_a");
  require_finite(pose_b, "pose_b");
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

}  // namespace hullcheck
