// Independent reference answers for tests and benchmarks (see oracles.hpp).
//
// Nothing here uses hullcheck: hull faces come from qhull (reentrant C API), distances from an
// exhaustive search over feature pairs, penetration from the qhull hull of the Minkowski
// difference. Lower-dimensional point sets (polygons, segments, points) are detected here and
// handled without qhull.
#include "oracles.hpp"

#include <libqhull_r/qhull_ra.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "rng.hpp"

namespace hullcheck::oracle {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

/// A point set thinner than this (relative to its size) around a lower-dimensional affine hull
/// is treated as lying on it.
constexpr double kFlatRelative = 1e-12;
/// Rounding noise of world coordinates, relative to their magnitude.
constexpr double kNoiseRelative = 1e-15;
/// Tolerance of the closed-set tests (containment, crossing), relative to the world scale.
constexpr double kContactRelative = 1e-13;

// ------------------------------------------------------------------------------------------
// qhull (3D) wrapper

struct QhullFacet {
  Vec3 normal;             // unit, outward
  std::array<int, 3> v{};  // point indices, counter-clockwise seen from outside
};

struct QhullOutput {
  std::vector<int> vertices;
  std::vector<QhullFacet> facets;
  std::string error;
};

/// Runs qhull on 3D points with `options` (must start with "qhull"). False on any qhull error
/// (flat input, precision) or a non-simplicial facet; the error text goes to out->error.
bool run_qhull3(const std::vector<Vec3>& pts, const char* options, QhullOutput* out) {
  out->vertices.clear();
  out->facets.clear();
  std::vector<coordT> coords(3 * pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    for (int k = 0; k < 3; ++k) coords[3 * i + static_cast<std::size_t>(k)] = pts[i][k];
  }
  char* err_buffer = nullptr;
  std::size_t err_size = 0;
  FILE* errfile = open_memstream(&err_buffer, &err_size);
  std::string command = options;  // qhull wants a mutable string

  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, errfile);
  const int exitcode = qh_new_qhull(qh, 3, static_cast<int>(pts.size()), coords.data(), 0,
                                    command.data(), nullptr, errfile);
  bool ok = exitcode == 0;
  if (ok) {
    for (vertexT* vertex = qh->vertex_list; vertex && vertex->next; vertex = vertex->next) {
      out->vertices.push_back(qh_pointid(qh, vertex->point));
    }
    for (facetT* facet = qh->facet_list; facet && facet->next; facet = facet->next) {
      setT* vertices = facet->vertices;
      if (qh_setsize(qh, vertices) != 3) {
        ok = false;
        break;
      }
      QhullFacet f;
      for (int k = 0; k < 3; ++k) {
        auto* vertex = static_cast<vertexT*>(vertices->e[k].p);
        f.v[static_cast<std::size_t>(k)] = qh_pointid(qh, vertex->point);
      }
      f.normal = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]).normalized();
      const Vec3& p0 = pts[static_cast<std::size_t>(f.v[0])];
      const Vec3& p1 = pts[static_cast<std::size_t>(f.v[1])];
      const Vec3& p2 = pts[static_cast<std::size_t>(f.v[2])];
      if ((p1 - p0).cross(p2 - p0).dot(f.normal) < 0) std::swap(f.v[1], f.v[2]);
      out->facets.push_back(f);
    }
  }
  qh_freeqhull(qh, 0);
  int curlong = 0;
  int totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  std::fclose(errfile);
  if (!ok && err_buffer != nullptr) out->error.assign(err_buffer, err_size);
  std::free(err_buffer);  // NOLINT(cppcoreguidelines-no-malloc): from open_memstream
  return ok && !out->facets.empty();
}

// ------------------------------------------------------------------------------------------
// Hull of a point set, of any affine dimension

struct Polytope {
  const std::vector<Vec3>* pts = nullptr;  // the input points (not owned)
  int dim = 0;
  Vec3 center{0, 0, 0};   // centroid of the points
  double size = 0.0;      // max |p - center|
  double flat_tol = 0.0;  // thickness below which the set counts as lower-dimensional
  std::vector<int> verts;
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 3>> tris;
  // dim 3: outward facet planes n.x <= h (h exact for the normal, from the vertices).
  std::vector<Vec3> plane_n;
  std::vector<double> plane_h;
  // dim 2: principal axes (e1, e2 in-plane, e3 = e1 x e2 the plane normal); the polygon
  // (verts) is counter-clockwise about e3. dim 1: e1 is the segment direction.
  Vec3 e1{1, 0, 0}, e2{0, 1, 0}, e3{0, 0, 1};

