// EPA (Expanding Polytope Algorithm, seed section 3 and algorithm 3): the point of the boundary
// of the core difference A - B nearest to the origin, when the origin is inside it.
//
// Storage is fixed (kMaxVertices, kMaxFaces) and lives in the caller's EpaWorkspace, so a query
// never allocates. Faces keep their neighbours across each edge; a new support point removes
// the faces that see it (found by a walk from the closest face) and is joined to the horizon.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <hullcheck/core/query_result.hpp>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "minkowski.hpp"
#include "simplex.hpp"

namespace hullcheck::detail {

constexpr int kEpaMaxVertices = 256;
constexpr int kEpaMaxFaces = 2 * kEpaMaxVertices;

struct EpaFace {
  int vertex[3];    // counter-clockwise seen from outside
  int neighbor[3];  // face across edge (vertex[i], vertex[(i+1)%3])
  int neighbor_edge[3];
  Eigen::Vector3d normal;  // unit, outward
  double offset;           // normal . vertex: distance of the plane from the origin
  bool alive;
  bool degenerate;  // zero area: never chosen as closest, removed when seen
};

struct EpaWorkspace {
  std::array<SimplexVertex, kEpaMaxVertices> vertices;
  /// Core vertex indices behind each vertex's a and b (-1: unknown, or a curved core): hints
  /// for the support calls along the normals of faces through them.
  std::array<std::array<int, 2>, kEpaMaxVertices> core_index;
  std::array<EpaFace, kEpaMaxFaces> faces;
  /// Selection key per face slot: its plane offset, +infinity when removed or degenerate; kept
  /// contiguous so that finding the closest face is a tight scan.
  std::array<double, kEpaMaxFaces> key;
  std::array<int, kEpaMaxFaces> free_faces;
  std::array<int, kEpaMaxFaces> stack;
  std::array<std::array<int, 2>, kEpaMaxFaces> horizon;  // (face, edge) pairs kept
  std::array<int, kEpaMaxVertices> new_face_of_vertex;
  std::array<std::uint64_t, kEpaMaxVertices> new_face_stamp;  // epoch that set the entry
  std::uint64_t epoch = 0;  // one per expansion, never reset (a thread-local workspace)
};

struct EpaOutput {
  double depth = 0.0;               ///< Distance from the origin to the boundary (>= 0).
  Eigen::Vector3d normal{0, 0, 1};  ///< Unit outward normal at the nearest boundary point.
  Eigen::Vector3d point_a{0, 0, 0},
      point_b{0, 0, 0};  ///< Witnesses: point_a - point_b = depth * normal
  Status status = Status::kConverged;
  int iterations = 0;
};

namespace epa_internal {

/// Plane of a face. A face is degenerate when the sine of its angle at vertex 0 is below 1e-12
/// (a sliver or a zero-area face, whose normal has no significant digits).
inline void set_plane(EpaWorkspace& ws, EpaFace& f) {
  const Eigen::Vector3d& p0 = ws.vertices[f.vertex[0]].w;
  const Eigen::Vector3d e1 = ws.vertices[f.vertex[1]].w - p0;
  const Eigen::Vector3d e2 = ws.vertices[f.vertex[2]].w - p0;
  Eigen::Vector3d n = e1.cross(e2);
  const double length_squared = n.squaredNorm();
  // |e1 x e2| > 1e-12 |e1| |e2|, written without the product of squares (which overflows for
  // coordinates beyond ~1e77 and underflows below ~1e-77).
  f.degenerate = !(std::sqrt(length_squared) > 1e-12 * (e1.norm() * e2.norm()));
  if (f.degenerate) {
    f.normal = Eigen::Vector3d::UnitZ();
    f.offset = INFINITY;
    return;
  }
  n /= std::sqrt(length_squared);
  f.normal = n;
  f.offset = n.dot(p0);  // the other vertices agree up to rounding
}

/// Closest point of a face's triangle to the origin (indices 0-2 into face.vertex).
inline SubSimplex closest_on_face(const EpaWorkspace& ws, const EpaFace& face) {
  const Eigen::Vector3d points[3] = {ws.vertices[face.vertex[0]].w, ws.vertices[face.vertex[1]].w,
                                     ws.vertices[face.vertex[2]].w};
  return closest_on_triangle(points, 0, 1, 2);
}

/// Barycentric weights of `p`, a point of the plane of triangle (w0, w1, w2) with unit normal
/// `n`, from signed areas on the coordinate plane most orthogonal to n (weights outside [0, 1]
/// when p lies outside the triangle; they sum to 1).
inline void plane_weights(const Eigen::Vector3d& w0, const Eigen::Vector3d& w1,
                          const Eigen::Vector3d& w2, const Eigen::Vector3d& n,
                          const Eigen::Vector3d& p, double (&lambda)[3]) {
  int k = 0;
  if (std::abs(n.y()) > std::abs(n(k))) k = 1;
  if (std::abs(n.z()) > std::abs(n(k))) k = 2;
  const int x = (k + 1) % 3, y = (k + 2) % 3;
  const auto area = [x, y](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
    return (b(x) - a(x)) * (c(y) - a(y)) - (b(y) - a(y)) * (c(x) - a(x));
  };
  const double total = area(w0, w1, w2);
  lambda[1] = area(w0, p, w2) / total;
  lambda[2] = area(w0, w1, p) / total;
  lambda[0] = 1.0 - lambda[1] - lambda[2];
}

/// Index of the first smallest finite key among keys[0, count), or -1 when none is finite.
/// Two passes: the minimum (two keys per SSE2 instruction), then its first position. Face
/// slots are few hundred at most; removed and degenerate faces have key +infinity.
inline int closest_face(const double* keys, int count) {
  double minimum = INFINITY;
  int f = 0;
#if defined(__SSE2__)
  __m128d m0 = _mm_set1_pd(INFINITY), m1 = m0;
  for (; f + 4 <= count; f += 4) {
    m0 = _mm_min_pd(m0, _mm_loadu_pd(keys + f));
    m1 = _mm_min_pd(m1, _mm_loadu_pd(keys + f + 2));
  }
  const __m128d m = _mm_min_pd(m0, m1);
  minimum = std::min(_mm_cvtsd_f64(m), _mm_cvtsd_f64(_mm_unpackhi_pd(m, m)));
#endif
  for (; f < count; ++f) minimum = std::min(minimum, keys[f]);
  for (f = 0; f < count; ++f) {
    if (keys[f] == minimum && minimum < INFINITY) return f;
  }
  // No finite key, or a NaN key upset the minimum: the plain scan, which skips NaN.
  int best = -1;
  double best_key = INFINITY;
  for (f = 0; f < count; ++f) {
    if (keys[f] < best_key) {
      best_key = keys[f];
      best = f;
    }
  }
  return best;
}

}  // namespace epa_internal

/// Grows a simplex containing the origin (from GJK, any size 1-4) into a tetrahedron; returns
/// false when the difference is flat (lower-dimensional), filling `flat_normal` with a unit
/// vector orthogonal to it: the depth is then 0.
template <class MD>
bool epa_initial_tetrahedron(MD& md, Simplex& s, double epsilon, Eigen::Vector3d& flat_normal) {
  const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                   Eigen::Vector3d::UnitZ()};
  if (s.size == 1) {
    bool grown = false;
    for (int i = 0; i < 6 && !grown; ++i) {
      const Eigen::Vector3d d = (i % 2 == 0 ? 1.0 : -1.0) * axes[i / 2];
      md.support(d, s.w[1], s.a[1], s.b[1]);
      s.index_a[1] = md.index_a;
      s.index_b[1] = md.index_b;
      grown = (s.w[1] - s.w[0]).norm() > epsilon;
    }
    if (!grown) {
      flat_normal = Eigen::Vector3d::UnitX();
      return false;
    }
    s.size = 2;
  }
  if (s.size == 2) {
    const Eigen::Vector3d u = (s.w[1] - s.w[0]).normalized();
    int k = 0;
    if (std::abs(u.y()) < std::abs(u(k))) k = 1;
    if (std::abs(u.z()) < std::abs(u(k))) k = 2;
    const Eigen::Vector3d d1 = u.cross(axes[k]).normalized();
    const Eigen::Vector3d d2 = u.cross(d1);
    bool grown = false;
    const Eigen::Vector3d directions[6] = {d1, -d1, d2, -d2, d1 + d2, -d1 - d2};
    for (int i = 0; i < 6 && !grown; ++i) {
      md.support(directions[i], s.w[2], s.a[2], s.b[2]);
      s.index_a[2] = md.index_a;
      s.index_b[2] = md.index_b;
      grown = (s.w[2] - s.w[0]).cross(u).norm() > epsilon;
    }
    if (!grown) {
      flat_normal = d1;
      return false;
    }
    s.size = 3;
  }
  if (s.size == 3) {
    const Eigen::Vector3d n = (s.w[1] - s.w[0]).cross(s.w[2] - s.w[0]).normalized();
    md.support(n, s.w[3], s.a[3], s.b[3]);
    double height = n.dot(s.w[3] - s.w[0]);
    if (!(std::abs(height) > epsilon)) {
      md.support(-n, s.w[3], s.a[3], s.b[3]);
      height = n.dot(s.w[3] - s.w[0]);
    }
    s.index_a[3] = md.index_a;
    s.index_b[3] = md.index_b;
    if (!(std::abs(height) > epsilon)) {
      flat_normal = n;
      return false;
    }
    s.size = 4;
  }
  return true;
}

