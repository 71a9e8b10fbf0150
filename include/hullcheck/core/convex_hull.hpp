// ConvexHull: the convex hull of a point set, with a fast support function.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace hullcheck {

namespace detail {
struct HullData;
}

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

  const detail::HullData& data() const { return *data_; }

 private:
  std::shared_ptr<const detail::HullData> data_;
};

/// Volume, m^3, of the convex hull of `points` (qhull; no ConvexHull is built): 0 when the
/// points are fewer than 4, coplanar or otherwise degenerate. Reentrant; allocates.
double convex_hull_volume(const std::vector<Eigen::Vector3d>& points);

namespace detail {
/// Immutable hull storage, laid out for the support function.
struct HullData {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<double> xs, ys, zs;  // vertices as structure of arrays, padded to a multiple of 4
  /// Vertex adjacency along hull edges, laid out for hill climbing: vertex i's neighbours
  /// (ascending) occupy slots [neighbour_slots[i], neighbour_slots[i+1]), an even count (padded
  /// with i itself), with their indices in neighbour_index[slot] and their coordinates in one
  /// block per vertex starting at neighbour_coords[3 * neighbour_slots[i]]: all x, then all y,
  /// then all z.
  std::vector<std::int32_t> neighbour_slots;
  std::vector<std::int32_t> neighbour_index;
  std::vector<double> neighbour_coords;
  std::vector<std::array<int, 3>> triangles;
  /// Hill-climbing starts: the support vertex for the centre direction of each cell of a cube
  /// map (6 faces x kCells x kCells), so that a climb usually ends within a step or two.
  static constexpr int kCells = 12;
  std::vector<std::int32_t> start_table;
  int vertex_count = 0;  // vertices.size(), kept as an int for the support function
  int padded_count = 0;  // xs.size()
  int dimension = 0;
  double extent = 0.0;
  /// Balls about the bounding-box centre: one containing the hull, and one inside it when the
  /// centre is strictly inside (dimension 3), else inner_radius = -1 (no inner ball). Quick
  /// proofs of separation and of overlap.
  Eigen::Vector3d center{0, 0, 0};
  double outer_radius = 0.0;
  double inner_radius = -1.0;
};
}  // namespace detail

}  // namespace hullcheck