  const Vec3& p(int i) const { return (*pts)[static_cast<std::size_t>(i)]; }
};

double cross2(double ox, double oy, double ax, double ay, double bx, double by) {
  return (ax - ox) * (by - oy) - (ay - oy) * (bx - ox);
}

/// Andrew's monotone chain on 2D coordinates; returns counter-clockwise hull indices without
/// collinear points.
std::vector<int> convex_hull_2d(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<int> order(x.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  auto X = [&](int i) { return x[static_cast<std::size_t>(i)]; };
  auto Y = [&](int i) { return y[static_cast<std::size_t>(i)]; };
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return X(a) < X(b) || (X(a) == X(b) && Y(a) < Y(b)); });
  std::vector<int> hull(2 * order.size() + 1);
  std::size_t k = 0;
  for (int i : order) {  // lower chain
    while (k >= 2 && cross2(X(hull[k - 2]), Y(hull[k - 2]), X(hull[k - 1]), Y(hull[k - 1]), X(i),
                            Y(i)) <= 0) {
      --k;
    }
    hull[k++] = i;
  }
  const std::size_t lower = k + 1;
  for (auto it = order.rbegin() + 1; it != order.rend(); ++it) {  // upper chain
    const int i = *it;
    while (k >= lower && cross2(X(hull[k - 2]), Y(hull[k - 2]), X(hull[k - 1]), Y(hull[k - 1]),
                                X(i), Y(i)) <= 0) {
      --k;
    }
    hull[k++] = i;
  }
  hull.resize(k > 1 ? k - 1 : k);
  return hull;
}

void set_segment(Polytope* P) {
  const std::vector<Vec3>& pts = *P->pts;
  int lo = 0;
  int hi = 0;
  double tlo = kInf;
  double thi = -kInf;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double t = (pts[i] - P->center).dot(P->e1);
    if (t < tlo) {
      tlo = t;
      lo = static_cast<int>(i);
    }
    if (t > thi) {
      thi = t;
      hi = static_cast<int>(i);
    }
  }
  P->dim = 1;
  P->verts = {lo, hi};
  P->edges = {{lo, hi}};
  P->tris.clear();
}

void add_unique_edges(Polytope* P) {
  std::vector<std::array<int, 2>> edges;
  for (const auto& t : P->tris) {
    for (int k = 0; k < 3; ++k) {
      int a = t[static_cast<std::size_t>(k)];
      int b = t[static_cast<std::size_t>((k + 1) % 3)];
      if (a > b) std::swap(a, b);
      if (a != b) edges.push_back({a, b});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  P->edges = std::move(edges);
}

/// Polygon hull of a (nearly) coplanar set; false when it turns out collinear.
bool set_polygon(Polytope* P) {
  const std::vector<Vec3>& pts = *P->pts;
  std::vector<double> x(pts.size());
  std::vector<double> y(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    x[i] = (pts[i] - P->center).dot(P->e1);
    y[i] = (pts[i] - P->center).dot(P->e2);
  }
  std::vector<int> ring = convex_hull_2d(x, y);
  if (ring.size() < 3) return false;
  P->dim = 2;
  P->verts = ring;
  P->tris.clear();
  P->edges.clear();
  for (std::size_t i = 1; i + 1 < ring.size(); ++i)
    P->tris.push_back({ring[0], ring[i], ring[i + 1]});
  for (std::size_t i = 0; i < ring.size(); ++i) {
    int a = ring[i];
    int b = ring[(i + 1) % ring.size()];
    P->edges.push_back({std::min(a, b), std::max(a, b)});
  }
  return true;
}

bool set_polytope3(Polytope* P) {
  QhullOutput out;
  if (!run_qhull3(*P->pts, "qhull Qt", &out) && !run_qhull3(*P->pts, "qhull QJ", &out)) {
    return false;
  }
  P->dim = 3;
  P->verts = out.vertices;
  std::sort(P->verts.begin(), P->verts.end());
  P->tris.clear();
  P->plane_n.clear();
  P->plane_h.clear();
  for (const QhullFacet& f : out.facets) {
    P->tris.push_back(f.v);
    double h = -kInf;
    for (int i : P->verts) h = std::max(h, f.normal.dot(P->p(i)));
    P->plane_n.push_back(f.normal);
    P->plane_h.push_back(h);
  }
  add_unique_edges(P);
  return true;
}

Polytope build_polytope(const std::vector<Vec3>& pts) {
  if (pts.empty()) throw std::invalid_argument("oracle: empty point set");
  for (const Vec3& p : pts) {
    if (!p.allFinite()) throw std::invalid_argument("oracle: non-finite point");
  }
  Polytope P;
  P.pts = &pts;
  Vec3 sum(0, 0, 0);
  for (const Vec3& p : pts) sum += p;
  P.center = sum / static_cast<double>(pts.size());
  for (const Vec3& p : pts) P.size = std::max(P.size, (p - P.center).norm());
  const double noise = kNoiseRelative * (P.center.norm() + P.size);
  P.flat_tol = std::max(kFlatRelative * P.size, noise);
  if (P.size <= noise) {  // a single point (possibly repeated)
    P.dim = 0;
    P.verts = {0};
    return P;
  }
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : pts) cov += (p - P.center) * (p - P.center).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  P.e1 = eig.eigenvectors().col(2).normalized();
  P.e2 = eig.eigenvectors().col(1).normalized();
  P.e3 = P.e1.cross(P.e2).normalized();
  double line_thickness = 0.0;
  double plane_thickness = 0.0;
  for (const Vec3& p : pts) {
    const Vec3 r = p - P.center;
    line_thickness = std::max(line_thickness, (r - r.dot(P.e1) * P.e1).norm());
    plane_thickness = std::max(plane_thickness, std::abs(r.dot(P.e3)));
  }
  if (line_thickness <= P.flat_tol) {
    set_segment(&P);
    return P;
  }
  if (plane_thickness <= P.flat_tol || !set_polytope3(&P)) {
    if (!set_polygon(&P)) set_segment(&P);
  }
  return P;
}

// ------------------------------------------------------------------------------------------
// Closest points between primitives

Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0)) return a;
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

