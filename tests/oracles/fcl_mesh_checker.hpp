// FclMeshChecker: robot-vs-itself-and-scene collision and distance on the links' triangle
// meshes with FCL 0.7, for tests only: the ground truth that convex representations (hulls,
// decompositions) are judged against.
//
// Geometry: an FclMeshModel (the URDF's <collision> elements read independently of hullcheck:
// triangle meshes as OBBRSS BVHs, primitives as FCL primitives), matched to the RobotModel's
// links by name; obstacles are the PlanningScene's shapes as FCL primitives (fcl::Convexd for
// hulls). Link poses come from the caller (RobotModel::compute_link_poses).
// Pairs, worked out like FclChecker's: the self pairs of links with geometry that the
// AllowedCollisionMatrix does not allow and the scene's allowed names do not name, and every
// link against every obstacle whose object the scene does not allow for that link; one pair
// per (element, element) or (element, obstacle).
//
// What "collision" means on meshes: FCL's mesh-mesh test finds intersecting triangles, i.e.
// surfaces that cross or touch. A mesh wholly inside another mesh is *not* a collision (a
// triangle soup has no inside), and its distance is that to the enclosing surface. Against a
// primitive (box, sphere, cylinder, convex) FCL tests each triangle against the solid, so a
// mesh inside an obstacle does collide. Padding is ignored: this is the bare meshes' answer.
//
// Queries: an AABB / bounding-ball cull (conservative lower bounds on each pair's distance) in
// front of fcl::collide and fcl::distance; distance calls are seeded with the best distance so
// far (or a small cutoff first), so FCL's BVH traversal prunes everything that cannot beat it:
// about 4 ms for a UR5 state with its 40k-triangle gripper and sensor meshes, where unseeded
// calls took 25 ms. Not thread-safe.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fcl_mesh_model.hpp"

namespace hullcheck::test {

/// One checked pair: an element of robot link `link_a` against an element of link `link_b`
/// (self) or against scene obstacle `obstacle`. Links are RobotModel link indices, elements
/// index FclMeshModel's elements of that link.
struct FclMeshPair {
  int link_a = -1;
  int element_a = -1;
  int link_b = -1;     ///< Self pairs: the other robot link; -1 otherwise.
  int element_b = -1;  ///< Self pairs: its element index.
  int obstacle = -1;   ///< Environment pairs: index into the scene's obstacles; -1 otherwise.
  bool self() const { return obstacle < 0; }
};

/// The answer of min_distance.
struct FclMeshDistance {
  /// Smallest fcl::distance over the pairs when no pair collides and it is below the cutoff;
  /// the cutoff itself (a lower bound) when nothing is closer; 0 on collision.
  double distance = std::numeric_limits<double>::infinity();
  bool collision = false;    ///< Some pair's fcl::collide found intersecting surfaces.
  std::ptrdiff_t pair = -1;  ///< Index into pairs() of the colliding or nearest pair; -1: none.
  int collide_calls = 0;     ///< fcl::collide calls made (the rest were culled).
  int distance_calls = 0;    ///< fcl::distance calls made.
};

class FclMeshChecker {
 public:
  /// `meshes` must hold a link for every RobotModel link with collision shapes (by name).
  /// Throws std::invalid_argument for a matrix not sized for `model`, a model link with shapes
  /// that `meshes` lacks, or a padded obstacle.
  FclMeshChecker(std::shared_ptr<const FclMeshModel> meshes, const RobotModel& model,
                 const AllowedCollisionMatrix& matrix, const PlanningScene& scene);
  ~FclMeshChecker();
  FclMeshChecker(const FclMeshChecker&) = delete;
  FclMeshChecker& operator=(const FclMeshChecker&) = delete;

  /// Every checked pair, environment pairs first, then self pairs.
  const std::vector<FclMeshPair>& pairs() const;
  /// "link_a / link_b" or "link_a / obstacle name" of pair `i`.
  std::string pair_name(std::size_t i) const;

  /// Poses every element at `link_poses` (model frame <- link frame, indexed like the model's
  /// links); the queries below use the poses of the last call.
  void set_link_poses(const std::vector<Eigen::Isometry3d>& link_poses);

  /// Index of the first pair whose fcl::collide reports contact (AABB cull first), or -1.
  std::ptrdiff_t first_collision() const;
  /// True when some pair collides.
  bool in_collision() const { return first_collision() >= 0; }
  /// Collision, else the smallest fcl::distance over the pairs, exact below `cutoff` (m).
  /// First fcl::collide on every pair whose bounds overlap (stops at the first collision),
  /// then fcl::distance on the pairs in order of their lower bounds, in passes under cutoffs
  /// growing from 1 cm (x8 per pass, up to `cutoff`), each call seeded with the best so far.
  /// With `cutoff` <= 0 no distance is computed (a collision test only).
  FclMeshDistance min_distance(double cutoff = std::numeric_limits<double>::infinity()) const;
  /// fcl::collide, then (when apart) fcl::distance on pair `i` alone, with no cull and no
  /// seed: the reference that min_distance's culls and seeds must not change. 0 on contact.
  double pair_distance(std::size_t i) const;
  /// min_distance over the pairs between link `a` and link or obstacle `b` (names, either
  /// order) only; distance +inf when no such pair is checked.
  FclMeshDistance named_pair_distance(const std::string& a, const std::string& b) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hullcheck::test
