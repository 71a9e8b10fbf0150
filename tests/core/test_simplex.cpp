// Unit tests of the GJK simplex solver (detail/simplex.hpp and reduce_simplex in detail/gjk.hpp):
// the point of a point, segment, triangle or tetrahedron nearest the origin, in every Voronoi
// region, with its barycentric weights and kept vertices. The expected answers are derived
// analytically here: each simplex is a reference simplex whose nearest point to a query point q
// is known in closed form, translated by -q and rotated so that q lands on the origin.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "detail/gjk.hpp"
#include "detail/simplex.hpp"
#include "oracles.hpp"
#include "rng.hpp"

namespace hullcheck::detail {
namespace {

using Eigen::Vector3d;

// A fixed, generic rotation (no axis-aligned coincidences), and the identity.
Eigen::Matrix3d generic_rotation() {
  return Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
}

// Reference vertices placed so that the query point q is the origin: R (v - q).
std::vector<Vector3d> place(const std::vector<Vector3d>& reference, const Vector3d& q,
                            const Eigen::Matrix3d& rotation) {
  std::vector<Vector3d> out;
  for (const Vector3d& v : reference) out.push_back(rotation * (v - q));
  return out;
}

// Expected sub-simplex: kept reference vertices (ascending) and their weights.
struct Expected {
  std::vector<int> index;
  std::vector<double> lambda;
};

// Checks `sub` against the expected region and weights, and its distance and weights against
// the point they combine, which must be R (c - q) for the reference nearest point c.
void expect_sub(const SubSimplex& sub, const std::vector<Vector3d>& p, const Expected& e,
                double expected_distance_squared) {
  ASSERT_EQ(sub.size, static_cast<int>(e.index.size()));
  Vector3d combined = Vector3d::Zero();
  for (int i = 0; i < sub.size; ++i) {
    EXPECT_EQ(sub.index[i], e.index[i]) << "kept vertex " << i;
    EXPECT_NEAR(sub.lambda[i], e.lambda[i], 1e-12) << "weight " << i;
    combined += sub.lambda[i] * p[sub.index[i]];
  }
  EXPECT_NEAR(sub.distance_squared, expected_distance_squared, 1e-12);
  EXPECT_NEAR(combined.squaredNorm(), expected_distance_squared, 1e-12);
}

// Case a (segment) in its three regions, including the one Casalino calls impossible
// (s_optimum >= 1, beyond the older vertex): the solver must not rely on temporal order.
TEST(SimplexSegment, EveryVoronoiRegion) {
  const std::vector<Vector3d> ref = {Vector3d(0, 0, 0), Vector3d(4, 0, 0)};
  const Eigen::Matrix3d r = generic_rotation();
  struct Case {
    Vector3d q;
    Expected e;
    double d2;
  };
  const Case cases[] = {
      {Vector3d(-1, 2, 0), {{0}, {1.0}}, 5.0},           // before the first vertex
      {Vector3d(6, 0, 1), {{1}, {1.0}}, 5.0},            // beyond the second vertex
      {Vector3d(1, 2, 0), {{0, 1}, {0.75, 0.25}}, 4.0},  // interior: (1,0,0)
      {Vector3d(3, 0, 0), {{0, 1}, {0.25, 0.75}}, 0.0},  // origin on the segment
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << "q = " << c.q.transpose());
    const std::vector<Vector3d> p = place(ref, c.q, r);
    expect_sub(closest_on_segment(p.data(), 0, 1), p, c.e, c.d2);
  }
}

// Case a on arbitrary parent indices, and a zero-length segment (repeated vertex).
TEST(SimplexSegment, ParentIndicesAndRepeatedVertex) {
  const Vector3d p[4] = {Vector3d(9, 9, 9), Vector3d(-1, 2, 0), Vector3d(9, 9, 9),
                         Vector3d(3, 2, 0)};
  const SubSimplex s = closest_on_segment(p, 1, 3);
  ASSERT_EQ(s.size, 2);
  EXPECT_EQ(s.index[0], 1);
  EXPECT_EQ(s.index[1], 3);
  EXPECT_NEAR(s.lambda[0], 0.75, 1e-15);
  EXPECT_NEAR(s.distance_squared, 4.0, 1e-15);
  const Vector3d q[2] = {Vector3d(1, 2, 3), Vector3d(1, 2, 3)};
  const SubSimplex z = closest_on_segment(q, 0, 1);
  ASSERT_EQ(z.size, 1);
  EXPECT_EQ(z.lambda[0], 1.0);
  EXPECT_EQ(z.distance_squared, 14.0);
  // Exactly on the boundary of the first vertex's region (s_optimum = 0): that vertex alone.
  const Vector3d b[2] = {Vector3d(0, 1, 0), Vector3d(5, 1, 0)};
  const SubSimplex e = closest_on_segment(b, 0, 1);
  ASSERT_EQ(e.size, 1);
  EXPECT_EQ(e.index[0], 0);
  EXPECT_EQ(e.distance_squared, 1.0);
}

// Case b (triangle (0,0),(1,0),(0,1) in the plane z = h): the seven Voronoi regions of the
// plane (face, three edges, three vertices), above, below and in the plane of the triangle.
TEST(SimplexTriangle, EveryVoronoiRegion) {
  struct Case {
    double x, y;
    Expected e;
    double planar_d2;  // squared distance of (x, y) to the reference triangle, in its plane
  };
  const Case cases[] = {
      {0.25, 0.25, {{0, 1, 2}, {0.5, 0.25, 0.25}}, 0.0},  // face
      {0.5, -1.0, {{0, 1}, {0.5, 0.5}}, 1.0},             // edge 01: (0.5, 0)
      {-1.0, 0.25, {{0, 2}, {0.75, 0.25}}, 1.0},          // edge 02: (0, 0.25)
      {1.0, 1.0, {{1, 2}, {0.5, 0.5}}, 0.5},              // edge 12: (0.5, 0.5)
      {-1.0, -1.0, {{0}, {1.0}}, 2.0},                    // vertex 0
      {2.0, -0.5, {{1}, {1.0}}, 1.25},                    // vertex 1
      {-0.5, 2.0, {{2}, {1.0}}, 1.25},                    // vertex 2
  };
  const Eigen::Matrix3d rotations[] = {Eigen::Matrix3d::Identity(), generic_rotation()};
  for (const double h : {0.0, 0.5, -2.0}) {
    const std::vector<Vector3d> ref = {Vector3d(0, 0, h), Vector3d(1, 0, h), Vector3d(0, 1, h)};
    for (const Eigen::Matrix3d& r : rotations) {
      for (const Case& c : cases) {
        SCOPED_TRACE(testing::Message() << "h = " << h << ", q = (" << c.x << ", " << c.y << ")");
        const std::vector<Vector3d> p = place(ref, Vector3d(c.x, c.y, 0.0), r);
        expect_sub(closest_on_triangle(p.data(), 0, 1, 2), p, c.e, c.planar_d2 + h * h);
      }
    }
  }
}

// Case b on degenerate triangles: collinear (answer on its longest edge), two repeated vertices
// (a segment) and three (a point), and a needle far thinner than the 1e-30 flatness guard.
TEST(SimplexTriangle, DegenerateTriangles) {
  const Vector3d collinear[3] = {Vector3d(-1, 1, 0), Vector3d(3, 1, 0), Vector3d(1, 1, 0)};
  const SubSimplex c = closest_on_triangle(collinear, 0, 1, 2);
  Vector3d point = Vector3d::Zero();
  double weight = 0.0;
  for (int i = 0; i < c.size; ++i) {
    EXPECT_GE(c.lambda[i], 0.0);
    weight += c.lambda[i];
    point += c.lambda[i] * collinear[c.index[i]];
  }
  EXPECT_NEAR(weight, 1.0, 1e-15);
  EXPECT_TRUE(point.isApprox(Vector3d(0, 1, 0), 1e-15)) << point.transpose();
  EXPECT_NEAR(c.distance_squared, 1.0, 1e-15);

  const Vector3d repeated[3] = {Vector3d(1, 1, 1), Vector3d(1, 1, 1), Vector3d(1, 1, -1)};
  const SubSimplex r = closest_on_triangle(repeated, 0, 1, 2);
  ASSERT_EQ(r.size, 2);
  EXPECT_EQ(r.index[1], 2);  // the distinct vertex is kept
  EXPECT_NEAR(r.lambda[0], 0.5, 1e-15);
  EXPECT_NEAR(r.distance_squared, 2.0, 1e-15);

  const Vector3d single[3] = {Vector3d(0, 3, 4), Vector3d(0, 3, 4), Vector3d(0, 3, 4)};
  const SubSimplex s = closest_on_triangle(single, 0, 1, 2);
  ASSERT_EQ(s.size, 1);
  EXPECT_EQ(s.distance_squared, 25.0);
}

// Case c (tetrahedron (0,0,0),(1,0,0),(0,1,0),(0,0,1)): interior, the four faces (the one
// opposite the newest vertex 3 included, which Casalino excludes), six edges, four vertices.
TEST(SimplexTetrahedron, EveryVoronoiRegion) {
  const std::vector<Vector3d> ref = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0),
                                     Vector3d(0, 0, 1)};
  struct Case {
    Vector3d q;
    Expected e;
    double d2;
  };
  const double third = 1.0 / 3.0;
  const Case cases[] = {
      {Vector3d(0.1, 0.2, 0.3), {{0, 1, 2, 3}, {0.4, 0.1, 0.2, 0.3}}, 0.0},  // interior
      {Vector3d(0.5, 0.5, 0.5), {{1, 2, 3}, {third, third, third}}, 1.0 / 12.0},
      {Vector3d(0.2, 0.3, -1), {{0, 1, 2}, {0.5, 0.2, 0.3}}, 1.0},  // face z = 0
      {Vector3d(0.2, -1, 0.3), {{0, 1, 3}, {0.5, 0.2, 0.3}}, 1.0},  // face y = 0
      {Vector3d(-1, 0.2, 0.3), {{0, 2, 3}, {0.5, 0.2, 0.3}}, 1.0},  // face x = 0
      {Vector3d(0.5, -1, -1), {{0, 1}, {0.5, 0.5}}, 2.0},           // edge 01
      {Vector3d(-1, 0.25, -1), {{0, 2}, {0.75, 0.25}}, 2.0},        // edge 02
      {Vector3d(-1, -1, 0.5), {{0, 3}, {0.5, 0.5}}, 2.0},           // edge 03
      {Vector3d(1, 1, -1), {{1, 2}, {0.5, 0.5}}, 1.5},              // edge 12
      {Vector3d(1, -1, 1), {{1, 3}, {0.5, 0.5}}, 1.5},              // edge 13
      {Vector3d(-1, 1, 1), {{2, 3}, {0.5, 0.5}}, 1.5},              // edge 23
      {Vector3d(-1, -1, -1), {{0}, {1.0}}, 3.0},                    // vertex 0
      {Vector3d(2, -1, -1), {{1}, {1.0}}, 3.0},                     // vertex 1
      {Vector3d(-1, 3, -1), {{2}, {1.0}}, 6.0},                     // vertex 2
      {Vector3d(-1, -1, 3), {{3}, {1.0}}, 6.0},                     // vertex 3
  };
  const Eigen::Matrix3d rotations[] = {Eigen::Matrix3d::Identity(), generic_rotation()};
  for (const Eigen::Matrix3d& r : rotations) {
    for (const Case& c : cases) {
      SCOPED_TRACE(testing::Message() << "q = " << c.q.transpose());
      const std::vector<Vector3d> p = place(ref, c.q, r);
      expect_sub(closest_on_tetrahedron(p.data()), p, c.e, c.d2);
    }
  }
}

