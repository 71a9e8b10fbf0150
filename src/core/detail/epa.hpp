// EPA (Expanding Polytope Algorithm; Casalino section 3 and algorithm 3): the point of the
// boundary of the core difference A - B nearest to the origin, when the origin is inside it.
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

#include "inline.hpp"
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
  std::array<std::uint64_t, kEpaMaxVertices> new_face_stamp{};  // epoch that set the entry
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

/// The polytope's counts; its vertices and faces live in the workspace.
struct Polytope {
  int vertex_count = 0;
  int face_count = 0;  ///< high-water mark of used face slots
  int free_count = 0;  ///< slots of removed faces, on ws.free_faces
};

/// The initial polytope: tetrahedron `s` (containing the origin), its four faces wound
/// counter-clockwise seen from outside, each with its neighbours across its edges. With the
/// vertices ordered so that vertex 3 lies below the plane of (0, 1, 2) (the signed volume
/// (v1 - v0) x (v2 - v0) . (v3 - v0) is <= 0, else 1 and 2 are swapped), the faces (0,1,2),
/// (0,3,1), (0,2,3), (1,3,2) all have the fourth vertex on their negative side: outward normals.
inline void init_tetrahedron(EpaWorkspace& ws, const Simplex& s, Polytope& p) {
  for (int i = 0; i < 4; ++i) {
    ws.vertices[i] = s.vertex(i);
    ws.core_index[i] = {s.index_a[i], s.index_b[i]};
  }
  const Eigen::Vector3d& p0 = ws.vertices[0].w;
  const double volume =
      (ws.vertices[1].w - p0).cross(ws.vertices[2].w - p0).dot(ws.vertices[3].w - p0);
  if (volume > 0.0) {
    std::swap(ws.vertices[1], ws.vertices[2]);
    std::swap(ws.core_index[1], ws.core_index[2]);
  }
  static constexpr int kTetFaces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  // Face across edge i (vertex[i], vertex[i+1]) of each face, and that edge's index there.
  static constexpr int kTetNeighbor[4][3] = {{1, 3, 2}, {2, 3, 0}, {0, 3, 1}, {1, 2, 0}};
  static constexpr int kTetNeighborEdge[4][3] = {{2, 2, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 1}};
  for (int f = 0; f < 4; ++f) {
    EpaFace& face = ws.faces[f];
    for (int i = 0; i < 3; ++i) face.vertex[i] = kTetFaces[f][i];
    face.alive = true;
    set_plane(ws, face);
    ws.key[f] = face.offset;
  }
  for (int f = 0; f < 4; ++f) {
    for (int i = 0; i < 3; ++i) {
      ws.faces[f].neighbor[i] = kTetNeighbor[f][i];
      ws.faces[f].neighbor_edge[i] = kTetNeighborEdge[f][i];
    }
  }
  p.vertex_count = 4;
  p.face_count = 4;
  p.free_count = 0;
}

/// Whether a face sees `point`: the point is more than `epsilon` above its plane (a degenerate
/// face, whose plane is meaningless, counts as seeing every point: it is removed).
HULLCHECK_ALWAYS_INLINE bool sees(const EpaFace& face, const Eigen::Vector3d& point,
                                  double epsilon) {
  return face.degenerate || face.normal.dot(point) - face.offset > epsilon;
}

/// Removes every face that sees `point`, by a walk across edges from face `seen` (which sees
/// it), and records the horizon in ws.horizon: each (kept face, edge) across which the walk met
/// a face that does not see the point. The visible faces of a convex polytope form a connected
/// cap, so the walk finds them all; visibility depends only on the face and the point, so a face
/// recorded as kept is never removed later: every recorded edge borders the cap, i.e. is a
/// horizon (silhouette) edge, seen from the kept side. Removed slots go to ws.free_faces.
/// Returns the number of horizon edges, or -1 when the record overflows (not on a consistent
/// polytope).
HULLCHECK_ALWAYS_INLINE int carve_visible_faces(EpaWorkspace& ws, int seen,
                                                const Eigen::Vector3d& point, double epsilon,
                                                Polytope& p) {
  int horizon_count = 0;
  int stack_size = 0;
  ws.faces[seen].alive = false;
  ws.key[seen] = INFINITY;
  ws.stack[stack_size++] = seen;
  while (stack_size > 0) {
    const int f = ws.stack[--stack_size];
    ws.free_faces[p.free_count++] = f;  // removed: its slot is free once the walk is done
    for (int i = 0; i < 3; ++i) {
      const int g = ws.faces[f].neighbor[i];
      EpaFace& neighbor = ws.faces[g];
      if (!neighbor.alive) continue;
      if (sees(neighbor, point, epsilon)) {
        neighbor.alive = false;
        ws.key[g] = INFINITY;
        ws.stack[stack_size++] = g;
      } else if (horizon_count < kEpaMaxFaces) {
        ws.horizon[horizon_count++] = {g, ws.faces[f].neighbor_edge[i]};
      } else {
        return -1;
      }
    }
  }
  return horizon_count;
}

