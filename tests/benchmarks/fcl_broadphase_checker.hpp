// FclBroadphaseChecker: the robot-vs-scene checker an FCL 0.7 user writes, for benchmarks only.
//
// Every robot collision shape (hulls as fcl::Convexd from ConvexHull::vertices()/triangles(),
// primitives as fcl::Boxd/Sphered/Cylinderd/Capsuled) is one CollisionObject in a
// DynamicAABBTreeCollisionManager, updated per state (setTransform, computeAABB, update()); the
// obstacles are in a second, static manager. Validity: robot manager against obstacle manager,
// then the robot manager against itself, with a callback that skips the pairs the allowed-
// collision matrix allows (the same matrix and scene-allowed (link, object) names that the
// hullcheck::CollisionChecker it is built from uses) and stops at the first collision.
// Clearance: the same two traversals with manager->distance and fcl::distance (GST_LIBCCD,
// enable_signed_distance) per pair, the running minimum passed back to the tree for pruning and
// a stop at the first penetration (FCL's default distance callback does the same). Forward
// kinematics is hullcheck's. Unpadded shapes only (FCL has no exact inflated convex).
// Not thread-safe: one object per thread.
#pragma once

#include <Eigen/Geometry>
#include <hullcheck/scene/collision_checker.hpp>
#include <memory>

namespace hullcheck::bench {

class FclBroadphaseChecker {
 public:
  /// The robot, matrix (scene's link pairs included) and scene of `hc` (which must outlive
  /// this object). Throws std::runtime_error for a padded shape or a hull FCL rejects.
  explicit FclBroadphaseChecker(const CollisionChecker& hc);
  ~FclBroadphaseChecker();
  FclBroadphaseChecker(const FclBroadphaseChecker&) = delete;
  FclBroadphaseChecker& operator=(const FclBroadphaseChecker&) = delete;

  /// True when no enabled pair collides at configuration q (full vector, rad / m).
  bool is_valid(const Eigen::VectorXd& q);
  /// Minimum signed distance (m) over enabled pairs at q, as FCL computes it (stops at the
  /// first penetration, whose depth FCL reports).
  double clearance(const Eigen::VectorXd& q);
  /// FCL's signed distance of the pair hullcheck reports as closest, at the poses of the last
  /// query, the smaller over both argument orders (libccd's GJK distance depends on the order
  /// and can stop early on large hulls; the broad phase passes the pair in either order).
  double pair_distance(const ClearanceResult& r);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hullcheck::bench