// Case c on degenerate tetrahedra: the origin on a face (not inside: size 3, distance 0), a
// flat tetrahedron (zero volume) beside and around the origin, and a repeated vertex.
TEST(SimplexTetrahedron, DegenerateTetrahedra) {
  const Vector3d on_face[4] = {Vector3d(-0.2, -0.3, 0), Vector3d(0.8, -0.3, 0),
                               Vector3d(-0.2, 0.7, 0), Vector3d(-0.2, -0.3, 1)};
  const SubSimplex f = closest_on_tetrahedron(on_face);
  EXPECT_EQ(f.size, 3);
  EXPECT_LT(f.distance_squared, 1e-30);

  for (const double h : {1.0, 0.0}) {
    SCOPED_TRACE(testing::Message() << "plane z = " << h);
    // A square in the plane z = h; the origin projects to (0.3, 0.1) in its interior.
    const Vector3d flat[4] = {Vector3d(-1.3, -1.1, h), Vector3d(0.7, 0.9, h),
                              Vector3d(0.7, -1.1, h), Vector3d(-1.3, 0.9, h)};
    const SubSimplex s = closest_on_tetrahedron(flat);
    ASSERT_EQ(s.size, 3);
    Vector3d point = Vector3d::Zero();
    for (int i = 0; i < 3; ++i) {
      EXPECT_GE(s.lambda[i], 0.0);
      point += s.lambda[i] * flat[s.index[i]];
    }
    EXPECT_TRUE(point.isApprox(Vector3d(0, 0, h), 1e-14) || point.norm() < 1e-14)
        << point.transpose();
    EXPECT_NEAR(s.distance_squared, h * h, 1e-14);
  }

  const Vector3d repeated[4] = {Vector3d(1, -1, 2), Vector3d(-1, -1, 2), Vector3d(0, 1, 2),
                                Vector3d(0, 1, 2)};
  const SubSimplex r = closest_on_tetrahedron(repeated);
  EXPECT_NEAR(r.distance_squared, 4.0, 1e-14);
  ASSERT_EQ(r.size, 3);
}

