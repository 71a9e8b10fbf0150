// Point queries against a fixed triangle mesh: the exact distance to its surface (through a
// bounding-box tree) and whether a point is inside the solid it bounds (winding number).
#pragma once

#include <Eigen/Geometry>
#include <hullcheck/robot/mesh_file.hpp>
#include <vector>

namespace hullcheck::detail {

/// The triangle point nearest to `p` (Ericson, Real-Time Collision Detection, 5.1.5: the
/// Voronoi regions of the corners, edges and face, tested in that order).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Distance and inside queries on one mesh, built once (O(n log n) in the triangle count).
/// Units are the mesh's (m). Degenerate triangles (zero area) are kept: their distance is that
/// of their segment or point. Immutable after construction; const queries are thread-safe.
class MeshDistance {
 public:
  explicit MeshDistance(const TriangleMesh& mesh);

  /// Euclidean distance from `p` to the nearest point of any triangle (exact up to rounding).
  /// +inf when the mesh has no triangle.
  double surface_distance(const Eigen::Vector3d& p) const { return nearest(p).distance; }

  /// The nearest triangle to a point: its distance and its index (into the tree's order, for
  /// triangle_distance); index -1 and +inf when the mesh has no triangle.
  struct Nearest {
    double distance;
    int triangle;
  };
  Nearest nearest(const Eigen::Vector3d& p) const;
  /// Distance from `p` to triangle `triangle` (an index from nearest()).
  double triangle_distance(const Eigen::Vector3d& p, int triangle) const;

  /// The generalised winding number of the triangles around `p` (Jacobson et al. 2013: the sum
  /// of the triangles' signed solid angles over 4 pi): +-1 inside a closed mesh (the sign is
  /// the orientation's), 0 outside, fractional near the holes of an open mesh. O(triangles).
  double winding_number(const Eigen::Vector3d& p) const;

  /// Whether `p` is inside the solid the surface bounds: the majority vote of three rays from p
  /// in fixed, unrelated directions (through the box tree, O(log n) each), each counting the
  /// triangles it crosses with the sign of the side it enters from; a non-zero sum (the
  /// winding number about p) is inside. Exact for closed, consistently oriented shells, also
  /// where several shells overlap (CAD exports often hold such unions); an open mesh gets the
  /// vote of the rays. A ray passing within 1e-9 (barycentric) of a triangle's edge, or lying
  /// in a triangle's plane, is replaced by another direction (the winding number, O(n), when
  /// all eight directions are degenerate).
  bool inside(const Eigen::Vector3d& p) const;

 private:
  struct Node {  // bounding box of triangles [begin, end) of order_, children when inner
    Eigen::Vector3d lo, hi;
    int begin = 0, end = 0;
    int left = -1, right = -1;
  };
  int build(int begin, int end);
  /// Signed crossings of the ray p + t*d (t > 0) with the triangles; INT_MIN when the ray is
  /// degenerate.
  int crossings(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const;
  double box_distance_squared(const Node& n, const Eigen::Vector3d& p) const;

  std::vector<Eigen::Vector3d> a_, b_, c_;  // triangle corners, in tree order
  std::vector<Node> nodes_;
};

}  // namespace hullcheck::detail
