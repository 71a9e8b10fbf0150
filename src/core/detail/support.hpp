// Support functions of the "core" of each shape, in its local frame. A shape is its core grown
// by a radius (sphere = point + radius, capsule = segment + radius, any shape + margin); GJK and
// EPA run on the cores and add the radii analytically, which is exact and converges faster.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <cmath>
#include <hullcheck/core/convex_hull.hpp>

#include "hull_data.hpp"
#include "inline.hpp"

namespace hullcheck::detail {

// Each core has a centre inside it, with a ball around the core (outer_radius) and one inside
// it (inner_radius, negative when there is none). Each core's support(d, index) returns a maximiser
// of dot(p, d) and sets `index` to the vertex it is, for cores with finitely many vertices
// (vertex(index) gives it back for 0 <= index < vertex_count(); the warm start re-evaluates
// simplices from them); curved cores leave `index` unchanged.

/// A single point at the origin (core of a sphere).
struct PointCore {
  static constexpr bool kIndexed = true;
  int vertex_count() const { return 1; }
  Eigen::Vector3d vertex(int /*index*/) const { return Eigen::Vector3d::Zero(); }
  Eigen::Vector3d center() const { return Eigen::Vector3d::Zero(); }
  double outer_radius() const { return 0.0; }
  double inner_radius() const { return 0.0; }
  Eigen::Vector3d support(const Eigen::Vector3d& /*d*/, int& index) const {
    index = 0;
    return Eigen::Vector3d::Zero();
  }
};

/// Segment from (0,0,-h) to (0,0,h) (core of a capsule).
struct SegmentCore {
  static constexpr bool kIndexed = true;
  double half_length;
  int vertex_count() const { return 2; }
  Eigen::Vector3d vertex(int index) const { return {0.0, 0.0, index ? half_length : -half_length}; }
  Eigen::Vector3d center() const { return Eigen::Vector3d::Zero(); }
  double outer_radius() const { return half_length; }
  double inner_radius() const { return 0.0; }
  Eigen::Vector3d support(const Eigen::Vector3d& d, int& index) const {
    index = d.z() >= 0.0 ? 1 : 0;
    return vertex(index);
  }
};

/// Axis-aligned box with half extents.
struct BoxCore {
  static constexpr bool kIndexed = true;
  Eigen::Vector3d half;
  int vertex_count() const { return 8; }
  /// Corner by sign bits: bit 0 set for +x, bit 1 for +y, bit 2 for +z.
  Eigen::Vector3d vertex(int index) const {
    return {index & 1 ? half.x() : -half.x(), index & 2 ? half.y() : -half.y(),
            index & 4 ? half.z() : -half.z()};
  }
  Eigen::Vector3d center() const { return Eigen::Vector3d::Zero(); }
  double outer_radius() const { return half.norm(); }
  double inner_radius() const { return half.minCoeff(); }
  Eigen::Vector3d support(const Eigen::Vector3d& d, int& index) const {
    index = (d.x() >= 0.0 ? 1 : 0) | (d.y() >= 0.0 ? 2 : 0) | (d.z() >= 0.0 ? 4 : 0);
    return vertex(index);
  }
};

/// Solid cylinder, axis z.
struct CylinderCore {
  static constexpr bool kIndexed = false;
  double radius;
  double half_length;
  Eigen::Vector3d center() const { return Eigen::Vector3d::Zero(); }
  double outer_radius() const { return std::sqrt(radius * radius + half_length * half_length); }
  double inner_radius() const { return std::min(radius, half_length); }
  Eigen::Vector3d support(const Eigen::Vector3d& d, int& /*index*/) const {
    const double z = d.z() >= 0.0 ? half_length : -half_length;
    const double rxy2 = d.x() * d.x() + d.y() * d.y();
    if (rxy2 <= 0.0) return {0.0, 0.0, z};
    const double s = radius / std::sqrt(rxy2);
    return {d.x() * s, d.y() * s, z};
  }
};

/// Index of the vertex maximising dot(v, d): linear scan over the structure-of-arrays copy.
/// Two passes: the maximum value (two vertices per SSE2 instruction), then the first vertex
/// reaching it, computed with the same arithmetic so the values compare bit for bit. The arrays
/// are padded to a multiple of 4 with copies of vertex 0, which cannot change the answer.
HULLCHECK_ALWAYS_INLINE int scan_support_index(const HullData& h, const Eigen::Vector3d& d) {
  const double* xs = h.xs.data();
  const double* ys = h.ys.data();
  const double* zs = h.zs.data();
  const int n = h.vertex_count;
  const double dx = d.x(), dy = d.y(), dz = d.z();
#if defined(__SSE2__)
  const int padded = h.padded_count;
  const __m128d vdx = _mm_set1_pd(dx), vdy = _mm_set1_pd(dy), vdz = _mm_set1_pd(dz);
  __m128d m0 = _mm_set1_pd(-INFINITY), m1 = m0;
  for (int i = 0; i < padded; i += 4) {
    const __m128d v0 = _mm_add_pd(
        _mm_add_pd(_mm_mul_pd(_mm_loadu_pd(xs + i), vdx), _mm_mul_pd(_mm_loadu_pd(ys + i), vdy)),
        _mm_mul_pd(_mm_loadu_pd(zs + i), vdz));
    const __m128d v1 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_loadu_pd(xs + i + 2), vdx),
                                             _mm_mul_pd(_mm_loadu_pd(ys + i + 2), vdy)),
                                  _mm_mul_pd(_mm_loadu_pd(zs + i + 2), vdz));
    m0 = _mm_max_pd(m0, v0);
    m1 = _mm_max_pd(m1, v1);
  }
  const __m128d m = _mm_max_pd(m0, m1);
  const double maximum = std::max(_mm_cvtsd_f64(m), _mm_cvtsd_f64(_mm_unpackhi_pd(m, m)));
  for (int i = 0; i < n; ++i) {
    if ((xs[i] * dx + ys[i] * dy) + zs[i] * dz == maximum) return i;
  }
  // Not reached unless the compiler fused the scalar arithmetic differently (or d is NaN):
  // fall through to the plain argmax.