/// Ericson, Real-Time Collision Detection, 5.1.5 (with a fallback for degenerate triangles).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double denom = va + vb + vc;
  if (denom > 0 && std::isfinite(denom)) {
    const Vec3 q = a + ab * (vb / denom) + ac * (vc / denom);
    if (q.allFinite()) return q;
  }
  // Degenerate (zero-area) triangle: the nearest of its edges.
  Vec3 best = closest_on_segment(p, a, b);
  for (const Vec3& q : {closest_on_segment(p, b, c), closest_on_segment(p, c, a)}) {
    if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
  }
  return best;
}

struct PointPair {
  double d = kInf;
  Vec3 p{0, 0, 0}, q{0, 0, 0};
  void offer(const Vec3& a, const Vec3& b) {
    const double dist = (b - a).norm();
    if (dist < d) {
      d = dist;
      p = a;
      q = b;
    }
  }
};

/// Ericson 5.1.9, plus the endpoint cases when the segments are nearly parallel.
void closest_segments(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2,
                      PointPair* best) {
  const Vec3 d1 = q1 - p1;
  const Vec3 d2 = q2 - p2;
  const Vec3 r = p1 - p2;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  if (!(a > 0) || !(e > 0)) {
    best->offer(p1, closest_on_segment(p1, p2, q2));
    best->offer(closest_on_segment(p2, p1, q1), p2);
    return;
  }
  const double c = d1.dot(r);
  const double b = d1.dot(d2);
  const double denom = a * e - b * b;
  double s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  best->offer(p1 + s * d1, p2 + t * d2);
  if (denom <= 1e-8 * a * e) {  // nearly parallel: the formula above is ill-conditioned
    best->offer(p1, closest_on_segment(p1, p2, q2));
    best->offer(q1, closest_on_segment(q1, p2, q2));
    best->offer(closest_on_segment(p2, p1, q1), p2);
    best->offer(closest_on_segment(q2, p1, q1), q2);
  }
}

struct Sphere {
  Vec3 c;
  double r;
};

std::vector<Sphere> triangle_spheres(const Polytope& P) {
  std::vector<Sphere> s;
  s.reserve(P.tris.size());
  for (const auto& t : P.tris) {
    const Vec3 c = (P.p(t[0]) + P.p(t[1]) + P.p(t[2])) / 3.0;
    double r = 0;
    for (int i : t) r = std::max(r, (P.p(i) - c).norm());
    s.push_back({c, r * (1 + 1e-12)});
  }
  return s;
}