/// The cone of new faces joining vertex `apex` to the horizon: for each horizon edge (a, b) of
/// a kept face (counter-clockwise there), the new face (b, a, apex) runs the edge the other way,
/// as the removed face across it did, so it is wound counter-clockwise from outside too; its
/// edge 0 (b, a) is glued to the kept face. ws.horizon[h][0] becomes the new face, and
/// ws.new_face_of_vertex[b] the new face whose edge 2 is (apex, b). Returns false when a vertex
/// starts two horizon edges or none (the horizon is not one simple loop).
HULLCHECK_ALWAYS_INLINE bool build_cone(EpaWorkspace& ws, int horizon_count, int apex,
                                        Polytope& p) {
  bool simple = true;
  const std::uint64_t epoch = ++ws.epoch;
  for (int h = 0; h < horizon_count; ++h) {
    const int g = ws.horizon[h][0];
    const int e = ws.horizon[h][1];
    const int a = ws.faces[g].vertex[e];
    const int b = ws.faces[g].vertex[(e + 1) % 3];
    const int f = p.free_count > 0 ? ws.free_faces[--p.free_count] : p.face_count++;
    EpaFace& face = ws.faces[f];
    face.vertex[0] = b;
    face.vertex[1] = a;
    face.vertex[2] = apex;
    face.alive = true;
    face.neighbor[0] = g;
    face.neighbor_edge[0] = e;
    ws.faces[g].neighbor[e] = f;
    ws.faces[g].neighbor_edge[e] = 0;
    set_plane(ws, face);
    ws.key[f] = face.offset;
    if (ws.new_face_stamp[b] == epoch) simple = false;  // b starts two horizon edges
    ws.new_face_of_vertex[b] = f;
    ws.new_face_stamp[b] = epoch;
    ws.horizon[h][0] = f;
  }
  // Each edge's end a must start another edge: then every vertex of the loop has one in- and
  // one out-edge.
  for (int h = 0; h < horizon_count && simple; ++h) {
    simple = ws.new_face_stamp[ws.faces[ws.horizon[h][0]].vertex[1]] == epoch;
  }
  return simple;
}