// A flat tetrahedron (coplanar to rounding) whose plane passes through the origin, with the
// origin inside it. Its signed volumes are all rounding noise (det 7.6e-17): their signs once
// skipped the faces around the origin and answered edge 01 at distance 0.19 instead of ~0
// (faces 123 and 013 reach 7e-18); random such inputs failed ~8% of the time.
TEST(SimplexTetrahedron, FlatThroughTheOriginWithRoundingNoise) {
  const Vector3d p[4] = {
      Vector3d(-0.080498497668783392, -0.13171913363678572, -0.60369338909288461),
      Vector3d(0.45424853983837432, 0.073493457520301231, 0.52231680064752706),
      Vector3d(0.70377593391808646, -0.22393489922767507, -0.64541816168570743),
      Vector3d(-0.65697702577726114, 0.043525915890058969, -0.11026379337594133)};
  EXPECT_LT(oracle::point_triangle_distance(Vector3d::Zero(), p[1], p[2], p[3]), 1e-15);
  EXPECT_LT(closest_on_tetrahedron(p).distance_squared, 1e-24);
}

// Random flat tetrahedra in planes through (or within 1e-13 of) the origin: the distance is
// the smallest over the four faces (Ericson's point-triangle distance), to the flat limit.
TEST(SimplexTetrahedron, RandomFlatThroughTheOrigin) {
  oracle::Rng rng(77);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vector3d u = rng.in_box(1.0).normalized();
    Vector3d v = rng.in_box(1.0);
    v = (v - v.dot(u) * u).normalized();
    const Vector3d offset = (trial % 2 == 0 ? 0.0 : 1e-13) * u.cross(v);
    Vector3d p[4];
    for (Vector3d& q : p) q = rng.in_box(1.0)[0] * u + rng.in_box(1.0)[1] * v + offset;
    double expected = INFINITY;
    const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    for (const auto& f : faces) {
      expected = std::min(
          expected, oracle::point_triangle_distance(Vector3d::Zero(), p[f[0]], p[f[1]], p[f[2]]));
    }
    EXPECT_NEAR(std::sqrt(closest_on_tetrahedron(p).distance_squared), expected, 1e-11)
        << "trial " << trial;
  }
}