std::vector<Sphere> edge_spheres(const Polytope& P) {
  std::vector<Sphere> s;
  s.reserve(P.edges.size());
  for (const auto& e : P.edges) {
    const Vec3 c = 0.5 * (P.p(e[0]) + P.p(e[1]));
    s.push_back({c, 0.5 * (P.p(e[0]) - P.p(e[1])).norm() * (1 + 1e-12)});
  }
  return s;
}

/// Minimum over all feature pairs: vertex-vertex, vertex-edge, vertex-triangle (both ways) and
/// edge-edge. Bounding spheres skip pairs that cannot beat the current best (exact pruning).
PointPair feature_distance(const Polytope& A, const Polytope& B) {
  PointPair best;
  for (int i : A.verts) {
    for (int j : B.verts) best.offer(A.p(i), B.p(j));
  }
  const std::vector<Sphere> ta = triangle_spheres(A);
  const std::vector<Sphere> tb = triangle_spheres(B);
  const std::vector<Sphere> ea = edge_spheres(A);
  const std::vector<Sphere> eb = edge_spheres(B);
  // A's vertices against B's edges and triangles.
  for (int i : A.verts) {
    const Vec3& p = A.p(i);
    for (std::size_t k = 0; k < B.edges.size(); ++k) {
      if ((p - eb[k].c).norm() - eb[k].r > best.d) continue;
      best.offer(p, closest_on_segment(p, B.p(B.edges[k][0]), B.p(B.edges[k][1])));
    }
    for (std::size_t k = 0; k < B.tris.size(); ++k) {
      if ((p - tb[k].c).norm() - tb[k].r > best.d) continue;
      const auto& t = B.tris[k];
      best.offer(p, closest_on_triangle(p, B.p(t[0]), B.p(t[1]), B.p(t[2])));
    }
  }
  // B's vertices against A's edges and triangles.
  for (int j : B.verts) {
    const Vec3& q = B.p(j);
    for (std::size_t k = 0; k < A.edges.size(); ++k) {
      if ((q - ea[k].c).norm() - ea[k].r > best.d) continue;
      best.offer(closest_on_segment(q, A.p(A.edges[k][0]), A.p(A.edges[k][1])), q);
    }
    for (std::size_t k = 0; k < A.tris.size(); ++k) {
      if ((q - ta[k].c).norm() - ta[k].r > best.d) continue;
      const auto& t = A.tris[k];
      best.offer(closest_on_triangle(q, A.p(t[0]), A.p(t[1]), A.p(t[2])), q);
    }
  }
  // Edge pairs.
  for (std::size_t i = 0; i < A.edges.size(); ++i) {
    for (std::size_t j = 0; j < B.edges.size(); ++j) {
      if ((ea[i].c - eb[j].c).norm() - ea[i].r - eb[j].r > best.d) continue;
      closest_segments(A.p(A.edges[i][0]), A.p(A.edges[i][1]), B.p(B.edges[j][0]),
                       B.p(B.edges[j][1]), &best);
    }
  }
  return best;
}

// ------------------------------------------------------------------------------------------
// Closed-set tests (with a tolerance `eps`, absolute)

bool contains(const Polytope& P, const Vec3& x, double eps) {
  switch (P.dim) {
    case 0:
      return (x - P.p(P.verts[0])).norm() <= eps;
    case 1:
      return (x - closest_on_segment(x, P.p(P.verts[0]), P.p(P.verts[1]))).norm() <= eps;
    case 2: {
      if (std::abs((x - P.center).dot(P.e3)) > eps + P.flat_tol) return false;
      const std::size_t n = P.verts.size();
      for (std::size_t i = 0; i < n; ++i) {
        const Vec3& a = P.p(P.verts[i]);
        const Vec3& b = P.p(P.verts[(i + 1) % n]);
        const Vec3 out = (b - a).cross(P.e3);
        const double len = out.norm();
        if (len > 0 && (x - a).dot(out) / len > eps) return false;
      }
      return true;
    }
    default:
      for (std::size_t k = 0; k < P.plane_n.size(); ++k) {
        if (P.plane_n[k].dot(x) - P.plane_h[k] > eps) return false;
      }
      return true;
  }
}

