// EPA's parts on small hand-built polytopes (Casalino section 3 and algorithm 3): the initial
// tetrahedron, the choice of the face nearest the origin, the horizon of a new support point
// (one face, two faces, three faces seen), the cone that replaces the faces it sees, and whole
// EPA runs on a box. Expected values are derived here from the geometry, not from the engine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "detail/epa.hpp"

namespace hullcheck::detail {
namespace {

using epa_internal::Polytope;

// The regular tetrahedron with alternate corners of the cube [-1, 1]^3. Its centroid is the
// origin; the face opposite v_i has the outward unit normal -v_i / sqrt(3) and lies at distance
// 1 / sqrt(3) from the centroid (n . v_j = -(v_i . v_j) / sqrt(3) = 1 / sqrt(3) for j != i).
const Eigen::Vector3d kTet[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
const double kInvSqrt3 = 1.0 / std::sqrt(3.0);

/// A size-4 simplex with w = p_i + shift, a = w, b = 0 and no core vertex indices.
Simplex tetrahedron_simplex(const Eigen::Vector3d (&p)[4], const Eigen::Vector3d& shift) {
  Simplex s;
  s.size = 4;
  for (int i = 0; i < 4; ++i) {
    s.w[i] = s.a[i] = p[i] + shift;
    s.b[i] = Eigen::Vector3d::Zero();
    s.index_a[i] = s.index_b[i] = -1;
    s.lambda[i] = 0.25;
  }
  return s;
}

/// Live faces (alive, slots below the high-water mark).
std::vector<int> live_faces(const EpaWorkspace& ws, const Polytope& p) {
  std::vector<int> faces;
  for (int f = 0; f < p.face_count; ++f) {
    if (ws.faces[f].alive) faces.push_back(f);
  }
  return faces;
}

/// An undirected edge as the positions of its ends (ordered lexicographically).
using Edge = std::pair<std::vector<double>, std::vector<double>>;
Edge edge_of(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  std::vector<double> a{x.x(), x.y(), x.z()}, b{y.x(), y.y(), y.z()};
  return a < b ? Edge{a, b} : Edge{b, a};
}

/// Every live face's neighbour across edge i is live and runs that edge the other way, and
/// records this face across it; every live face's plane has all vertices of the live faces on
/// or below it (a convex polytope) and the origin strictly below (it contains the origin).
void expect_consistent_convex_polytope(const EpaWorkspace& ws, const Polytope& p) {
  const std::vector<int> faces = live_faces(ws, p);
  std::set<int> vertices;
  for (int f : faces) {
    for (int i = 0; i < 3; ++i) vertices.insert(ws.faces[f].vertex[i]);
  }
  // Euler: a closed triangulated sphere has V - E + F = 2 with E = 3F / 2.
  EXPECT_EQ(static_cast<int>(vertices.size()) - 3 * static_cast<int>(faces.size()) / 2 +
                static_cast<int>(faces.size()),
            2);
  for (int f : faces) {
    const EpaFace& face = ws.faces[f];
    for (int i = 0; i < 3; ++i) {
      const int g = face.neighbor[i];
      const int j = face.neighbor_edge[i];
      ASSERT_TRUE(ws.faces[g].alive) << f << " " << i;
      EXPECT_EQ(ws.faces[g].neighbor[j], f);
      EXPECT_EQ(ws.faces[g].neighbor_edge[j], i);
      EXPECT_EQ(ws.faces[g].vertex[j], face.vertex[(i + 1) % 3]);
      EXPECT_EQ(ws.faces[g].vertex[(j + 1) % 3], face.vertex[i]);
    }
    EXPECT_GT(face.offset, 0.0) << f;
    for (int v : vertices) EXPECT_LE(face.normal.dot(ws.vertices[v].w), face.offset + 1e-12);
  }
}

/// The undirected horizon edges recorded by carve_visible_faces, as positions.
std::set<Edge> horizon_edges(const EpaWorkspace& ws, int count) {
  std::set<Edge> edges;
  for (int h = 0; h < count; ++h) {
    const EpaFace& kept = ws.faces[ws.horizon[h][0]];
    const int e = ws.horizon[h][1];
    edges.insert(edge_of(ws.vertices[kept.vertex[e]].w, ws.vertices[kept.vertex[(e + 1) % 3]].w));
  }
  return edges;
}

/// Puts `point` in the workspace as the next vertex and returns its index.
int add_vertex(EpaWorkspace& ws, Polytope& p, const Eigen::Vector3d& point) {
  ws.vertices[p.vertex_count] = {point, point, Eigen::Vector3d::Zero()};
  ws.core_index[p.vertex_count] = {-1, -1};
  return p.vertex_count++;
}

/// The live face whose outward normal is `normal` (-1 if none).
int face_with_normal(const EpaWorkspace& ws, const Polytope& p, const Eigen::Vector3d& normal) {
  for (int f : live_faces(ws, p)) {
    if ((ws.faces[f].normal - normal).norm() < 1e-12) return f;
  }
  return -1;
}

TEST(EpaPolytope, InitialTetrahedronHasOutwardFacesAtTheirDistance) {
  // Both windings of the input: the vertex order must not matter.
  const Eigen::Vector3d swapped[4] = {kTet[0], kTet[2], kTet[1], kTet[3]};
  for (const auto* points : {&kTet, &swapped}) {
    auto workspace = std::make_unique<EpaWorkspace>();
    EpaWorkspace& ws = *workspace;
    Polytope p;
    epa_internal::init_tetrahedron(ws, tetrahedron_simplex(*points, Eigen::Vector3d::Zero()), p);
    EXPECT_EQ(p.vertex_count, 4);
    ASSERT_EQ(p.face_count, 4);
    for (int i = 0; i < 4; ++i) {  // the face opposite kTet[i]
      const int f = face_with_normal(ws, p, -kTet[i] * kInvSqrt3);
      ASSERT_GE(f, 0) << i;
      EXPECT_NEAR(ws.faces[f].offset, kInvSqrt3, 1e-15);
      EXPECT_EQ(ws.key[f], ws.faces[f].offset);
      EXPECT_FALSE(ws.faces[f].degenerate);
    }
    expect_consistent_convex_polytope(ws, p);
  }
}

TEST(EpaFaceSelection, ClosestFaceOfAnOffCentreTetrahedron) {
  // Shifted by c, the face opposite v_i lies at (1 - v_i . c) / sqrt(3) from the origin:
  // v . c = 0.6, -0.4, -0.2, 0 for c = (0.1, 0.2, 0.3), so the face opposite v_0 is nearest, at
  // 0.4 / sqrt(3).
  const Eigen::Vector3d c(0.1, 0.2, 0.3);
  auto workspace = std::make_unique<EpaWorkspace>();
  EpaWorkspace& ws = *workspace;
  Polytope p;
  epa_internal::init_tetrahedron(ws, tetrahedron_simplex(kTet, c), p);
  const int best = epa_internal::closest_face(ws.key.data(), p.face_count);
  ASSERT_GE(best, 0);
  EXPECT_LT((ws.faces[best].normal + kTet[0] * kInvSqrt3).norm(), 1e-12);
  EXPECT_NEAR(ws.faces[best].offset, 0.4 * kInvSqrt3, 1e-15);
}

TEST(EpaFaceSelection, FirstSmallestFiniteKey) {
  // Lengths around the four-key blocks of the vectorised scan; the minimum in the tail too.
  const double keys[] = {3.0, 1.5, INFINITY, 2.0, 1.5, 7.0, 0.25};
  EXPECT_EQ(epa_internal::closest_face(keys, 1), 0);
  EXPECT_EQ(epa_internal::closest_face(keys, 5), 1);  // the first of the two 1.5
  EXPECT_EQ(epa_internal::closest_face(keys, 7), 6);
  const double removed[] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY};
  EXPECT_EQ(epa_internal::closest_face(removed, 5), -1);
  const double with_nan[] = {NAN, 2.0, 1.0, NAN, 4.0};
  EXPECT_EQ(epa_internal::closest_face(with_nan, 5), 2);
}

TEST(EpaHorizon, PointSeenByOneFace) {
  // q = 1 x the unit normal of the face opposite v_3, n = (1, 1, -1) / sqrt(3). The face
  // opposite v_i sees q when -v_i . q / sqrt(3) > 1 / sqrt(3): -v_i . q = -1/sqrt(3) x
  // (1, 1, 1, -3) for i = 0..3, so only the face opposite v_3 does. The horizon is that face's
  // boundary: the triangle v_0 v_1 v_2.
  auto workspace = std::make_unique<EpaWorkspace>();
  EpaWorkspace& ws = *workspace;
  Polytope p;
  epa_internal::init_tetrahedron(ws, tetrahedron_simplex(kTet, Eigen::Vector3d::Zero()), p);
  const Eigen::Vector3d n = -kTet[3] * kInvSqrt3;
  const int seen = face_with_normal(ws, p, n);
  ASSERT_GE(seen, 0);
  const int apex = add_vertex(ws, p, n);
  const int count = epa_internal::carve_visible_faces(ws, seen, n, 1e-12, p);
  ASSERT_EQ(count, 3);
  EXPECT_EQ(horizon_edges(ws, count),
            (std::set<Edge>{edge_of(kTet[0], kTet[1]), edge_of(kTet[1], kTet[2]),
                            edge_of(kTet[0], kTet[2])}));
  EXPECT_EQ(live_faces(ws, p).size(), 3u);
  ASSERT_TRUE(epa_internal::build_cone(ws, count, apex, p));
  epa_internal::link_cone(ws, count);
  EXPECT_EQ(live_faces(ws, p).size(), 6u);  // 3 kept + one per horizon edge
  expect_consistent_convex_polytope(ws, p);
}

TEST(EpaHorizon, PointSeenByTwoFaces) {
  // q = (2, 0, 0), beyond the edge v_0 v_1 (midpoint (1, 0, 0)). -v_i . q = -2, -2, 2, 2: the
  // two faces through that edge (opposite v_2 and v_3) see q. The horizon is the boundary of
  // their union, the quadrilateral v_0 v_2 v_1 v_3 (the shared edge v_0 v_1 is not on it).
  auto workspace = std::make_unique<EpaWorkspace>();
  EpaWorkspace& ws = *workspace;
  Polytope p;
  epa_internal::init_tetrahedron(ws, tetrahedron_simplex(kTet, Eigen::Vector3d::Zero()), p);
  const Eigen::Vector3d q(2, 0, 0);
  const int seen = face_with_normal(ws, p, -kTet[2] * kInvSqrt3);
  ASSERT_GE(seen, 0);
  const int apex = add_vertex(ws, p, q);
  const int count = epa_internal::carve_visible_faces(ws, seen, q, 1e-12, p);
  ASSERT_EQ(count, 4);
  EXPECT_EQ(horizon_edges(ws, count),
            (std::set<Edge>{edge_of(kTet[0], kTet[2]), edge_of(kTet[2], kTet[1]),
                            edge_of(kTet[1], kTet[3]), edge_of(kTet[3], kTet[0])}));
  EXPECT_EQ(live_faces(ws, p).size(), 2u);
  ASSERT_TRUE(epa_internal::build_cone(ws, count, apex, p));
  epa_internal::link_cone(ws, count);
  EXPECT_EQ(live_faces(ws, p).size(), 6u);  // 2 kept + 4 new
  expect_consistent_convex_polytope(ws, p);
}

TEST(EpaHorizon, PointSeenByThreeFacesRemovesAVertex) {
  // q = 2 v_0 = (2, 2, 2): -v_i . q = -6, 2, 2, 2, so the three faces through v_0 see q; the
  // horizon is the face opposite v_0, the triangle v_1 v_2 v_3, and v_0 leaves the polytope,
  // which becomes the tetrahedron v_1 v_2 v_3 q.
  auto workspace = std::make_unique<EpaWorkspace>();
  EpaWorkspace& ws = *workspace;
  Polytope p;
  epa_internal::init_tetrahedron(ws, tetrahedron_simplex(kTet, Eigen::Vector3d::Zero()), p);
  const Eigen::Vector3d q = 2.0 * kTet[0];
  const int seen = face_with_normal(ws, p, -kTet[1] * kInvSqrt3);
  ASSERT_GE(seen, 0);
  const int apex = add_vertex(ws, p, q);
  const int count = epa_internal::carve_visible_faces(ws, seen, q, 1e-12, p);
  ASSERT_EQ(count, 3);
  EXPECT_EQ(horizon_edges(ws, count),
            (std::set<Edge>{edge_of(kTet[1], kTet[2]), edge_of(kTet[2], kTet[3]),
                            edge_of(kTet[1], kTet[3])}));
  ASSERT_TRUE(epa_internal::build_cone(ws, count, apex, p));
  epa_internal::link_cone(ws, count);
  const std::vector<int> faces = live_faces(ws, p);
  ASSERT_EQ(faces.size(), 4u);
  for (int f : faces) {
    for (int i = 0; i < 3; ++i) EXPECT_NE(ws.vertices[ws.faces[f].vertex[i]].w, kTet[0]);
  }
  expect_consistent_convex_polytope(ws, p);
}

TEST(EpaHorizon, PointBelowEveryFaceSeesNone) {
  // A point inside the tetrahedron (the origin) is below every face: the walk removes only the
  // face it starts from and records that face's three edges.
  auto workspace = std::make_unique<EpaWorkspace>();
  EpaWorkspace& ws = *workspace;
  Polytope p;
  epa_internal::init_tetrahedron(ws, tetrahedron_simplex(kTet, Eigen::Vector3d::Zero()), p);
  const int count = epa_internal::carve_visible_faces(ws, 0, Eigen::Vector3d::Zero(), 1e-12, p);
  EXPECT_EQ(count, 3);
  EXPECT_EQ(live_faces(ws, p).size(), 3u);
}

// A - B for the box core with half extents (1, 2, 3) and a point core placed at t: the box
// shifted by -t, [-1.2, 0.8] x [-2.1, 1.9] x [-3.3, 2.7] for t = (0.2, 0.1, 0.3). Its faces lie
// at 0.8, 1.2, 1.9, 2.1, 2.7, 3.3 from the origin: the depth is 0.8 along +x, with the point of
// A at t + 0.8 x = (1, 0.1, 0.3) and that of B at t.
struct BoxMinusPoint {
  BoxCore box{Eigen::Vector3d(1, 2, 3)};
  PointCore point;
  Eigen::Vector3d t{0.2, 0.1, 0.3};
  MinkowskiDifference<BoxCore, PointCore> md{box, point, Eigen::Matrix3d::Identity(), t};
  /// Alternate corners of the difference (the regular tetrahedron of the box's corners): in the
  /// box's coordinates scaled to [-1, 1]^3 the origin is (0.2, 0.05, 0.1), and v . (0.2, 0.05,
  /// 0.1) >= -1 for all four corners v of kTet, so the tetrahedron contains the origin.
  Simplex start() const {
    Simplex s;
    s.size = 4;
    for (int i = 0; i < 4; ++i) {
      s.a[i] = kTet[i].cwiseProduct(box.half);
      s.b[i] = t;
      s.w[i] = s.a[i] - s.b[i];
      s.index_a[i] = s.index_b[i] = -1;
      s.lambda[i] = 0.25;
    }
    return s;
  }
};

TEST(Epa, BoxDepthNormalAndWitnesses) {
  BoxMinusPoint pair;
  auto workspace = std::make_unique<EpaWorkspace>();
  EpaWorkspace& ws = *workspace;
  const EpaOutput out = epa(pair.md, pair.start(), 1e-12, 100, ws);
  EXPECT_EQ(out.status, Status::kConverged);
  EXPECT_NEAR(out.depth, 0.8, 1e-12);
  EXPECT_LT((out.normal - Eigen::Vector3d::UnitX()).norm(), 1e-12);
  EXPECT_LT((out.point_a - Eigen::Vector3d(1.0, 0.1, 0.3)).norm(), 1e-12);
  EXPECT_LT((out.point_b - pair.t).norm(), 1e-12);
}

TEST(Epa, StopDepthAboveTheDepthStopsEarly) {
  // Every support plane n . x = h bounds the depth from above (the nearest boundary point lies
  // below it), and h <= |(1.2, 2.1, 3.3)| < 4.1, the farthest corner of the difference. The
  // start's closest face cuts through the box (no tetrahedron face lies on a box face), so the
  // first support plane does not converge, and with the stop depth 10 EPA stops there: status
  // kAboveCutoff with that bound, in [0.8, 4.1].
  BoxMinusPoint pair;
  auto workspace = std::make_unique<EpaWorkspace>();
  const EpaOutput out = epa(pair.md, pair.start(), 1e-12, 100, *workspace, 10.0);
  EXPECT_EQ(out.status, Status::kAboveCutoff);
  EXPECT_EQ(out.iterations, 1);
  EXPECT_GE(out.depth, 0.8 - 1e-12);
  EXPECT_LE(out.depth, 4.1);
  // A stop depth below the depth never triggers: the full answer.
  const EpaOutput full = epa(pair.md, pair.start(), 1e-12, 100, *workspace, 0.5);
  EXPECT_EQ(full.status, Status::kConverged);
  EXPECT_NEAR(full.depth, 0.8, 1e-12);
}

TEST(Epa, IterationCapIsReported) {
  // One expansion is allowed, then the cap: the polytope (inside the difference) has not been
  // proven to reach the boundary. Its closest face is inside the box, so its offset is a lower
  // bound of the depth.
  BoxMinusPoint pair;
  auto workspace = std::make_unique<EpaWorkspace>();
  EpaWorkspace& ws = *workspace;
  const EpaOutput out = epa(pair.md, pair.start(), 1e-12, 1, ws);
  EXPECT_EQ(out.status, Status::kIterationCap);
  EXPECT_EQ(out.iterations, 2);
  EXPECT_LE(out.depth, 0.8 + 1e-12);
}

}  // namespace
}  // namespace hullcheck::detail
