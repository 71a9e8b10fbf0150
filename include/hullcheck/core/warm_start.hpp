// WarmStart: what one query between two shapes leaves for the next query of the same pair.
#pragma once

#include <Eigen/Core>

namespace hullcheck {

/// The state a query passes on to the next query of the same two shapes at nearby poses (in
/// the spirit of Box2D's simplex cache): the last separating direction, in A's local frame, and
/// for shapes with vertices (boxes, hulls, capsules' and spheres' cores) the final GJK simplex as
/// pairs of vertex indices, which the next query re-evaluates at its poses and starts from.
///
/// A starting point only: answers are the same to the query tolerance with any warm start,
/// including a default-constructed one (a cold start) or one left by another pair; indices out
/// of range for the shapes are ignored. It pays when the poses moved little since the query
/// that wrote it: GJK then usually needs one or two iterations. Plain data, 64 bytes; one per
/// ordered pair of shapes, owned by the caller (ProximityPair keeps its own).
struct WarmStart {
  Eigen::Vector3d direction{0, 0, 0};  ///< Last separating direction, A's frame (any length).
  bool valid = false;                  ///< false: a cold start (the rest is ignored).
  int simplex_size = 0;                ///< Vertex pairs below (0 to 4).
  int index_a[4] = {-1, -1, -1, -1};   ///< Vertex indices of A's core.
  int index_b[4] = {-1, -1, -1, -1};   ///< Vertex indices of B's core.
};

}  // namespace hullcheck