/// Whether segment pq meets triangle abc at a point where it crosses the triangle's plane
/// (coplanar contact is left to the other tests). `hit` receives the crossing point.
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                              const Vec3& c, double eps, Vec3* hit) {
  Vec3 n = (b - a).cross(c - a);
  const double len = n.norm();
  if (!(len > 0)) return false;
  n /= len;
  const double sp = n.dot(p - a);
  const double sq = n.dot(q - a);
  if ((sp > eps && sq > eps) || (sp < -eps && sq < -eps)) return false;
  if (std::abs(sp - sq) <= eps) return false;  // (nearly) parallel to the plane
  const Vec3 x = p + (sp / (sp - sq)) * (q - p);
  const std::array<const Vec3*, 3> v = {&a, &b, &c};
  for (std::size_t k = 0; k < 3; ++k) {
    const Vec3& u = *v[k];
    const Vec3& w = *v[(k + 1) % 3];
    const Vec3 out = (w - u).cross(n);
    const double l = out.norm();
    if (l > 0 && (x - u).dot(out) / l > eps) return false;
  }
  *hit = x;
  return true;
}

/// Exhaustive overlap test of closed hulls: an extreme point of A n B is a vertex of one inside
/// the other, or an edge of one crossing a face of the other. Returns a common point in `hit`.
bool hulls_meet(const Polytope& A, const Polytope& B, double eps, Vec3* hit) {
  for (int i : A.verts) {
    if (contains(B, A.p(i), eps)) {
      *hit = A.p(i);
      return true;
    }
  }
  for (int j : B.verts) {
    if (contains(A, B.p(j), eps)) {
      *hit = B.p(j);
      return true;
    }
  }
  auto edges_vs_tris = [&](const Polytope& E, const Polytope& T) {
    const std::vector<Sphere> es = edge_spheres(E);
    const std::vector<Sphere> ts = triangle_spheres(T);
    for (std::size_t i = 0; i < E.edges.size(); ++i) {
      for (std::size_t k = 0; k < T.tris.size(); ++k) {
        if ((es[i].c - ts[k].c).norm() - es[i].r - ts[k].r > eps) continue;
        const auto& t = T.tris[k];
        if (segment_crosses_triangle(E.p(E.edges[i][0]), E.p(E.edges[i][1]), T.p(t[0]), T.p(t[1]),
                                     T.p(t[2]), eps, hit)) {
          return true;
        }
      }
    }
    return false;
  };
  return edges_vs_tris(A, B) || edges_vs_tris(B, A);
}

double world_scale(const Polytope& A, const Polytope& B) {
  return std::max(A.center.norm() + A.size, B.center.norm() + B.size);
}

// ------------------------------------------------------------------------------------------
// Minkowski difference

/// max over A of n.a - min over B of n.b: the support value of A - B in direction n.
double support_difference(const Polytope& A, const Polytope& B, const Vec3& n) {
  double ha = -kInf;
  for (int i : A.verts) ha = std::max(ha, n.dot(A.p(i)));
  double lb = kInf;
  for (int j : B.verts) lb = std::min(lb, n.dot(B.p(j)));
  return ha - lb;
}

/// Facet planes n.x <= h of A - B (h recomputed exactly from A and B for qhull's normal).
/// Empty when the difference is not full-dimensional.
struct MinkowskiHull {
  std::vector<Vec3> points;
  Polytope hull;
  std::vector<Vec3> n;
  std::vector<double> h;
};

void build_minkowski(const Polytope& A, const Polytope& B, MinkowskiHull* M) {
  M->points.clear();
  M->points.reserve(A.verts.size() * B.verts.size());
  for (int i : A.verts) {
    for (int j : B.verts) M->points.push_back(A.p(i) - B.p(j));
  }
  M->hull = build_polytope(M->points);
  M->n.clear();
  M->h.clear();
  if (M->hull.dim < 3) return;
  for (std::size_t k = 0; k < M->hull.plane_n.size(); ++k) {
    M->n.push_back(M->hull.plane_n[k]);
    M->h.push_back(support_difference(A, B, M->hull.plane_n[k]));
  }
}

// ------------------------------------------------------------------------------------------
// Random numbers, identical on every platform (no std distributions)

}  // namespace

// ------------------------------------------------------------------------------------------
// Public API

