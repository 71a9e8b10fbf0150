// Tests of the reference oracles themselves (tests/oracles), against analytic answers. The
// randomized comparisons of hullcheck with the oracles are in test_random_pairs.cpp.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "oracles.hpp"

namespace {

using Eigen::Vector3d;
using hullcheck::oracle::brute_force_distance;
using hullcheck::oracle::minkowski_penetration;
using Points = std::vector<Vector3d>;

constexpr double kTol = 1e-12;
const double kSqrt2 = std::sqrt(2.0);
const double kSqrt3 = std::sqrt(3.0);

Points box_points(const Vector3d& half,
                  const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity()) {
  Points pts;
  for (int i = 0; i < 8; ++i) {
    const Vector3d corner((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                          (i & 4) ? half.z() : -half.z());
    pts.push_back(pose * corner);
  }
  return pts;
}

Points unit_cube(const Vector3d& center = Vector3d::Zero(),
                 const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = center;
  return box_points(Vector3d(0.5, 0.5, 0.5), pose);
}

Points translated(Points pts, const Vector3d& t) {
  for (Vector3d& p : pts) p += t;
  return pts;
}

Eigen::Matrix3d rot(double angle, const Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// Distance of a point to a hull (0 inside), via the oracle.
double point_distance(const Vector3d& p, const Points& hull) {
  return brute_force_distance({p}, hull).distance;
}

void expect_witnesses(const hullcheck::oracle::Distance& d, const Points& a, const Points& b,
                      double tol) {
  EXPECT_NEAR((d.point_b - d.point_a).norm(), d.distance, tol);
  EXPECT_NEAR(point_distance(d.point_a, a), 0.0, tol);
  EXPECT_NEAR(point_distance(d.point_b, b), 0.0, tol);
}

// ------------------------------------------------------------------------------------------
// Distance between unit cubes

TEST(OracleDistance, CubesFaceFace) {
  const Points a = unit_cube();
  for (const Vector3d& offset : {Vector3d(1.5, 0, 0), Vector3d(1.5, 0.3, -0.2),
                                 Vector3d(0, -1.25, 0.9), Vector3d(0.1, 0.2, 3.0)}) {
    const Points b = unit_cube(offset);
    const double expected = offset.cwiseAbs().maxCoeff() - 1.0;
    const auto d = brute_force_distance(a, b);
    EXPECT_FALSE(d.overlapping);
    EXPECT_NEAR(d.distance, expected, kTol) << offset.transpose();
    expect_witnesses(d, a, b, kTol);
    const auto p = minkowski_penetration(a, b);
    EXPECT_FALSE(p.overlapping);
    EXPECT_EQ(p.depth, 0.0);
  }
}

TEST(OracleDistance, CubesEdgeEdgeParallel) {
  const Points a = unit_cube();
  const Points b = unit_cube(Vector3d(1.5, 1.5, 0.2));
  const auto d = brute_force_distance(a, b);
  EXPECT_NEAR(d.distance, std::sqrt(0.5), kTol);
  expect_witnesses(d, a, b, kTol);
}

TEST(OracleDistance, CubesEdgeEdgeCrossed) {
  // A's top is an edge along x at height sqrt(2)/2; B's bottom an edge along y.
  const Points a = unit_cube(Vector3d::Zero(), rot(M_PI / 4, Vector3d::UnitX()));
  for (double gap : {1e-6, 0.01, 0.5, 3.0}) {
    const Vector3d center(0.2, 0.1, kSqrt2 + gap);
    const Points b = unit_cube(center, rot(M_PI / 4, Vector3d::UnitY()));
    const auto d = brute_force_distance(a, b);
    EXPECT_NEAR(d.distance, gap, kTol) << gap;
    EXPECT_NEAR(d.point_a.x(), 0.2, 1e-9);
    EXPECT_NEAR(d.point_a.y(), 0.0, 1e-9);
    EXPECT_NEAR(d.point_a.z(), kSqrt2 / 2, 1e-9);
    EXPECT_NEAR(d.point_b.z(), kSqrt2 / 2 + gap, 1e-9);
    expect_witnesses(d, a, b, kTol);
  }
}

TEST(OracleDistance, CubesVertexFace) {
  // Rotate B so that its corner (-1,-1,-1)/2 points straight down.
  const Eigen::Matrix3d r =
      Eigen::Quaterniond::FromTwoVectors(Vector3d(-1, -1, -1), Vector3d(0, 0, -1))
          .toRotationMatrix();
  const Points a = unit_cube();
  for (double gap : {1e-7, 0.25, 2.0}) {
    const Vector3d center(0.1, -0.2, 0.5 + kSqrt3 / 2 + gap);
    const Points b = unit_cube(center, r);
    const auto d = brute_force_distance(a, b);
    EXPECT_FALSE(d.overlapping);
    EXPECT_NEAR(d.distance, gap, kTol);
    EXPECT_NEAR((d.point_a - Vector3d(0.1, -0.2, 0.5)).norm(), 0.0, 1e-9);
    expect_witnesses(d, a, b, kTol);
  }
}

TEST(OracleDistance, RotationAndTranslationInvariant) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const Points a = hullcheck::oracle::random_hull_points(1, 20);
  const Points b = translated(hullcheck::oracle::random_hull_points(2, 30), Vector3d(2.5, 0.3, 0));
  const double d0 = brute_force_distance(a, b).distance;
  ASSERT_GT(d0, 0.1);
  for (int i = 0; i < 10; ++i) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    t.translation() = Vector3d(u(rng), u(rng), u(rng)) * 10;
    const auto ta = hullcheck::oracle::transformed(a, t);
    const auto tb = hullcheck::oracle::transformed(b, t);
    EXPECT_NEAR(brute_force_distance(ta, tb).distance, d0, 1e-12 * 12);
    EXPECT_NEAR(brute_force_distance(tb, ta).distance, d0, 1e-12 * 12);
  }
}

// ------------------------------------------------------------------------------------------
// Overlap and penetration depth

TEST(OraclePenetration, OverlappingCubesDepthAndSign) {
  const Points a = unit_cube();
  struct Case {
    Vector3d offset;
    double depth;
    Vector3d normal;
  };
  for (const Case& c :
       {Case{{0.7, 0.1, 0.05}, 0.3, {1, 0, 0}}, Case{{-0.7, 0.1, 0.05}, 0.3, {-1, 0, 0}},
        Case{{0.1, -0.2, 0.9}, 0.1, {0, 0, 1}}, Case{{0.1, -0.6, 0.3}, 0.4, {0, -1, 0}}}) {
    const Points b = unit_cube(c.offset);
    const auto d = brute_force_distance(a, b);
    EXPECT_TRUE(d.overlapping);
    EXPECT_EQ(d.distance, 0.0);
    const auto p = minkowski_penetration(a, b);
    EXPECT_TRUE(p.overlapping);
    EXPECT_NEAR(p.depth, c.depth, kTol) << c.offset.transpose();
    EXPECT_NEAR((p.normal - c.normal).norm(), 0.0, 1e-9) << p.normal.transpose();
    // Translating B by depth * normal leaves them touching; a little further separates them.
    const Points touching = translated(b, p.depth * p.normal);
    EXPECT_NEAR(brute_force_distance(a, touching).distance, 0.0, kTol);
    EXPECT_NEAR(minkowski_penetration(a, touching).depth, 0.0, kTol);
    const Points apart = translated(b, (p.depth + 1e-3) * p.normal);
    EXPECT_NEAR(brute_force_distance(a, apart).distance, 1e-3, kTol);
  }
}

TEST(OraclePenetration, SlabsOneDimensional) {
  // Thin in x, huge in y and z: the only short way out is along x, towards B.
  const Vector3d half(0.5, 10, 10);
  const Points a = box_points(half);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Vector3d(0.8, 0, 0);
  const Points b = box_points(half, pose);
  const auto p = minkowski_penetration(a, b);
  EXPECT_NEAR(p.depth, 0.2, kTol);
  EXPECT_NEAR((p.normal - Vector3d::UnitX()).norm(), 0.0, 1e-12);
}

TEST(OraclePenetration, SmallCubeInsideBigCube) {
  const Points a = box_points(Vector3d(2, 2, 2));
  const Points b = unit_cube(Vector3d(1, 0, 0));
  const auto d = brute_force_distance(a, b);
  EXPECT_TRUE(d.overlapping);
  EXPECT_EQ(d.distance, 0.0);
  const auto p = minkowski_penetration(a, b);
  EXPECT_NEAR(p.depth, 1.5, kTol);
  EXPECT_NEAR((p.normal - Vector3d::UnitX()).norm(), 0.0, 1e-12);
  // And the other way round: moving A's copy... i.e. B = big cube, A = small one.
  const auto q = minkowski_penetration(b, a);
  EXPECT_NEAR(q.depth, 1.5, kTol);
  EXPECT_NEAR((q.normal + Vector3d::UnitX()).norm(), 0.0, 1e-12);
}

TEST(OraclePenetration, RotatedCubesAgreeWithAnalyticDepth) {
  // Overlapping cubes along a face normal, the whole scene rotated and moved.
  const Eigen::Matrix3d r = rot(0.7, Vector3d(1, 2, 3));
  const Vector3d t(3, -4, 5);
  const Points a = unit_cube(t, r);
  const Points b = unit_cube(t + r * Vector3d(0.15, 0.75, 0.1), r);
  const auto p = minkowski_penetration(a, b);
  EXPECT_NEAR(p.depth, 0.25, kTol);
  EXPECT_NEAR((p.normal - r * Vector3d::UnitY()).norm(), 0.0, 1e-12);
}

TEST(OraclePenetration, Tetrahedra) {
  const Points a = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  // Apart: vertex (1,0,0) against vertex (2,0,0).
  {
    const auto d = brute_force_distance(a, translated(a, Vector3d(2, 0, 0)));
    EXPECT_FALSE(d.overlapping);
    EXPECT_NEAR(d.distance, 1.0, kTol);
  }
  // Vertex of B against the slanted face x + y + z = 1 of A.
  {
    const Points b = {{1, 1, 1}, {2, 1, 1}, {1, 2, 1}, {1, 1, 2}};
    const auto d = brute_force_distance(a, b);
    EXPECT_NEAR(d.distance, 2.0 / kSqrt3, kTol);
    EXPECT_NEAR((d.point_a - Vector3d(1, 1, 1) / 3).norm(), 0.0, 1e-12);
  }
  // A flipped tetrahedron poking through the slanted face by 0.1: depth 0.1 along (1,1,1).
  {
    const Vector3d apex = Vector3d(1, 1, 1) / 3 - 0.1 * Vector3d(1, 1, 1) / kSqrt3;
    const Points b = {apex, apex + Vector3d(1, 1, 1) * 2 + Vector3d(1, 0, 0),
                      apex + Vector3d(1, 1, 1) * 2 + Vector3d(0, 1, 0),
                      apex + Vector3d(1, 1, 1) * 2 + Vector3d(0, 0, 1)};
    const auto p = minkowski_penetration(a, b);
    EXPECT_TRUE(p.overlapping);
    EXPECT_NEAR(p.depth, 0.1, 1e-12);
    EXPECT_NEAR((p.normal - Vector3d(1, 1, 1) / kSqrt3).norm(), 0.0, 1e-9);
    EXPECT_TRUE(brute_force_distance(a, b).overlapping);
  }
}

// ------------------------------------------------------------------------------------------
// Degenerate point sets

TEST(OracleDegenerate, PointsAndSegments) {
  const Points p = {{1, 1, 0}};
  const Points seg = {{0, 0, 0}, {2, 0, 0}};
  EXPECT_NEAR(brute_force_distance(p, {{4, 5, 0}}).distance, 5.0, kTol);
  EXPECT_NEAR(brute_force_distance(p, seg).distance, 1.0, kTol);
  EXPECT_NEAR(brute_force_distance({{3, 1, 0}}, seg).distance, kSqrt2, kTol);
  // Skew segments, 1 apart.
  const Points skew = {{0.5, -1, 1}, {0.5, 1, 1}};
  const auto d = brute_force_distance(seg, skew);
  EXPECT_NEAR(d.distance, 1.0, kTol);
  EXPECT_NEAR((d.point_a - Vector3d(0.5, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((d.point_b - Vector3d(0.5, 0, 1)).norm(), 0.0, 1e-12);
  // Collinear points with duplicates are one segment; parallel segments.
  const Points needle = {{0, 1, 0}, {1, 1, 0}, {1, 1, 0}, {0.5, 1, 0}, {3, 1, 0}};
  EXPECT_NEAR(brute_force_distance(seg, needle).distance, 1.0, kTol);
  // A point on a segment touches it; a flat difference has no depth.
  const auto touch = brute_force_distance({{1, 0, 0}}, seg);
  EXPECT_TRUE(touch.overlapping);
  EXPECT_EQ(touch.distance, 0.0);
  const auto pen = minkowski_penetration({{1, 0, 0}}, seg);
  EXPECT_TRUE(pen.overlapping);
  EXPECT_EQ(pen.depth, 0.0);
  EXPECT_FALSE(minkowski_penetration({{1, 0.5, 0}}, seg).overlapping);
  // Single repeated point inside a cube: depth = distance to the nearest face.
  const auto inside = minkowski_penetration(unit_cube(), {{0.1, 0.3, 0}, {0.1, 0.3, 0}});
  EXPECT_NEAR(inside.depth, 0.2, kTol);
  EXPECT_NEAR((inside.normal - Vector3d::UnitY()).norm(), 0.0, 1e-12);
  EXPECT_TRUE(brute_force_distance(unit_cube(), {{0.1, 0.3, 0}}).overlapping);
}

TEST(OracleDegenerate, FlatPolygons) {
  const Points square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  EXPECT_NEAR(brute_force_distance(square, {{0.3, 0.6, 2}}).distance, 2.0, kTol);
  EXPECT_NEAR(brute_force_distance(square, {{2, 0.5, 0}}).distance, 1.0, kTol);
  EXPECT_NEAR(brute_force_distance(square, {{2, 2, 1}}).distance, kSqrt3, kTol);
  // Parallel squares 1 apart; coplanar overlapping squares (touching: no depth).
  EXPECT_NEAR(brute_force_distance(square, translated(square, {0.5, 0.5, 1})).distance, 1.0, kTol);
  const Points coplanar = translated(square, {0.5, 0.5, 0});
  EXPECT_TRUE(brute_force_distance(square, coplanar).overlapping);
  EXPECT_EQ(minkowski_penetration(square, coplanar).depth, 0.0);
  // Two perpendicular squares crossing: the difference is a box, depth 0.5.
  const Points wall = {{0.5, 0.25, -0.5}, {0.5, 0.75, -0.5}, {0.5, 0.75, 0.5}, {0.5, 0.25, 0.5}};
  EXPECT_TRUE(brute_force_distance(square, wall).overlapping);
  const auto pen = minkowski_penetration(square, wall);
  EXPECT_TRUE(pen.overlapping);
  EXPECT_NEAR(pen.depth, 0.5, kTol);
  // A square through a cube (no vertex of either inside the other, edges cross faces).
  const Points big_square = {{-2, -2, 0.1}, {2, -2, 0.1}, {2, 2, 0.1}, {-2, 2, 0.1}};
  EXPECT_TRUE(brute_force_distance(unit_cube(), big_square).overlapping);
  EXPECT_NEAR(minkowski_penetration(unit_cube(), big_square).depth, 0.4, kTol);
  // A needle through a cube.
  const Points needle = {{0.2, 0.1, -3}, {0.2, 0.1, 3}};
  EXPECT_TRUE(brute_force_distance(unit_cube(), needle).overlapping);
  EXPECT_NEAR(minkowski_penetration(unit_cube(), needle).depth, 0.3, kTol);
}

TEST(OracleDegenerate, RotatedFlatAndNearlyFlat) {
  const Eigen::Matrix3d r = rot(1.1, Vector3d(-1, 2, 0.5));
  const Vector3d t(10, 20, -30);
  // A rotated square (world coordinates only coplanar up to rounding) above a rotated cube.
  Points square = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  for (Vector3d& p : square) p = r * (p + Vector3d(0, 0, 0.75)) + t;
  const Points cube = unit_cube(t, r);
  EXPECT_NEAR(brute_force_distance(cube, square).distance, 0.25, 1e-12 * 40);
  EXPECT_NEAR(brute_force_distance(square, cube).distance, 0.25, 1e-12 * 40);
  // Nearly flat: thickness 1e-6.
  Points slab = {{-1, -1, 0},    {1, -1, 0},    {1, 1, 0},    {-1, 1, 0},
                 {-1, -1, 1e-6}, {1, -1, 1e-6}, {1, 1, 1e-6}, {-1, 1, 1e-6}};
  for (Vector3d& p : slab) p = r * (p + Vector3d(0, 0, 0.75)) + t;
  EXPECT_NEAR(brute_force_distance(cube, slab).distance, 0.25, 1e-12 * 40);
  for (Vector3d& p : slab) p -= r * Vector3d(0, 0, 0.3);  // now 0.05 deep
  const auto pen = minkowski_penetration(cube, slab);
  EXPECT_NEAR(pen.depth, 0.05, 1e-12 * 40);
  EXPECT_NEAR((pen.normal - r * Vector3d::UnitZ()).norm(), 0.0, 1e-9);
}

TEST(OracleDegenerate, DuplicatedPointsChangeNothing) {
  const Points a = hullcheck::oracle::random_hull_points(11, 12);
  const Points b = translated(hullcheck::oracle::random_hull_points(12, 9), Vector3d(1.2, 0.4, 0));
  Points a3;
  for (int k = 0; k < 3; ++k) a3.insert(a3.end(), a.begin(), a.end());
  const auto d = brute_force_distance(a, b);
  const auto d3 = brute_force_distance(a3, b);
  EXPECT_EQ(d.overlapping, d3.overlapping);
  EXPECT_NEAR(d.distance, d3.distance, kTol);
  EXPECT_NEAR(minkowski_penetration(a, b).depth, minkowski_penetration(a3, b).depth, kTol);
}

TEST(OracleDegenerate, EmptySetThrows) {
  EXPECT_THROW(brute_force_distance({}, {{0, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(minkowski_penetration({{0, 0, 0}}, {}), std::invalid_argument);
}

// ------------------------------------------------------------------------------------------
// Consistency of the two oracles, and of the overlap interval

TEST(OracleConsistency, DistanceEqualsOriginToMinkowskiDifference) {
  // dist(A, B) = dist(0, A - B): the second is a point-to-hull query on |A||B| points.
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const Points a = hullcheck::oracle::random_hull_points(100 + seed, 4 + seed % 13);
    Points b = hullcheck::oracle::random_hull_points(200 + seed, 4 + seed % 7, 0.7);
    b = translated(b, Vector3d(1.0 + 0.05 * seed, 0.3, -0.2));
    Points diff;
    for (const Vector3d& p : a) {
      for (const Vector3d& q : b) diff.push_back(p - q);
    }
    const auto d = brute_force_distance(a, b);
    const auto m = brute_force_distance({Vector3d::Zero()}, diff);
    const auto p = minkowski_penetration(a, b);
    EXPECT_EQ(d.overlapping, m.overlapping) << seed;
    EXPECT_NEAR(d.distance, m.distance, kTol) << seed;
    if (d.distance > 1e-9 || p.depth > 1e-9) {
      EXPECT_EQ(d.overlapping, p.overlapping) << seed;
    }
    if (!d.overlapping) expect_witnesses(d, a, b, kTol);
  }
}

TEST(OracleConsistency, OverlapInterval) {
  const Points a = unit_cube();
  const auto r = hullcheck::oracle::overlap_interval(a, unit_cube(), Vector3d::UnitX());
  EXPECT_NEAR(r.lo, -1.0, kTol);
  EXPECT_NEAR(r.hi, 1.0, kTol);
  const auto diag =
      hullcheck::oracle::overlap_interval(a, unit_cube(Vector3d(0, 0.5, 0)), Vector3d(1, 1, 0));
  EXPECT_NEAR(diag.lo, -1.0, kTol);  // B's centre at (t, 0.5 + t, 0): |t| < 1, |0.5 + t| < 1
  EXPECT_NEAR(diag.hi, 0.5, kTol);
  EXPECT_TRUE(
      hullcheck::oracle::overlap_interval(a, unit_cube(Vector3d(0, 3, 0)), Vector3d::UnitX())
          .empty());
  EXPECT_TRUE(
      hullcheck::oracle::overlap_interval({{0, 0, 0}}, {{1, 0, 0}}, Vector3d::UnitX()).empty());
}

// ------------------------------------------------------------------------------------------
// Random data

TEST(OracleRandom, HullPointsAreDeterministicVerticesOnTheEllipsoid) {
  for (int n : {1, 4, 5, 16, 64}) {
    const Points p = hullcheck::oracle::random_hull_points(42, n, 2.0);
    ASSERT_EQ(static_cast<int>(p.size()), n);
    EXPECT_EQ(p, hullcheck::oracle::random_hull_points(42, n, 2.0));
    EXPECT_NE(p, hullcheck::oracle::random_hull_points(43, n, 2.0));
    for (const Vector3d& q : p) {
      EXPECT_LE(q.norm(), 2.0 + 1e-12);
      EXPECT_GE(q.norm(), 1.0 - 1e-12);
    }
    if (n < 5) continue;
    for (int i = 0; i < n; ++i) {  // every point lies outside the hull of the others
      Points others = p;
      others.erase(others.begin() + i);
      EXPECT_GT(brute_force_distance({p[static_cast<std::size_t>(i)]}, others).distance, 1e-6)
          << n << " " << i;
    }
  }
}

TEST(OracleRandom, HullPairsHaveExactOverlapFraction) {
  for (double fraction : {0.0, 0.3, 1.0}) {
    const auto pairs = hullcheck::oracle::make_hull_pairs(5, 40, 12, fraction, 2.0);
    ASSERT_EQ(pairs.size(), 40U);
    int overlapping = 0;
    for (const auto& pair : pairs) {
      const Points a = hullcheck::oracle::transformed(pair.a, pair.pose_a);
      const Points b = hullcheck::oracle::transformed(pair.b, pair.pose_b);
      const auto d = brute_force_distance(a, b);
      const auto p = minkowski_penetration(a, b);
      EXPECT_EQ(d.overlapping, p.overlapping);
      if (d.overlapping) {
        ++overlapping;
        EXPECT_GT(p.depth, 1e-6);
      } else {
        EXPECT_GT(d.distance, 1e-6);
        EXPECT_LE(d.distance, 2.0 + 1e-9);
      }
    }
    EXPECT_EQ(overlapping, static_cast<int>(std::lround(fraction * 40)));
  }
  const auto again = hullcheck::oracle::make_hull_pairs(5, 3, 12, 0.3, 2.0);
  const auto first = hullcheck::oracle::make_hull_pairs(5, 3, 12, 0.3, 2.0);
  for (std::size_t i = 0; i < again.size(); ++i) {
    EXPECT_EQ(again[i].a, first[i].a);
    EXPECT_TRUE(again[i].pose_b.isApprox(first[i].pose_b, 0.0));
  }
}

}  // namespace