// Random simplices of 2, 3 and 4 vertices against independent oracles (clamped projection,
// Ericson's point-triangle distance, a barycentric solve for the inside test): the distance,
// non-negative weights summing to one, and the weighted point at that distance.
TEST(SimplexRandom, AgreesWithIndependentOracles) {
  oracle::Rng rng(20240601);
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 2 + trial % 3;
    Vector3d p[4];
    const Vector3d centre = rng.in_box(1.5);
    for (int i = 0; i < n; ++i) p[i] = centre + rng.in_box(1.0);
    double expected;
    SubSimplex s;
    if (n == 2) {
      const Vector3d t = p[1] - p[0];
      const double mu = std::clamp(-p[0].dot(t) / t.squaredNorm(), 0.0, 1.0);
      expected = (p[0] + mu * t).norm();
      s = closest_on_segment(p, 0, 1);
    } else if (n == 3) {
      expected = oracle::point_triangle_distance(Vector3d::Zero(), p[0], p[1], p[2]);
      s = closest_on_triangle(p, 0, 1, 2);
    } else {
      Eigen::Matrix3d m;
      m << p[1] - p[0], p[2] - p[0], p[3] - p[0];
      const Vector3d beta = m.fullPivLu().solve(-p[0]);
      const bool inside = beta.minCoeff() > 0.0 && beta.sum() < 1.0;
      expected = INFINITY;
      const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
      for (const auto& f : faces) {
        expected = std::min(
            expected, oracle::point_triangle_distance(Vector3d::Zero(), p[f[0]], p[f[1]], p[f[2]]));
      }
      if (inside) expected = 0.0;
      s = closest_on_tetrahedron(p);
      EXPECT_EQ(s.size == 4, inside) << "trial " << trial;
    }
    Vector3d point = Vector3d::Zero();
    double weight = 0.0;
    for (int i = 0; i < s.size; ++i) {
      EXPECT_GE(s.lambda[i], 0.0) << "trial " << trial;
      weight += s.lambda[i];
      point += s.lambda[i] * p[s.index[i]];
      if (i > 0) {
        EXPECT_LT(s.index[i - 1], s.index[i]) << "indices ascending";
      }
    }
    EXPECT_NEAR(weight, 1.0, 1e-12) << "trial " << trial;
    EXPECT_NEAR(std::sqrt(s.distance_squared), expected, 1e-12) << "trial " << trial;
    EXPECT_NEAR(point.norm(), expected, 1e-12) << "trial " << trial;
  }
}