Distance brute_force_distance(const std::vector<Eigen::Vector3d>& world_a,
                              const std::vector<Eigen::Vector3d>& world_b) {
  const Polytope A = build_polytope(world_a);
  const Polytope B = build_polytope(world_b);
  const double eps = kContactRelative * world_scale(A, B);
  Distance result;
  const PointPair best = feature_distance(A, B);
  Vec3 hit;
  if (best.d <= eps) {  // touching (or overlapping): distance 0 either way
    result.overlapping = true;
    result.point_a = best.p;
    result.point_b = best.q;
  } else if (hulls_meet(A, B, eps, &hit)) {
    result.overlapping = true;
    result.point_a = hit;
    result.point_b = hit;
  } else {
    result.distance = best.d;
    result.point_a = best.p;
    result.point_b = best.q;
  }
  return result;
}

Penetration minkowski_penetration(const std::vector<Eigen::Vector3d>& world_a,
                                  const std::vector<Eigen::Vector3d>& world_b) {
  const Polytope A = build_polytope(world_a);
  const Polytope B = build_polytope(world_b);
  MinkowskiHull M;
  build_minkowski(A, B, &M);
  Penetration result;
  if (M.hull.dim < 3) {
    // Flat difference: no translation of positive length is needed, the depth is 0. The
    // origin may still lie in it (touching); report that as overlapping.
    const double eps = kContactRelative * world_scale(A, B);
    result.overlapping = contains(M.hull, Vec3::Zero(), eps);
    if (result.overlapping) {
      Vec3 n = M.hull.dim == 2 ? M.hull.e3 : M.hull.e1.unitOrthogonal();
      result.normal = n.normalized();
    }
    return result;
  }
  std::size_t best = 0;
  for (std::size_t k = 1; k < M.h.size(); ++k) {
    if (M.h[k] < M.h[best]) best = k;
  }
  double depth = M.h[best];
  Vec3 normal = M.n[best];
  // Every unit n gives an upper bound support(n) >= depth when the origin is inside, so
  // refining the normals of the near-best facets from their exact vertices can only help.
  const double slack = 1e-9 * (A.size + B.size) + std::abs(depth) * 1e-9;
  for (std::size_t k = 0; k < M.h.size(); ++k) {
    if (M.h[k] > M.h[best] + slack) continue;
    const auto& t = M.hull.tris[k];
    Vec3 n = (M.hull.p(t[1]) - M.hull.p(t[0])).cross(M.hull.p(t[2]) - M.hull.p(t[0]));
    if (!(n.norm() > 0)) continue;
    n.normalize();
    if (n.dot(M.n[k]) < 0.99) continue;
    const double h = support_difference(A, B, n);
    if (h < depth) {
      depth = h;
      normal = n;
    }
  }
  if (depth > 0) {
    result.overlapping = true;
    result.depth = depth;
    result.normal = normal;
  }
  return result;
}

Interval overlap_interval(const std::vector<Eigen::Vector3d>& world_a,
                          const std::vector<Eigen::Vector3d>& world_b,
                          const Eigen::Vector3d& direction) {
  const Polytope A = build_polytope(world_a);
  const Polytope B = build_polytope(world_b);
  MinkowskiHull M;
  build_minkowski(A, B, &M);
  Interval result;
  if (M.hull.dim < 3) return result;
  result.lo = -kInf;
  result.hi = kInf;
  // B + t d overlaps A  <=>  t d in the interior of A - B  <=>  n_k . d t < h_k for all k.
  for (std::size_t k = 0; k < M.n.size(); ++k) {
    const double nd = M.n[k].dot(direction);
    if (nd > 0) {
      result.hi = std::min(result.hi, M.h[k] / nd);
    } else if (nd < 0) {
      result.lo = std::max(result.lo, M.h[k] / nd);
    } else if (M.h[k] <= 0) {
      return Interval{};
    }
  }
  if (!(result.lo < result.hi)) return Interval{};
  return result;
}

std::vector<Eigen::Vector3d> transformed(const std::vector<Eigen::Vector3d>& local,
                                         const Eigen::Isometry3d& pose) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(local.size());
  for (const Eigen::Vector3d& p : local) out.push_back(pose * p);
  return out;
}

