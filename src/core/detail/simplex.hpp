// The GJK simplex ("plex" in Casalino §2) and its closest point to the origin.
//
// Casalino's update cases a (segment), b (triangle) and c (tetrahedron) are implemented with
// signed volumes (sub-determinants of the projected simplex), which decide the closest region
// by signs of quantities computed directly from the vertices, instead of by differences of
// squared distances. This keeps the region choice consistent on near-degenerate simplices
// (slivers, needles), where the classic formulas lose all significant digits. Every region
// whose sign test fails is evaluated, so the answer does not depend on the temporal-order
// assumption of Casalino §2 (which rounding can violate).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace hullcheck::detail {

/// One simplex vertex: w = a - b, with the shapes' support points a and b (A's frame).
/// Also the vertex type of the boolean GJK when EPA continues from its tetrahedron.
struct SimplexVertex {
  Eigen::Vector3d w, a, b;
  void set(const Eigen::Vector3d& w_in, const Eigen::Vector3d& a_in, const Eigen::Vector3d& b_in) {
    w = w_in;
    a = a_in;
    b = b_in;
  }
};

/// Up to four vertices (structure of arrays, oldest first) with the barycentric weights of the
/// closest point to the origin.
struct Simplex {
  // Entries from `size` on are unset (no initialisation: this sits on every query's path).
  Eigen::Vector3d w[4], a[4], b[4];
  int index_a[4];  // vertex of core A behind a[i] (-1: a curved core)
  int index_b[4];
  double lambda[4];
  int size = 0;

  Eigen::Vector3d closest_point() const { return combine(w); }
  Eigen::Vector3d point_a() const { return combine(a); }
  Eigen::Vector3d point_b() const { return combine(b); }
  SimplexVertex vertex(int i) const { return {w[i], a[i], b[i]}; }
  void set_vertex(int i, const SimplexVertex& v) {
    w[i] = v.w;
    a[i] = v.a;
    b[i] = v.b;
  }

 private:
  Eigen::Vector3d combine(const Eigen::Vector3d* p) const {
    Eigen::Vector3d sum = lambda[0] * p[0];
    for (int i = 1; i < size; ++i) sum += lambda[i] * p[i];
    return sum;
  }
};

/// Closest point of a sub-simplex: which vertices (by index into the parent, ascending) and
/// weights.
struct SubSimplex {
  int index[4];
  double lambda[4];
  int size;
  double distance_squared;
};

inline bool same_sign(double a, double b) { return (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0); }

/// Case a: segment p[i0] p[i1].
inline SubSimplex closest_on_segment(const Eigen::Vector3d* p, int i0, int i1) {
  const Eigen::Vector3d& s0 = p[i0];
  const Eigen::Vector3d& s1 = p[i1];
  const Eigen::Vector3d t = s1 - s0;
  const double tt = t.squaredNorm();
  const double along = -s0.dot(t);
  SubSimplex r;
  if (along <= 0.0 || tt <= 0.0) {
    // Vertex region of s0, or a zero-length segment: the nearer end (s1 only by rounding).
    const bool second = s1.squaredNorm() < s0.squaredNorm();
    r.size = 1;
    r.index[0] = second ? i1 : i0;
    r.lambda[0] = 1.0;
    r.distance_squared = second ? s1.squaredNorm() : s0.squaredNorm();
    return r;
  }
  if (along >= tt) {
    r.size = 1;
    r.index[0] = i1;
    r.lambda[0] = 1.0;
    r.distance_squared = s1.squaredNorm();
    return r;
  }
  const double mu = along / tt;
  r.size = 2;
  r.index[0] = i0;
  r.index[1] = i1;
  r.lambda[0] = 1.0 - mu;
  r.lambda[1] = mu;
  r.distance_squared = ((1.0 - mu) * s0 + mu * s1).squaredNorm();
  return r;
}

