// Common interface over hullcheck and the peer libraries the benchmarks compare it with
// (libccd 2.1, FCL 0.7, Bullet 3.24 in double precision). Benchmark-only code: nothing here is
// part of hullcheck, and only the benchmark executables link the peers.
//
// Every implementation receives exactly the same input: the vertices of each hull (local frame,
// computed once with qhull), an outward triangulation of that hull (FCL needs faces), and the
// world poses of both shapes. `prepare` converts them to the implementation's own types outside
// the timed loop; the queries then take the index of a prepared case.
//
// Conventions of the results (each wrapper converts its library's convention to these):
//  - DistanceOut: points in the world frame, point_a on A, point_b on B.
//  - PenetrationOut: `normal` is the unit direction to translate B by `depth` to separate the
//    shapes (from A towards B), world frame.
//  - SignedOut: distance when apart, minus the depth when overlapping.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace hullcheck::bench {

/// A convex hull as every implementation receives it.
struct HullMesh {
  std::vector<Eigen::Vector3d> vertices;               ///< hull vertices, local frame
  std::vector<std::array<int, 3>> triangles;           ///< outward (counter-clockwise) triangles
  std::vector<std::vector<int>> neighbors;             ///< vertex adjacency along hull edges
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< mean of the vertices (local frame)
  double extent = 0.0;  ///< largest vertex distance from the local origin (hullcheck's scale)
};

/// Hull of a point set with qhull (option Qt: triangulated output), independent of hullcheck.
/// Throws std::runtime_error when qhull fails (e.g. flat input).
std::shared_ptr<const HullMesh> make_hull_mesh(const std::vector<Eigen::Vector3d>& points);

/// One query configuration: two hulls and their world poses (local -> world).
struct Case {
  std::shared_ptr<const HullMesh> a, b;
  Eigen::Isometry3d pose_a = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d pose_b = Eigen::Isometry3d::Identity();
};

enum class Query { kIntersect, kDistance, kPenetration, kSignedDistance };
const char* to_string(Query q);

struct DistanceOut {
  bool ok = true;         ///< false when the implementation gave no answer (failure, exception)
  bool flagged = false;   ///< answered, but flagged as not converged (hullcheck: status)
  bool separated = true;  ///< false when the implementation says the shapes overlap
  double distance = 0.0;
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero(), point_b = Eigen::Vector3d::Zero();
  int iterations = 0;  ///< GJK iterations when the implementation reports them, else 0
};

struct PenetrationOut {
  bool ok = true;
  bool flagged = false;
  bool overlapping = false;
  double depth = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< translate B by depth*normal to separate
};

struct SignedOut {
  bool ok = true;
  bool flagged = false;
  double value = 0.0;
};

/// One implementation of the proximity queries. Not thread-safe.
class Impl {
 public:
  virtual ~Impl() = default;
  /// Short name shown in the tables (e.g. "FCL indep").
  virtual std::string name() const = 0;
  /// Whether the implementation answers this query (and which API it uses, for the notes).
  virtual bool supports(Query q) const = 0;
  virtual std::string api(Query q) const = 0;
  /// Converts the cases to the implementation's own shape/pose types (not timed).
  virtual void prepare(const std::vector<Case>& cases) = 0;
  virtual bool intersect(std::size_t i) = 0;
  virtual DistanceOut distance(std::size_t i) = 0;
  virtual PenetrationOut penetration(std::size_t i) = 0;
  virtual SignedOut signed_distance(std::size_t i) = 0;
};

/// hullcheck free functions (intersect, distance, penetration, signed_distance), default options.
std::unique_ptr<Impl> make_hullcheck_impl();
/// libccd 2.1: ccdGJKIntersect / ccdGJKPenetration (GJK + EPA).
std::unique_ptr<Impl> make_libccd_gjk_impl();
/// libccd 2.1: ccdMPRIntersect / ccdMPRPenetration (Minkowski portal refinement).
std::unique_ptr<Impl> make_libccd_mpr_impl();
/// FCL 0.7 narrow phase with fcl::detail::GJKSolver_libccd<double> on fcl::Convex<double>.
std::unique_ptr<Impl> make_fcl_libccd_impl();
/// FCL 0.7 narrow phase with fcl::detail::GJKSolver_indep<double> on fcl::Convex<double>.
std::unique_ptr<Impl> make_fcl_indep_impl();
/// Bullet 3.24 (double precision) btGjkEpaSolver2 on btConvexHullShape with zero margin.
std::unique_ptr<Impl> make_bullet_impl();

/// All peers (not hullcheck), in table order.
std::vector<std::unique_ptr<Impl>> make_peer_impls();

}  // namespace hullcheck::bench