std::vector<Eigen::Vector3d> random_hull_points(std::uint64_t seed, int n, double size) {
  std::vector<Eigen::Vector3d> pts;
  if (n <= 0) return pts;
  Rng rng(seed);
  const Vec3 axes(size * rng.uniform(0.5, 1.0), size * rng.uniform(0.5, 1.0),
                  size * rng.uniform(0.5, 1.0));
  const Eigen::Quaterniond lattice = rng.quaternion();
  const Eigen::Quaterniond orientation = rng.quaternion();
  // Fibonacci lattice on the unit sphere (evenly spread, so all points are clearly vertices),
  // jittered, then stretched onto the ellipsoid: every point is a hull vertex.
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const double spacing = std::sqrt(4.0 * kPi / n);
  pts.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
    d += 0.15 * spacing * rng.uniform() * rng.unit_vector();
    d.normalize();
    pts.push_back(orientation * axes.cwiseProduct(lattice * d));
  }
  return pts;
}

std::vector<HullPair> make_hull_pairs(std::uint64_t seed, int count, int vertices,
                                      double overlap_fraction, double size) {
  std::vector<HullPair> pairs;
  if (count <= 0) return pairs;
  Rng rng(seed);
  // Exactly round(fraction * count) overlapping pairs, in a shuffled order.
  const double fraction = std::clamp(overlap_fraction, 0.0, 1.0);
  const auto n_overlap = static_cast<std::size_t>(std::llround(fraction * count));
  std::vector<char> overlap(static_cast<std::size_t>(count), 0);
  std::fill(overlap.begin(), overlap.begin() + static_cast<std::ptrdiff_t>(n_overlap), 1);
  for (std::size_t i = overlap.size(); i > 1; --i) {
    std::swap(overlap[i - 1], overlap[static_cast<std::size_t>(rng.bits() % i)]);
  }
  pairs.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    HullPair pair;
    pair.a = random_hull_points(rng.bits(), vertices, size);
    pair.b = random_hull_points(rng.bits(), vertices, size);
    pair.pose_a.linear() = rng.quaternion().toRotationMatrix();
    pair.pose_a.translation() =
        size * Vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    const std::vector<Vec3> world_a = transformed(pair.a, pair.pose_a);
    const bool want_overlap = overlap[static_cast<std::size_t>(i)] != 0;
    // B starts on A's centre with a random orientation, then moves along a random line to a
    // place inside (overlap) or beyond (separation) the interval where the two overlap.
    for (int attempt = 0;; ++attempt) {
      Eigen::Isometry3d pose_b = Eigen::Isometry3d::Identity();
      pose_b.linear() = rng.quaternion().toRotationMatrix();
      pose_b.translation() = pair.pose_a.translation();
      const Vec3 u = rng.unit_vector();
      const Interval range = overlap_interval(world_a, transformed(pair.b, pose_b), u);
      const double lo_frac = rng.uniform(0.1, 0.9);
      const double gap = size * rng.uniform(0.02, 1.0);
      const bool forward = (rng.bits() & 1U) != 0;
      if (range.empty() || !std::isfinite(range.lo) || !std::isfinite(range.hi)) {
        if (attempt < 100) continue;  // degenerate hulls (vertices < 4): just move apart
        pose_b.translation() += u * (4.0 * size + gap);
      } else if (want_overlap) {
        pose_b.translation() += u * (range.lo + lo_frac * (range.hi - range.lo));
      } else {
        pose_b.translation() += u * (forward ? range.hi + gap : range.lo - gap);
      }
      pair.pose_b = pose_b;
      break;
    }
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (closest_on_triangle(p, a, b, c) - p).norm();
}

HullDistance::HullDistance(const std::vector<Eigen::Vector3d>& points) : points_(points) {
  const Polytope P = build_polytope(points_);
  dim_ = P.dim;
  eps_ = 1e-12 * (P.center.norm() + P.size);
  if (dim_ == 3) {
    tris_ = P.tris;
    plane_n_ = P.plane_n;
    plane_h_ = P.plane_h;
  }
}

double HullDistance::operator()(const Eigen::Vector3d& p) const {
  if (dim_ < 3) return brute_force_distance({p}, points_).distance;
  bool inside = true;
  for (std::size_t f = 0; f < plane_n_.size() && inside; ++f) {
    inside = plane_n_[f].dot(p) <= plane_h_[f] + eps_;
  }
  if (inside) return 0.0;
  double best = kInf;
  for (const auto& t : tris_) {
    best = std::min(best, point_triangle_distance(p, points_[static_cast<std::size_t>(t[0])],
                                                  points_[static_cast<std::size_t>(t[1])],
                                                  points_[static_cast<std::size_t>(t[2])]));
  }
  return best;
}

}  // namespace hullcheck::oracle