// reduce_simplex keeps the nearest region's vertices in place, moving their support points and
// vertex indices with them; point_a - point_b is then the nearest point. Returns false (size 4)
// only when the tetrahedron encloses the origin.
TEST(SimplexReduce, CompactsVerticesWithTheirSupportPoints) {
  // Reference tetrahedron with the origin beyond edge 12 (vertices 1 and 2 kept, moved to 0, 1).
  const std::vector<Vector3d> w =
      place({Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1)},
            Vector3d(1, 1, -1), generic_rotation());
  Simplex s;
  s.size = 4;
  for (int i = 0; i < 4; ++i) {
    s.b[i] = Vector3d(i, 10.0 * i, -3.0);
    s.a[i] = w[i] + s.b[i];
    s.w[i] = w[i];
    s.index_a[i] = 100 + i;
    s.index_b[i] = 200 + i;
  }
  EXPECT_TRUE(reduce_simplex(s));
  ASSERT_EQ(s.size, 2);
  for (int j = 0; j < 2; ++j) {
    EXPECT_EQ(s.w[j], w[j + 1]);
    EXPECT_EQ(s.b[j], Vector3d(j + 1, 10.0 * (j + 1), -3.0));
    EXPECT_EQ(s.index_a[j], 101 + j);
    EXPECT_EQ(s.index_b[j], 201 + j);
    EXPECT_NEAR(s.lambda[j], 0.5, 1e-12);
  }
  EXPECT_NEAR(s.closest_point().squaredNorm(), 1.5, 1e-12);
  EXPECT_TRUE((s.point_a() - s.point_b()).isApprox(s.closest_point(), 1e-12));

  // A single point: weight 1, kept as is.
  Simplex one;
  one.size = 1;
  one.w[0] = Vector3d(1, 2, 2);
  EXPECT_TRUE(reduce_simplex(one));
  EXPECT_EQ(one.size, 1);
  EXPECT_EQ(one.lambda[0], 1.0);
  EXPECT_EQ(one.closest_point(), Vector3d(1, 2, 2));

  // Origin enclosed: false, all four kept with the interior weights.
  Simplex in;
  in.size = 4;
  const std::vector<Vector3d> t =
      place({Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1)},
            Vector3d(0.1, 0.2, 0.3), generic_rotation());
  for (int i = 0; i < 4; ++i) in.w[i] = t[i];
  EXPECT_FALSE(reduce_simplex(in));
  EXPECT_EQ(in.size, 4);
  EXPECT_NEAR(in.lambda[0], 0.4, 1e-12);
  EXPECT_NEAR(in.lambda[3], 0.3, 1e-12);
  EXPECT_LT(in.closest_point().norm(), 1e-14);
}

}  // namespace
}  // namespace hullcheck::detail