/// EPA from a tetrahedron `s` that contains the origin (on its boundary at worst).
/// `tolerance`: absolute; stops when the support distance along the closest face's normal is
/// within it of the face's distance (then the depth is exact to `tolerance`).
/// `stop_depth`: when the depth is proven below it (a support plane closer than it), EPA stops
/// with status kAboveCutoff and `depth` = that upper bound of the depth (no witnesses).
template <class MD>
EpaOutput epa(MD& md, const Simplex& s, double tolerance, int max_iterations, EpaWorkspace& ws,
              double stop_depth = INFINITY) {
  using epa_internal::closest_on_face;
  using epa_internal::set_plane;
  EpaOutput out;
  // A point is above a face when it is more than this above its plane (rounding noise of the
  // coordinates is ~1e-16 x scale; tolerance is ~1e-10 x scale).
  const double visibility_epsilon = 1e-4 * tolerance;
  int vertex_count = 4;
  for (int i = 0; i < 4; ++i) {
    ws.vertices[i] = s.vertex(i);
    ws.core_index[i] = {s.index_a[i], s.index_b[i]};
  }
  // Orient the tetrahedron so that (0,1,2) sees vertex 3 on its negative side.
  {
    const Eigen::Vector3d& p0 = ws.vertices[0].w;
    const double volume =
        (ws.vertices[1].w - p0).cross(ws.vertices[2].w - p0).dot(ws.vertices[3].w - p0);
    if (volume > 0.0) {
      std::swap(ws.vertices[1], ws.vertices[2]);
      std::swap(ws.core_index[1], ws.core_index[2]);
    }
  }
  // Faces of tetrahedron (0,1,2),(0,3,1),(0,2,3),(1,3,2) with consistent outward winding.
  static constexpr int kTetFaces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  int face_count = 0;  // high-water mark of used face slots
  int free_count = 0;
  for (int f = 0; f < 4; ++f) {
    EpaFace& face = ws.faces[f];
    for (int i = 0; i < 3; ++i) face.vertex[i] = kTetFaces[f][i];
    face.alive = true;
    set_plane(ws, face);
    ws.key[f] = face.offset;
  }
  face_count = 4;
  // Neighbours across each edge of kTetFaces (edge i joins vertex[i] and vertex[i+1]).
  static constexpr int kTetNeighbor[4][3] = {{1, 3, 2}, {2, 3, 0}, {0, 3, 1}, {1, 2, 0}};
  static constexpr int kTetNeighborEdge[4][3] = {{2, 2, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 1}};
  for (int f = 0; f < 4; ++f) {
    for (int i = 0; i < 3; ++i) {
      ws.faces[f].neighbor[i] = kTetNeighbor[f][i];
      ws.faces[f].neighbor_edge[i] = kTetNeighborEdge[f][i];
    }
  }

  int best = -1;
  EpaFace result{};  // copy of the closest face: its slot may be reused by the expansion
  for (int iteration = 1;; ++iteration) {
    out.iterations = iteration;
    best = epa_internal::closest_face(ws.key.data(), face_count);
    if (best < 0) {  // every face degenerate: cannot happen for a proper tetrahedron
      out.status = Status::kDegenerate;
      break;
    }
    result = ws.faces[best];
    const EpaFace& closest = result;
    if (iteration > max_iterations || vertex_count == kEpaMaxVertices) {
      out.status = Status::kIterationCap;
      break;
    }
    SimplexVertex& w = ws.vertices[vertex_count];
    // The support climbs start at the face's newest vertex (its last; the expansion puts the
    // new support point there): a support point of a nearby direction.
    const std::array<int, 2>& hint = ws.core_index[closest.vertex[2]];
    md.support(closest.normal, w.w, w.a, w.b, hint[0], hint[1]);
    ws.core_index[vertex_count] = {md.index_a, md.index_b};
    const double support_offset = closest.normal.dot(w.w);
    if (support_offset - closest.offset <= tolerance) break;  // converged
    if (support_offset < stop_depth) {  // every point of the boundary is within that plane
      out.status = Status::kAboveCutoff;
      out.depth = support_offset;
      return out;
    }
    // Remove every face that sees w, walking from the closest face; collect the horizon.
    const int new_vertex = vertex_count++;
    int horizon_count = 0;
    int stack_size = 0;
    ws.faces[best].alive = false;
    ws.key[best] = INFINITY;
    ws.stack[stack_size++] = best;
    bool broken = false;
    while (stack_size > 0 && !broken) {
      const int f = ws.stack[--stack_size];
      ws.free_faces[free_count++] = f;  // removed: its slot is free once the walk is done
      for (int i = 0; i < 3; ++i) {
        const int g = ws.faces[f].neighbor[i];
        EpaFace& neighbor = ws.faces[g];
        if (!neighbor.alive) continue;
        const bool visible =
            neighbor.degenerate || neighbor.normal.dot(w.w) - neighbor.offset > visibility_epsilon;
        if (visible) {
          neighbor.alive = false;
          ws.key[g] = INFINITY;
          ws.stack[stack_size++] = g;
        } else if (horizon_count < kEpaMaxFaces) {
          ws.horizon[horizon_count++] = {g, ws.faces[f].neighbor_edge[i]};
        } else {
          broken = true;  // cannot happen on a consistent polytope
        }
      }
    }
    // Visibility depends only on the face and w, so a face recorded on the horizon (not
    // visible) is never removed later in the walk: every recorded edge is a horizon edge.
    if (horizon_count < 3 || face_count + horizon_count > kEpaMaxFaces) {
      out.status = Status::kDegenerate;
      broken = true;
    }
    if (broken) break;
    // One new face per horizon edge (b, a, w) where (a, b) is the edge in the kept face.
    const std::uint64_t epoch = ++ws.epoch;
    for (int h = 0; h < horizon_count; ++h) {
      const int g = ws.horizon[h][0];
      const int e = ws.horizon[h][1];
      const int a = ws.faces[g].vertex[e];
      const int b = ws.faces[g].vertex[(e + 1) % 3];
      const int f = free_count > 0 ? ws.free_faces[--free_count] : face_count++;
      EpaFace& face = ws.faces[f];
      face.vertex[0] = b;
      face.vertex[1] = a;
      face.vertex[2] = new_vertex;
      face.alive = true;
      face.neighbor[0] = g;
      face.neighbor_edge[0] = e;
      ws.faces[g].neighbor[e] = f;
      ws.faces[g].neighbor_edge[e] = 0;
      set_plane(ws, face);
      ws.key[f] = face.offset;
      if (ws.new_face_stamp[b] == epoch) broken = true;  // horizon is not a simple loop
      ws.new_face_of_vertex[b] = f;                      // the new face whose edge (w, b) is edge 2
      ws.new_face_stamp[b] = epoch;
      ws.horizon[h][0] = f;
    }
    for (int h = 0; h < horizon_count && !broken; ++h) {
      broken = ws.new_face_stamp[ws.faces[ws.horizon[h][0]].vertex[1]] != epoch;
    }
    if (broken) {
      out.status = Status::kDegenerate;
      break;
    }
    // Link the new faces: edge 1 (a, w) of one meets edge 2 (w, a) of the new face built on
    // the horizon edge that ends at a.
    for (int h = 0; h < horizon_count; ++h) {
      const int f = ws.horizon[h][0];
      const int a = ws.faces[f].vertex[1];
      const int g = ws.new_face_of_vertex[a];
      ws.faces[f].neighbor[1] = g;
      ws.faces[f].neighbor_edge[1] = 2;
      ws.faces[g].neighbor[2] = f;
      ws.faces[g].neighbor_edge[2] = 1;
    }
  }
  if (best >= 0) {
    // Witnesses: several faces can share the nearest plane (coplanar triangles of one polytope
    // face); take the one whose triangle holds the origin's projection, i.e. whose closest
    // point to the origin is nearest. Only faces of that plane qualify: a face of another
    // plane at the same distance (symmetric differences, e.g. identical shapes) has another
    // normal, and its witnesses would contradict the one reported. Depth and normal are those
    // of the face the witnesses come from, so point_a - point_b = depth * normal holds by
    // construction (up to rounding, when the projection lies in the triangle).
    EpaFace face = result;
    SubSimplex sub = closest_on_face(ws, face);
    if (out.status == Status::kConverged && sub.size < 3) {  // projection outside the face
      for (int f = 0; f < face_count; ++f) {
        if (!(ws.key[f] <= result.offset + tolerance)) continue;  // removed, degenerate or far
        const EpaFace& candidate = ws.faces[f];
        if (!(candidate.normal.dot(result.normal) > 1.0 - 1e-9)) continue;  // another plane
        const SubSimplex c = closest_on_face(ws, candidate);
        if (c.distance_squared < sub.distance_squared) {
          sub = c;
          face = candidate;
        }
      }
    }
    out.depth = std::max(0.0, face.offset);
    out.normal = face.normal;
    // Witnesses: the weights of the foot of the perpendicular, offset * normal, in the face's
    // triangle (extrapolated by rounding when the foot lies just outside it), so that
    // point_a - point_b = depth * normal by construction.
    double lambda[3];
    epa_internal::plane_weights(ws.vertices[face.vertex[0]].w, ws.vertices[face.vertex[1]].w,
                                ws.vertices[face.vertex[2]].w, face.normal,
                                face.offset * face.normal, lambda);
    out.point_a.setZero();
    out.point_b.setZero();
    for (int i = 0; i < 3; ++i) {
      const SimplexVertex& v = ws.vertices[face.vertex[i]];
      out.point_a += lambda[i] * v.a;
      out.point_b += lambda[i] * v.b;
    }
  }
  return out;
}

}  // namespace hullcheck::detail