#endif
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
/// Each step evaluates the current vertex's neighbours from their contiguous block (two per
/// SSE2 instruction), then moves to the first neighbour with the largest value if it beats the
/// current one; values are computed as in scan_support_index, so they compare bit for bit.
inline int climb_support_index(const HullData& h, const Eigen::Vector3d& d, int start) {
  const std::int32_t* slots = h.neighbour_slots.data();
  const std::int32_t* index = h.neighbour_index.data();
  const double* coords = h.neighbour_coords.data();
  const double dx = d.x(), dy = d.y(), dz = d.z();
  int current = start;
  const Eigen::Vector3d& v = h.vertices[current];
  double current_value = (v.x() * dx + v.y() * dy) + v.z() * dz;
  // Each step strictly increases the value, so at most vertex_count steps are taken.
  for (;;) {
    const int first = slots[current], count = slots[current + 1] - first;
    const double* xs = coords + 3 * first;
    const double* ys = xs + count;
    const double* zs = ys + count;
#if defined(__SSE2__)
    const __m128d vdx = _mm_set1_pd(dx), vdy = _mm_set1_pd(dy), vdz = _mm_set1_pd(dz);
    __m128d m = _mm_set1_pd(-INFINITY);
    for (int k = 0; k < count; k += 2) {
      const __m128d value = _mm_add_pd(
          _mm_add_pd(_mm_mul_pd(_mm_loadu_pd(xs + k), vdx), _mm_mul_pd(_mm_loadu_pd(ys + k), vdy)),
          _mm_mul_pd(_mm_loadu_pd(zs + k), vdz));
      m = _mm_max_pd(m, value);
    }
    const double best = std::max(_mm_cvtsd_f64(m), _mm_cvtsd_f64(_mm_unpackhi_pd(m, m)));
#else
    double best = -INFINITY;
    for (int k = 0; k < count; ++k) best = std::max(best, (xs[k] * dx + ys[k] * dy) + zs[k] * dz);
#endif
    if (!(best > current_value)) return current;
    const auto value_at = [&](int k) { return (xs[k] * dx + ys[k] * dy) + zs[k] * dz; };
    int k = 0;
    while (k < count && value_at(k) != best) ++k;
    if (k == count) {  // only if the compiler fused the scalar arithmetic differently: argmax
      k = 0;
      for (int j = 1; j < count; ++j) {
        if (value_at(j) > value_at(k)) k = j;
      }
      if (!(value_at(k) > current_value)) return current;
    }
    current = index[first + k];
    current_value = value_at(k);
  }
}

