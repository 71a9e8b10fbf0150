// ProximityPair: two shapes and their poses, with cached, warm-started queries (Casalino §4).
#pragma once

#include <hullcheck/core/queries.hpp>
#include <hullcheck/core/warm_start.hpp>
#include <optional>

namespace hullcheck {

/// A pair of shapes A and B with poses, answering collision, distance, penetration and signed
/// distance in any order. Results are cached until a shape or pose is set again (Casalino figure
/// 14: the collision verdict, distance and penetration each computed at most once per
/// configuration, and one GJK run shared between them). Setting only a pose keeps the warm start:
/// GJK starts from the last separating direction and hull support vertices, so a slightly moved
/// pose converges in fewer iterations.
///
/// Poses are local -> world; all results in the world frame (see queries.hpp). Not thread-safe:
/// use one pair per thread. Queries before both shapes are set throw std::logic_error.
class ProximityPair {
 public:
  explicit ProximityPair(const QueryOptions& options = {}) : options_(options) {}

  /// Shape with the identity pose (local frame = world frame; Casalino's Set_shape_A).
  void set_shape_a(const Shape& shape) { set_shape_a(shape, Eigen::Isometry3d::Identity()); }
  void set_shape_a(const Shape& shape, const Eigen::Isometry3d& pose);
  /// Shape placed at `position` with X-Y-Z angles (radians), Casalino's Set_shape_A_transformed.
  void set_shape_a(const Shape& shape, const Eigen::Vector3d& position,
                   const Eigen::Vector3d& xyz_angles);
  void set_shape_b(const Shape& shape) { set_shape_b(shape, Eigen::Isometry3d::Identity()); }
  void set_shape_b(const Shape& shape, const Eigen::Isometry3d& pose);
  void set_shape_b(const Shape& shape, const Eigen::Vector3d& position,
                   const Eigen::Vector3d& xyz_angles);

  /// Move a shape, keeping the warm start. Throws InputError for a non-finite/non-rigid pose.
  void set_pose_a(const Eigen::Isometry3d& pose);
  void set_pose_b(const Eigen::Isometry3d& pose);

  bool in_collision();
  const DistanceResult& distance();
  const PenetrationResult& penetration();
  const SignedDistanceResult& signed_distance();

  /// GJK (+ EPA) iterations spent by the most recent query (0 when served from the cache, or
  /// when a bounding-ball test decided it).
  int last_iterations() const { return last_iterations_; }
  /// Whether the most recent query was answered from the cache, without computation.
  bool last_was_cached() const { return last_was_cached_; }
  const QueryOptions& options() const { return options_; }

 private:
  enum class Verdict { kUnknown, kColliding, kSeparated };
  void invalidate();
  void require_shapes() const;

  QueryOptions options_;
  std::optional<Shape> shape_a_, shape_b_;
  Eigen::Isometry3d pose_a_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d pose_b_ = Eigen::Isometry3d::Identity();
  Verdict verdict_ = Verdict::kUnknown;
  std::optional<DistanceResult> distance_;
  std::optional<PenetrationResult> penetration_;
  std::optional<SignedDistanceResult> signed_distance_;
  WarmStart warm_;
  int last_iterations_ = 0;
  bool last_was_cached_ = false;
};

}  // namespace hullcheck
