// FclChecker: an independent robot-vs-scene collision checker built on FCL 0.7, for tests only.
//
// It sees the same geometry as hullcheck::CollisionChecker, rebuilt as FCL objects: each robot
// shape and each obstacle becomes fcl::Boxd / Sphered / Cylinderd / Capsuled, or an fcl::Convexd
// from the hull's vertices() and triangles(). Which pairs it checks it works out by itself from
// the AllowedCollisionMatrix and the scene's allowed (link, link) and (link, object) names. Only
// unpadded shapes are supported (margin 0: FCL has no exact inflated convex). Link poses come
// from the caller (RobotModel forward kinematics, which has its own oracle in the KDL tests).
//
// Queries: fcl::collide and fcl::distance on geometry + transform (no broad-phase manager), with
// a world-AABB cull in front of them (conservative: FCL's own computeBV). Not thread-safe.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <limits>
#include <memory>
#include <vector>

namespace hullcheck::test {

/// FCL's narrow-phase solver: libccd (MPR for booleans, GJK for distance) or FCL's own GJK/EPA.
enum class FclSolver { kLibccd, kIndep };

/// One checked pair: robot shape (link_a, shape_a) against another robot shape (self) or a
/// scene obstacle (environment).
struct FclPair {
  int link_a = -1;
  int shape_a = -1;
  int link_b = -1;    ///< Self pairs: the other robot link; -1 otherwise.
  int shape_b = -1;   ///< Self pairs: its shape index.
  int obstacle = -1;  ///< Environment pairs: index into the scene's obstacles; -1 otherwise.
  bool self() const { return obstacle < 0; }
};

/// Minimum of FCL's distance over the checked pairs.
struct FclDistance {
  /// Smallest distance FCL reports over the pairs that do not collide; +inf when none.
  double distance = std::numeric_limits<double>::infinity();
  std::ptrdiff_t pair = -1;  ///< Index into pairs() of that minimum (or of a colliding pair).
  bool collision = false;    ///< Some pair's fcl::distance reported a collision (distance < 0).
  int distance_calls = 0;    ///< fcl::distance calls made (the rest were culled by AABBs).
};

class FclChecker {
 public:
  /// Throws std::invalid_argument for a padded shape or a hull FCL rejects.
  FclChecker(const RobotModel& model, const AllowedCollisionMatrix& matrix,
             const PlanningScene& scene, FclSolver solver = FclSolver::kLibccd);
  ~FclChecker();
  FclChecker(const FclChecker&) = delete;
  FclChecker& operator=(const FclChecker&) = delete;

  /// Every checked pair, environment pairs first, then self pairs.
  const std::vector<FclPair>& pairs() const;

  /// Poses every robot shape at `link_poses` (model frame <- link frame, one per link); the
  /// queries below use the poses of the last call.
  void set_link_poses(const std::vector<Eigen::Isometry3d>& link_poses);

  /// fcl::collide on pair `i`.
  bool pair_collides(std::size_t i) const;
  /// fcl::distance on pair `i`: >= 0 apart, negative (FCL returns -1) when FCL finds contact.
  double pair_distance(std::size_t i) const;
  /// True when some pair collides (AABB cull, then fcl::collide).
  bool in_collision() const;
  /// The smallest fcl::distance over all pairs (AABB lower bounds prune pairs that cannot
  /// beat the best so far); stops at the first collision.
  FclDistance min_distance() const;

  /// World pose of a pair's sides at the current link poses (for diagnostics).
  Eigen::Isometry3d pose_a(std::size_t i) const;
  Eigen::Isometry3d pose_b(std::size_t i) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hullcheck::test
