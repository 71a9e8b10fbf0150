#include <hullcheck/core/pose.hpp>
#include <hullcheck/core/proximity_pair.hpp>
#include <stdexcept>

#include "detail/query_engine.hpp"
#include "detail/result_conversion.hpp"

namespace hullcheck {

void ProximityPair::invalidate() {
  verdict_ = Verdict::kUnknown;
  distance_.reset();
  penetration_.reset();
  signed_distance_.reset();
}

void ProximityPair::set_shape_a(const Shape& shape, const Eigen::Isometry3d& pose) {
  validate_pose(pose, "ProximityPair::set_shape_a");
  shape_a_ = shape;
  pose_a_ = pose;
  warm_ = WarmStart{};  // vertex indices belong to the old shape
  invalidate();
}

void ProximityPair::set_shape_a(const Shape& shape, const Eigen::Vector3d& position,
                                const Eigen::Vector3d& xyz_angles) {
  set_shape_a(shape, pose_from_xyz_angles(position, xyz_angles));
}

void ProximityPair::set_shape_b(const Shape& shape, const Eigen::Isometry3d& pose) {
  validate_pose(pose, "ProximityPair::set_shape_b");
  shape_b_ = shape;
  pose_b_ = pose;
  warm_ = WarmStart{};
  invalidate();
}

void ProximityPair::set_shape_b(const Shape& shape, const Eigen::Vector3d& position,
                                const Eigen::Vector3d& xyz_angles) {
  set_shape_b(shape, pose_from_xyz_angles(position, xyz_angles));
}

void ProximityPair::set_pose_a(const Eigen::Isometry3d& pose) {
  validate_pose(pose, "ProximityPair::set_pose_a");
  pose_a_ = pose;
  invalidate();
}

void ProximityPair::set_pose_b(const Eigen::Isometry3d& pose) {
  validate_pose(pose, "ProximityPair::set_pose_b");
  pose_b_ = pose;
  invalidate();
}

void ProximityPair::require_shapes() const {
  if (!shape_a_ || !shape_b_) {
    throw std::logic_error("ProximityPair: set both shapes before querying");
  }
}

bool ProximityPair::in_collision() {
  require_shapes();
  last_iterations_ = 0;
  last_was_cached_ = true;
  if (verdict_ == Verdict::kUnknown) {
    const detail::Answer answer = detail::query(*shape_a_, pose_a_, *shape_b_, pose_b_,
                                                detail::QueryKind::kIntersect, options_, &warm_);
    last_iterations_ = answer.iterations;
    last_was_cached_ = false;
    verdict_ = answer.overlapping ? Verdict::kColliding : Verdict::kSeparated;
  }
  return verdict_ == Verdict::kColliding;
}

const SignedDistanceResult& ProximityPair::signed_distance() {
  require_shapes();
  last_iterations_ = 0;
  last_was_cached_ = true;
  if (!signed_distance_) {
    // One GJK run (and EPA when overlapping) answers all three questions.
    const detail::Answer answer =
        detail::query(*shape_a_, pose_a_, *shape_b_, pose_b_, detail::QueryKind::kSignedDistance,
                      options_, &warm_);
    last_iterations_ = answer.iterations;
    last_was_cached_ = false;
    signed_distance_ = detail::to_signed_distance_result(answer);
    verdict_ = answer.overlapping ? Verdict::kColliding : Verdict::kSeparated;
    if (!penetration_) penetration_ = detail::to_penetration_result(answer);
    if (!distance_) {
      distance_ = detail::to_distance_result(answer);
      if (answer.overlapping) {
        distance_->point_a = distance_->point_b = 0.5 * (answer.point_a + answer.point_b);
      }
    }
  }
  return *signed_distance_;
}

const DistanceResult& ProximityPair::distance() {
  require_shapes();
  last_iterations_ = 0;
  last_was_cached_ = true;
  if (!distance_) {
    const detail::Answer answer = detail::query(*shape_a_, pose_a_, *shape_b_, pose_b_,
                                                detail::QueryKind::kDistance, options_, &warm_);
    last_iterations_ = answer.iterations;
    last_was_cached_ = false;
    distance_ = detail::to_distance_result(answer);
    verdict_ = answer.overlapping ? Verdict::kColliding : Verdict::kSeparated;
    if (!answer.overlapping) {  // apart: signed distance and (zero) penetration are known too
      signed_distance_ = detail::to_signed_distance_result(answer);
      penetration_ = detail::to_penetration_result(answer);
    }
  }
  return *distance_;
}

const PenetrationResult& ProximityPair::penetration() {
  require_shapes();
  last_iterations_ = 0;
  last_was_cached_ = true;
  if (!penetration_) {
    if (verdict_ == Verdict::kSeparated) {
      penetration_ = PenetrationResult{};  // apart: depth 0 (Casalino figure 14, state 3)
      last_was_cached_ = false;
    } else {
      signed_distance();  // one GJK + EPA run fills penetration_ and the rest
    }
  }
  return *penetration_;
}

}  // namespace hullcheck
