// Support functions of the "core" of each shape, in its local frame. A shape is its core grown
// by a radius (sphere = point + radius, capsule = segment + radius, any shape + margin); GJK and
// EPA run on the cores and add the radii analytically, which is exact and converges faster.
#pragma once

#include <Eigen/Core>
#include <hullcheck/convex_hull.hpp>

namespace hullcheck::detail {

/// A single point at the origin (core of a sphere).
struct PointCore {
  Eigen::Vector3d support(const Eigen::Vector3d& /*d*/, int& /*hint*/) const {
    return Eigen::Vector3d::Zero();
  }
};

/// Segment from (0,0,-h) to (0,0,h) (core of a capsule).
struct SegmentCore {
  double half_length;
  Eigen::Vector3d support(const Eigen::Vector3d& d, int& /*hint*/) const {
    return {0.0, 0.0, d.z() >= 0.0 ? half_length : -half_length};
  }
};

/// Axis-aligned box with half extents.
struct BoxCore {
  Eigen::Vector3d half;
  Eigen::Vector3d support(const Eigen::Vector3d& d, int& /*hint*/) const {
    return {d.x() >= 0.0 ? half.x() : -half.x(), d.y() >= 0.0 ? half.y() : -half.y(),
            d.z() >= 0.0 ? half.z() : -half.z()};
  }
};

/// Solid cylinder, axis z.
struct CylinderCore {
  double radius;
  double half_length;
  Eigen::Vector3d support(const Eigen::Vector3d& d, int& /*hint*/) const {
    const double z = d.z() >= 0.0 ? half_length : -half_length;
    const double rxy2 = d.x() * d.x() + d.y() * d.y();
    if (rxy2 <= 0.0) return {0.0, 0.0, z};
    const double s = radius / std::sqrt(rxy2);
    return {d.x() * s, d.y() * s, z};
  }
};

/// Index of the vertex maximising dot(v, d): linear scan over the structure-of-arrays copy.
inline int scan_support_index(const HullData& h, const Eigen::Vector3d& d) {
  const double* xs = h.xs.data();
  const double* ys = h.ys.data();
  const double* zs = h.zs.data();
  const int n = static_cast<int>(h.xs.size());
  const double dx = d.x(), dy = d.y(), dz = d.z();
  int best = 0;
  double best_value = xs[0] * dx + ys[0] * dy + zs[0] * dz;
  for (int i = 1; i < n; ++i) {
    const double value = xs[i] * dx + ys[i] * dy + zs[i] * dz;
    if (value > best_value) {
      best_value = value;
      best = i;
    }
  }
  return best;
}

/// Index of a vertex maximising dot(v, d) by steepest-ascent hill climbing over the hull's edge
/// graph from `start`. Exact on a convex polytope: a vertex with no strictly better neighbour
/// is a global maximum (the edge directions at a vertex span a cone containing the polytope).
inline int climb_support_index(const HullData& h, const Eigen::Vector3d& d, int start) {
  const double* xs = h.xs.data();
  const double* ys = h.ys.data();
  const double* zs = h.zs.data();
  const std::int32_t* offsets = h.adjacency_offsets.data();
  const std::int32_t* adjacency = h.adjacency.data();
  const double dx = d.x(), dy = d.y(), dz = d.z();
  int current = start;
  double current_value = xs[current] * dx + ys[current] * dy + zs[current] * dz;
  // Each step strictly increases the value, so at most vertex_count steps are taken.
  for (;;) {
    int next = -1;
    for (std::int32_t k = offsets[current]; k < offsets[current + 1]; ++k) {
      const int j = adjacency[k];
      const double value = xs[j] * dx + ys[j] * dy + zs[j] * dz;
      if (value > current_value) {
        current_value = value;
        next = j;
      }
    }
    if (next < 0) return current;
    current = next;
  }
}

inline int octant_of(const Eigen::Vector3d& d) {
  return (d.x() >= 0.0 ? 1 : 0) | (d.y() >= 0.0 ? 2 : 0) | (d.z() >= 0.0 ? 4 : 0);
}

/// Convex hull core; `hint` carries the last support vertex between calls (warm start).
struct HullCore {
  const HullData* data;
  Eigen::Vector3d support(const Eigen::Vector3d& d, int& hint) const {
    const HullData& h = *data;
    if (h.xs.size() < ConvexHull::kHillClimbingThreshold) {
      hint = scan_support_index(h, d);
    } else {
      hint = climb_support_index(h, d, hint >= 0 ? hint : h.octant_start[octant_of(d)]);
    }
    return h.vertices[hint];
  }
};

}  // namespace hullcheck::detail
