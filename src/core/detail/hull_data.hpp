// The storage of a ConvexHull (opaque in the public header), laid out for the support
// functions of the query engine (support.hpp) and filled by ConvexHull's constructor.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <hullcheck/core/convex_hull.hpp>
#include <vector>

namespace hullcheck {

/// Immutable hull storage, laid out for the support function.
struct ConvexHull::Data {
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

}  // namespace hullcheck

namespace hullcheck::detail {

/// The engine's name for a hull's storage.
using HullData = ConvexHull::Data;

}  // namespace hullcheck::detail