/// Case b: triangle p[i0] p[i1] p[i2].
inline SubSimplex closest_on_triangle(const Eigen::Vector3d* p, int i0, int i1, int i2) {
  const Eigen::Vector3d& s0 = p[i0];
  const Eigen::Vector3d& s1 = p[i1];
  const Eigen::Vector3d& s2 = p[i2];
  const Eigen::Vector3d n = (s1 - s0).cross(s2 - s0);
  const double nn = n.squaredNorm();
  const int ids[3] = {i0, i1, i2};
  SubSimplex best;
  best.size = 0;
  best.distance_squared = INFINITY;
  auto consider_edges = [&](const bool* check) {
    static constexpr int kEdges[3][2] = {{1, 2}, {0, 2}, {0, 1}};  // opposite vertex j
    for (int j = 0; j < 3; ++j) {
      if (!check[j]) continue;
      const SubSimplex e = closest_on_segment(p, ids[kEdges[j][0]], ids[kEdges[j][1]]);
      if (e.distance_squared < best.distance_squared) best = e;
    }
  };
  const double scale2 = std::max({s0.squaredNorm(), s1.squaredNorm(), s2.squaredNorm(),
                                  (s1 - s0).squaredNorm(), (s2 - s0).squaredNorm()});
  if (!(nn > 1e-30 * scale2 * scale2)) {  // degenerate (collinear) triangle: its edges
    const bool all[3] = {true, true, true};
    consider_edges(all);
    return best;
  }
  // Projection of the origin on the plane, then 2D signed areas on the plane of the largest
  // normal component.
  const Eigen::Vector3d p0 = n * (s0.dot(n) / nn);
  int k = 0;
  if (std::abs(n.y()) > std::abs(n(k))) k = 1;
  if (std::abs(n.z()) > std::abs(n(k))) k = 2;
  const int x = (k + 1) % 3;
  const int y = (k + 2) % 3;
  auto area = [x, y](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return (b(x) - a(x)) * (c(y) - a(y)) - (b(y) - a(y)) * (c(x) - a(x));
  };
  const double mu = area(s0, s1, s2);
  const double c[3] = {area(p0, s1, s2), area(s0, p0, s2), area(s0, s1, p0)};
  const bool outside[3] = {!same_sign(mu, c[0]), !same_sign(mu, c[1]), !same_sign(mu, c[2])};
  if (!outside[0] && !outside[1] && !outside[2]) {
    best.size = 3;
    for (int j = 0; j < 3; ++j) {
      best.index[j] = ids[j];
      best.lambda[j] = c[j] / mu;
    }
    best.distance_squared =
        (best.lambda[0] * s0 + best.lambda[1] * s1 + best.lambda[2] * s2).squaredNorm();
    return best;
  }
  consider_edges(outside);
  return best;
}

/// Case c: tetrahedron p[0..3]. size 4 in the result means the origin is inside.
inline SubSimplex closest_on_tetrahedron(const Eigen::Vector3d* p) {
  const Eigen::Vector3d& s0 = p[0];
  const Eigen::Vector3d& s1 = p[1];
  const Eigen::Vector3d& s2 = p[2];
  const Eigen::Vector3d& s3 = p[3];
  // Signed volumes of the tetrahedra with the origin in place of vertex j (the barycentric
  // coordinates of the origin times the full volume, which is their sum):
  //   vol(O,s1,s2,s3) = s1.(s2 x s3),  vol(s0,O,s2,s3) = -s0.(s2 x s3),
  //   vol(s0,s1,O,s3) = s0.(s1 x s3),  vol(s0,s1,s2,O) = -s0.(s1 x s2).
  const Eigen::Vector3d s2xs3 = s2.cross(s3);
  const double cofactor[4] = {s1.dot(s2xs3), -s0.dot(s2xs3), s0.dot(s1.cross(s3)),
                              -s0.dot(s1.cross(s2))};
  const double det = cofactor[0] + cofactor[1] + cofactor[2] + cofactor[3];
  const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  // Each cofactor carries rounding of order eps |s|^3: a tetrahedron whose volume is within a
  // few thousand times that is flat as far as the signs tell (a flat one through the origin
  // has cofactors of pure noise, whose signs would pick a far region). It is then measured by
  // all four faces: exact when the origin is outside, and within its thickness (below
  // 1e-11 |s|, under every query tolerance) when inside.
  const double reach_squared = std::max(std::max(s0.squaredNorm(), s1.squaredNorm()),
                                        std::max(s2.squaredNorm(), s3.squaredNorm()));
  const bool flat = det * det <= 1e-22 * reach_squared * reach_squared * reach_squared;
  SubSimplex best;
  best.size = 0;
  best.distance_squared = INFINITY;
  bool inside = !flat;
  bool outside[4];
  for (int j = 0; j < 4; ++j) {
    outside[j] = !same_sign(det, cofactor[j]);
    inside = inside && !outside[j];
  }
  if (inside) {
    best.size = 4;
    for (int j = 0; j < 4; ++j) {
      best.index[j] = j;
      best.lambda[j] = cofactor[j] / det;
    }
    best.distance_squared = 0.0;
    return best;
  }
  for (int j = 0; j < 4; ++j) {
    if (!flat && !outside[j]) continue;
    const SubSimplex f = closest_on_triangle(p, faces[j][0], faces[j][1], faces[j][2]);
    if (f.distance_squared < best.distance_squared) best = f;
  }
  return best;
}

}  // namespace hullcheck::detail