/// Glues the cone's faces to each other: edge 1 (a, apex) of the face on horizon edge (a, b)
/// meets edge 2 (apex, a) of the face on the horizon edge that ends at a.
HULLCHECK_ALWAYS_INLINE void link_cone(EpaWorkspace& ws, int horizon_count) {
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

/// Adds vertex `apex` (a support point above face `seen`) to the polytope (Casalino figure
/// 12): the faces that see it are replaced by the cone joining it to their horizon. A closed
/// triangulated polytope's horizon is a loop of at least 3 edges; anything else, or a cone that
/// does not fit in the workspace, is reported as false (numerical degeneracy).
HULLCHECK_ALWAYS_INLINE bool expand(EpaWorkspace& ws, int seen, int apex, double epsilon,
                                    Polytope& p) {
  const int horizon_count = carve_visible_faces(ws, seen, ws.vertices[apex].w, epsilon, p);
  if (horizon_count < 3 || p.face_count + horizon_count > kEpaMaxFaces) return false;
  if (!build_cone(ws, horizon_count, apex, p)) return false;
  link_cone(ws, horizon_count);
  return true;
}

/// How the support point along the closest face's normal ends EPA (Casalino algorithm 3: "if
/// P_D* is in Plex"). Every point of the difference lies below the support plane
/// n.x = support_offset, so the depth (the distance of the nearest boundary point) is at most
/// support_offset, and at least the face's offset (the face is inside the difference):
/// kConverged when the two are within the tolerance, kBelowStopDepth when the upper bound is
/// already below the caller's stop depth, else kExpand.
enum class EpaStep { kExpand, kConverged, kBelowStopDepth };
HULLCHECK_ALWAYS_INLINE EpaStep support_plane_test(double support_offset, double face_offset,
                                                   double tolerance, double stop_depth) {
  if (support_offset - face_offset <= tolerance) return EpaStep::kConverged;
  if (support_offset < stop_depth) return EpaStep::kBelowStopDepth;
  return EpaStep::kExpand;
}

/// Depth, normal and witnesses from the closest face `closest` (Casalino eq. 34-35). Several
/// faces can share the nearest plane (coplanar triangles of one polytope face); when converged,
/// take the one whose triangle holds the origin's projection, i.e. whose closest point to the
/// origin is nearest. Only faces of that plane qualify: a face of another plane at the same
/// distance (symmetric differences, e.g. identical shapes) has another normal, and its
/// witnesses would contradict the one reported. The witnesses are the weights of the foot of
/// the perpendicular, offset * normal, in the face's triangle (extrapolated by rounding when the
/// foot lies just outside it), so point_a - point_b = depth * normal by construction.
inline void face_witnesses(const EpaWorkspace& ws, const EpaFace& closest, int face_count,
                           double tolerance, EpaOutput& out) {
  EpaFace face = closest;
  SubSimplex sub = closest_on_face(ws, face);
  if (out.status == Status::kConverged && sub.size < 3) {  // projection outside the face
    for (int f = 0; f < face_count; ++f) {
      if (!(ws.key[f] <= closest.offset + tolerance)) continue;  // removed, degenerate or far
      const EpaFace& candidate = ws.faces[f];
      if (!(candidate.normal.dot(closest.normal) > 1.0 - 1e-9)) continue;  // another plane
      const SubSimplex c = closest_on_face(ws, candidate);
      if (c.distance_squared < sub.distance_squared) {
        sub = c;
        face = candidate;
      }
    }
  }
  out.depth = std::max(0.0, face.offset);
  out.normal = face.normal;
  double lambda[3];
  plane_weights(ws.vertices[face.vertex[0]].w, ws.vertices[face.vertex[1]].w,
                ws.vertices[face.vertex[2]].w, face.normal, face.offset * face.normal, lambda);
  out.point_a.setZero();
  out.point_b.setZero();
  for (int i = 0; i < 3; ++i) {
    const SimplexVertex& v = ws.vertices[face.vertex[i]];
    out.point_a += lambda[i] * v.a;
    out.point_b += lambda[i] * v.b;
  }
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

/// EPA from a tetrahedron `s` that contains the origin (on its boundary at worst); Casalino,
/// algorithm 3: repeatedly the face nearest the origin, the support point along its normal, and
/// either a proof that the face is the boundary's nearest (to `tolerance`, absolute) or the
/// polytope grown by that point.
/// `stop_depth`: when the depth is proven below it (a support plane closer than it), EPA stops
/// with status kAboveCutoff and `depth` = that upper bound of the depth (no witnesses); the
/// default, -infinity, never stops.
template <class MD>
EpaOutput epa(MD& md, const Simplex& s, double tolerance, int max_iterations, EpaWorkspace& ws,
              double stop_depth = -INFINITY) {
  using namespace epa_internal;
  EpaOutput out;
  // A point is above a face when it is more than this above its plane (rounding noise of the
  // coordinates is ~1e-16 x scale; tolerance is ~1e-10 x scale).
  const double visibility_epsilon = 1e-4 * tolerance;
  Polytope p;
  init_tetrahedron(ws, s, p);
  int best = -1;
  EpaFace result{};  // copy of the closest face: its slot may be reused by the expansion
  for (int iteration = 1;; ++iteration) {
    out.iterations = iteration;
    best = closest_face(ws.key.data(), p.face_count);
    if (best < 0) {  // every face degenerate: cannot happen for a proper tetrahedron
      out.status = Status::kDegenerate;
      break;
    }
    result = ws.faces[best];
    if (iteration > max_iterations || p.vertex_count == kEpaMaxVertices) {
      out.status = Status::kIterationCap;
      break;
    }
    SimplexVertex& w = ws.vertices[p.vertex_count];
    // The support climbs start at the face's newest vertex (its last; the expansion puts the
    // new support point there): a support point of a nearby direction.
    const std::array<int, 2>& hint = ws.core_index[result.vertex[2]];
    md.support(result.normal, w.w, w.a, w.b, hint[0], hint[1]);
    ws.core_index[p.vertex_count] = {md.index_a, md.index_b};
    const double support_offset = result.normal.dot(w.w);
    const EpaStep step = support_plane_test(support_offset, result.offset, tolerance, stop_depth);
    if (step == EpaStep::kConverged) break;
    if (step == EpaStep::kBelowStopDepth) {  // every point of the boundary is within that plane
      out.status = Status::kAboveCutoff;
      out.depth = support_offset;
      return out;
    }
    if (!expand(ws, best, p.vertex_count++, visibility_epsilon, p)) {
      out.status = Status::kDegenerate;
      break;
    }
  }
  if (best >= 0) face_witnesses(ws, result, p.face_count, tolerance, out);
  return out;
}

}  // namespace hullcheck::detail
