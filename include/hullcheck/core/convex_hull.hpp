// ConvexHull: the convex hull of a point set, with a fast support function.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

namespace hullcheck {

/// Convex hull of a finite point set, in the points' own (local) frame.
///
/// Built once with qhull; the input may contain duplicates, and may be coplanar (a flat polygon),
/// collinear (a segment) or a single point: the hull then has dimension 2, 1 or 0 and is still a
/// valid shape for every query. Points closer than 1e-12 x (set size) to a lower-dimensional
/// affine hull are treated as lying on it.
///
/// The support function is exact (it returns a vertex that maximises the dot product). Below
/// `kHillClimbingThreshold` vertices it scans all vertices; above, it hill-climbs over the vertex
/// adjacency graph, which on a convex polytope always ends at a global maximum, starting from a
/// precomputed support vertex of a nearby direction (a cube map of 864 directions).
///
/// Copying is cheap: copies share the immutable hull data. Thread-safe for concurrent reads.
/// Throws InputError for an empty point set, or a coordinate that is not finite or exceeds
/// kMaxLength (1e6 m) in magnitude (naming the point index).
class ConvexHull {
 public:
  /// Hull vertex count from which support uses hill climbing instead of a linear scan.
  static constexpr std::size_t kHillClimbingThreshold = 24;

  explicit ConvexHull(const std::vector<Eigen::Vector3d>& points);

  /// Hull vertices (a subset of the input points, exact copies), local frame.
  const std::vector<Eigen::Vector3d>& vertices() const;
  std::size_t vertex_count() const;
  /// Affine dimension of the hull: 0 point, 1 segment, 2 polygon, 3 polytope.
  int dimension() const;
  /// Indices (into vertices()) of the vertices joined to vertex `i` by a hull edge.
  std::vector<int> neighbors(int i) const;
  /// Triangulated boundary (indices into vertices()), outward-facing for dimension 3;
  /// for a polygon, a fan over its vertices; empty for dimension < 2.
  const std::vector<std::array<int, 3>>& triangles() const;
  /// Largest distance of a vertex from the local origin: the scale used by tolerances.
  double extent() const;
  /// A vertex maximising dot(v, direction) (local frame). Zero direction gives some vertex.
  Eigen::Vector3d support(const Eigen::Vector3d& direction) const;
  /// Index (into vertices()) of such a vertex.
  int support_index(const Eigen::Vector3d& direction) const;
  /// A ball containing the hull: its centre (the vertices' bounding-box centre, local frame)
  /// and radius (the largest distance of a vertex from it, rounded up).
  const Eigen::Vector3d& bounding_ball_center() const;
  double bounding_ball_radius() const;

  /// The hull's storage, laid out for the support function: opaque here, defined in the core's
  /// private headers for the query engine.
  struct Data;
  const Data& data() const { return *data_; }

 private:
  std::shared_ptr<const Data> data_;
};

/// Volume, m^3, of the convex hull of `points` (qhull; no ConvexHull is built): 0 when the
/// points are fewer than 4, coplanar or otherwise degenerate. Reentrant; allocates.
double convex_hull_volume(const std::vector<Eigen::Vector3d>& points);

}  // namespace hullcheck