/// Cube-map cell of a direction: the face of its largest component, then a kCells x kCells
/// grid over that face. Cells are indexed face * kCells^2 + row * kCells + column.
inline int cube_map_cell(const Eigen::Vector3d& d) {
  constexpr int k = HullData::kCells;
  const double ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
  int face;
  double u, v, m;
  if (ax >= ay && ax >= az) {
    face = d.x() >= 0.0 ? 0 : 1;
    u = d.y();
    v = d.z();
    m = ax;
  } else if (ay >= az) {
    face = d.y() >= 0.0 ? 2 : 3;
    u = d.x();
    v = d.z();
    m = ay;
  } else {
    face = d.z() >= 0.0 ? 4 : 5;
    u = d.x();
    v = d.y();
    m = az;
  }
  if (!(m > 0.0)) return 0;
  const double scale = 0.5 * k / m;  // u/m in [-1, 1] -> [0, k]
  // Clamped in floating point before the conversion, so that a NaN (a NaN or infinite
  // component beside a finite largest one) lands in cell 0 of the face, never out of range.
  const auto bin = [](double x) {
    return static_cast<int>(x >= 0.0 ? std::min(x, static_cast<double>(k - 1)) : 0.0);
  };
  return (face * k + bin((u + m) * scale)) * k + bin((v + m) * scale);
}

/// Centre direction of a cube-map cell (inverse of cube_map_cell).
inline Eigen::Vector3d cube_map_direction(int cell) {
  constexpr int k = HullData::kCells;
  const int face = cell / (k * k), row = (cell / k) % k, column = cell % k;
  const double u = (row + 0.5) * 2.0 / k - 1.0, v = (column + 0.5) * 2.0 / k - 1.0;
  const double sign = face % 2 == 0 ? 1.0 : -1.0;
  switch (face / 2) {
    case 0:
      return {sign, u, v};
    case 1:
      return {u, sign, v};
    default:
      return {u, v, sign};
  }
}

/// Convex hull core.
struct HullCore {
  static constexpr bool kIndexed = true;
  const HullData* data;
  int vertex_count() const { return data->vertex_count; }
  const Eigen::Vector3d& vertex(int index) const { return data->vertices[index]; }
  const Eigen::Vector3d& center() const { return data->center; }
  double outer_radius() const { return data->outer_radius; }
  double inner_radius() const { return data->inner_radius; }
  HULLCHECK_ALWAYS_INLINE Eigen::Vector3d support(const Eigen::Vector3d& d, int& index) const {
    const HullData& h = *data;
    if (h.vertex_count < static_cast<int>(ConvexHull::kHillClimbingThreshold)) {
      index = scan_support_index(h, d);
    } else {
      index = climb_support_index(h, d, h.start_table[cube_map_cell(d)]);
    }
    return h.vertices[index];
  }
};

/// core.support(d, index), given `hint`: the vertex index of a support point in a nearby
/// direction (-1: none). Hulls that hill-climb with fewer than kNearHintLimit vertices start
/// the climb there instead of at the cube map's vertex (EPA asks for supports along face
/// normals whose vertices are such points): it saves the cell lookup and is as close; on finer
/// hulls the cube map's start is closer in steps. Exact either way.
constexpr int kNearHintLimit = 64;
template <class Core>
HULLCHECK_ALWAYS_INLINE Eigen::Vector3d support_near(const Core& core, const Eigen::Vector3d& d,
                                                     int /*hint*/, int& index) {
  return core.support(d, index);
}
HULLCHECK_ALWAYS_INLINE Eigen::Vector3d support_near(const HullCore& core, const Eigen::Vector3d& d,
                                                     int hint, int& index) {
  const HullData& h = *core.data;
  // One unsigned comparison rejects -1 and any index out of range.
  if (static_cast<unsigned>(hint) >= static_cast<unsigned>(h.vertex_count) ||
      h.vertex_count < static_cast<int>(ConvexHull::kHillClimbingThreshold) ||
      h.vertex_count >= kNearHintLimit) {
    return core.support(d, index);
  }
  index = climb_support_index(h, d, hint);
  return h.vertices[index];
}

}  // namespace hullcheck::detail
