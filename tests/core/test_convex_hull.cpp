// ConvexHull construction (qhull), degenerate point sets, and exactness of the support function.
#include <gtest/gtest.h>

#include <hullcheck/core.hpp>
#include <random>

#include "test_support.hpp"

namespace hullcheck {
namespace {

std::vector<Eigen::Vector3d> unit_cube() {
  std::vector<Eigen::Vector3d> cube;
  for (int i = 0; i < 8; ++i) {
    cube.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  }
  return cube;
}

std::vector<Eigen::Vector3d> points_on_sphere(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    points.push_back(Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
  }
  return points;
}

int brute_force_support(const std::vector<Eigen::Vector3d>& v, const Eigen::Vector3d& d) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(v.size()); ++i) {
    if (v[i].dot(d) > v[best].dot(d)) best = i;
  }
  return best;
}

TEST(ConvexHull, CubeWithInteriorPointsAndDuplicates) {
  std::vector<Eigen::Vector3d> points = unit_cube();
  points.push_back({0.1, 0.2, -0.3});
  points.push_back({0, 0, 0});
  points.push_back(points[3]);  // duplicate vertex
  const ConvexHull hull(points);
  EXPECT_EQ(hull.dimension(), 3);
  EXPECT_EQ(hull.vertex_count(), 8u);
  EXPECT_EQ(hull.triangles().size(), 12u);
  EXPECT_NEAR(hull.extent(), std::sqrt(0.75), 1e-15);
  for (int i = 0; i < 8; ++i) EXPECT_GE(hull.neighbors(i).size(), 3u);
  // Triangles face outwards.
  for (const auto& t : hull.triangles()) {
    const auto& v = hull.vertices();
    const Eigen::Vector3d n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
    EXPECT_GT(n.dot(v[t[0]]), 0.0);
  }
}

TEST(ConvexHull, SinglePointAndDuplicates) {
  const ConvexHull one({{1, 2, 3}});
  EXPECT_EQ(one.dimension(), 0);
  EXPECT_EQ(one.vertex_count(), 1u);
  const ConvexHull same({{1, 2, 3}, {1, 2, 3}, {1, 2, 3}});
  EXPECT_EQ(same.dimension(), 0);
  EXPECT_EQ(same.vertex_count(), 1u);
  EXPECT_TRUE(same.support({0, 0, 1}).isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST(ConvexHull, CollinearKeepsTheTwoEnds) {
  const ConvexHull line({{0, 0, 0}, {1, 1, 1}, {0.5, 0.5, 0.5}, {-1, -1, -1}, {0.2, 0.2, 0.2}});
  EXPECT_EQ(line.dimension(), 1);
  ASSERT_EQ(line.vertex_count(), 2u);
  EXPECT_TRUE(line.support({1, 0, 0}).isApprox(Eigen::Vector3d(1, 1, 1)));
  EXPECT_TRUE(line.support({-1, 0, 0}).isApprox(Eigen::Vector3d(-1, -1, -1)));
}

TEST(ConvexHull, CoplanarIsAPolygon) {
  // A hexagon with interior points, tilted out of the coordinate planes.
  const Eigen::Matrix3d r = rotation_from_xyz_angles(0.3, -0.7, 1.1);
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 6; ++k) points.push_back(r * Eigen::Vector3d(std::cos(k), std::sin(k), 0));
  for (int k = 0; k < 6; ++k) points.push_back(r * Eigen::Vector3d(0.3 * std::cos(k), 0.2, 0));
  const ConvexHull hull(points);
  EXPECT_EQ(hull.dimension(), 2);
  EXPECT_EQ(hull.vertex_count(), 6u);
  EXPECT_EQ(hull.triangles().size(), 4u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(hull.neighbors(i).size(), 2u);
}

TEST(ConvexHull, NeedleAndNearlyFlatHullsAreThreeDimensional) {
  std::vector<Eigen::Vector3d> needle = {{0, 0, -1}, {0, 0, 1}, {1e-4, 0, 0}, {0, 1e-4, 0.1}};
  EXPECT_EQ(ConvexHull(needle).dimension(), 3);
  std::vector<Eigen::Vector3d> slab = unit_cube();
  for (auto& p : slab) p.z() *= 1e-6;
  const ConvexHull flat(slab);
  EXPECT_EQ(flat.dimension(), 3);
  EXPECT_EQ(flat.vertex_count(), 8u);
}

TEST(ConvexHull, HillClimbingSupportIsExact) {
  for (int n : {50, 200, 2000}) {
    const ConvexHull hull(points_on_sphere(n, n));
    ASSERT_GE(hull.vertex_count(), ConvexHull::kHillClimbingThreshold);
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int k = 0; k < 20000; ++k) {
      Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
      if (k % 4 == 1) d.x() = 0.0;  // directions on cube-map cell borders and axes
      if (k % 4 == 2) d.y() = d.z();
      const int expected = brute_force_support(hull.vertices(), d);
      const int got = hull.support_index(d);
      ASSERT_EQ(hull.vertices()[got].dot(d), hull.vertices()[expected].dot(d)) << n << " " << k;
    }
  }
}

TEST(ConvexHull, EveryInputPointIsInside) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 500; ++i)
    points.emplace_back(normal(rng), 0.3 * normal(rng), 2 * normal(rng));
  const ConvexHull hull(points);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    const double h = hull.support(d).dot(d);
    for (const auto& p : points) ASSERT_LE(p.dot(d), h + 1e-12 * d.norm());
  }
}

TEST(ConvexHull, BadInputThrowsClearErrors) {
  EXPECT_THROW(ConvexHull(std::vector<Eigen::Vector3d>{}), InputError);
  try {
    ConvexHull({{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("point 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ConvexHull({{0, 0, INFINITY}}), InputError);
  EXPECT_THROW(ConvexHull({{0, 0, 0}}).neighbors(5), InputError);
}

}  // namespace
}  // namespace hullcheck

namespace hullcheck {
namespace {

// The bounding-box centre of a corner tetrahedron, (1/2, 1/2, 1/2), lies outside it: a small
// sphere there is 0.5/sqrt(3) - r away, and no shortcut may call the pair overlapping.
TEST(ConvexHull, BoxCentreOutsideTheHullIsNotTakenAsInside) {
  const ConvexHull corner({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  const Eigen::Isometry3d at_centre = test::translation(0.5, 0.5, 0.5);
  const double expected = 0.5 / std::sqrt(3.0) - 0.05;
  EXPECT_FALSE(intersect(corner, Eigen::Isometry3d::Identity(), Sphere(0.05), at_centre));
  EXPECT_NEAR(distance(corner, Eigen::Isometry3d::Identity(), Sphere(0.05), at_centre).distance,
              expected, 1e-12);
  EXPECT_EQ(penetration(corner, Eigen::Isometry3d::Identity(), Sphere(0.05), at_centre).depth, 0.0);
  // Flat hulls have no inner ball either; (0.6, 0.6, 0) is 0.2/sqrt(2) - 0.05 off the triangle.
  const ConvexHull flat({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  EXPECT_FALSE(intersect(flat, Eigen::Isometry3d::Identity(), Sphere(0.05),
                         test::translation(0.6, 0.6, 0.0)));
}

}  // namespace
}  // namespace hullcheck
