// ProximityPair: Casalino section 4 state machine, caching, invalidation and warm start.
#include <gtest/gtest.h>

#include <hullcheck/core.hpp>
#include <random>

#include "test_support.hpp"

namespace hullcheck {
namespace {

using test::translation;

ConvexHull ellipsoid_hull(int n) {
  std::mt19937_64 rng(n);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    points.push_back(Eigen::Vector3d(1.0, 0.7, 0.5).asDiagonal() * p);
  }
  return ConvexHull(points);
}

TEST(ProximityPair, QueriesBeforeShapesThrow) {
  ProximityPair pair;
  EXPECT_THROW(pair.in_collision(), std::logic_error);
  pair.set_shape_a(Sphere(1.0));
  EXPECT_THROW(pair.distance(), std::logic_error);
}

TEST(ProximityPair, MatchesFreeFunctionsInAnyOrder) {
  const ConvexHull hull = ellipsoid_hull(100);
  for (double x : {0.5, 1.0, 2.5}) {
    for (int order = 0; order < 3; ++order) {
      ProximityPair pair;
      pair.set_shape_a(hull, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0.2, 0.3));
      pair.set_shape_b(Box(0.5, 0.5, 0.5), Eigen::Vector3d(x, 0.1, 0), Eigen::Vector3d(0, 0, 0.4));
      const Eigen::Isometry3d pa = pose_from_xyz_angles({0, 0, 0}, {0.1, 0.2, 0.3});
      const Eigen::Isometry3d pb = pose_from_xyz_angles({x, 0.1, 0}, {0, 0, 0.4});
      if (order == 1) pair.penetration();
      if (order == 2) pair.distance();
      EXPECT_EQ(pair.in_collision(), intersect(hull, pa, Box(0.5, 0.5, 0.5), pb));
      EXPECT_NEAR(pair.distance().distance, distance(hull, pa, Box(0.5, 0.5, 0.5), pb).distance,
                  1e-12);
      EXPECT_NEAR(pair.penetration().depth, penetration(hull, pa, Box(0.5, 0.5, 0.5), pb).depth,
                  1e-12);
      EXPECT_NEAR(pair.signed_distance().signed_distance,
                  signed_distance(hull, pa, Box(0.5, 0.5, 0.5), pb).signed_distance, 1e-12);
    }
  }
}

TEST(ProximityPair, CachesUntilAPoseOrShapeIsSet) {
  ProximityPair pair;
  pair.set_shape_a(Sphere(1.0));
  pair.set_shape_b(Sphere(1.0), translation(3, 0, 0));
  EXPECT_NEAR(pair.distance().distance, 1.0, 1e-12);
  EXPECT_FALSE(pair.last_was_cached());
  EXPECT_GT(pair.last_iterations(), 0);
  pair.distance();
  EXPECT_TRUE(pair.last_was_cached());
  EXPECT_EQ(pair.last_iterations(), 0);
  EXPECT_FALSE(pair.in_collision());
  EXPECT_TRUE(pair.last_was_cached());
  EXPECT_EQ(pair.penetration().depth, 0.0);  // apart: known without EPA
  EXPECT_TRUE(pair.last_was_cached());
  pair.set_pose_b(translation(1.5, 0, 0));
  EXPECT_TRUE(pair.in_collision());
  EXPECT_FALSE(pair.last_was_cached());
  EXPECT_NEAR(pair.penetration().depth, 0.5, 1e-12);
  EXPECT_FALSE(pair.last_was_cached());
  EXPECT_NEAR(pair.signed_distance().signed_distance, -0.5, 1e-12);
  EXPECT_TRUE(pair.last_was_cached());  // penetration's GJK+EPA run answered it
  pair.set_shape_b(Sphere(0.25), translation(1.5, 0, 0));
  EXPECT_NEAR(pair.distance().distance, 0.25, 1e-12);
}

TEST(ProximityPair, WarmStartNeedsFewerIterationsOnSmallMotions) {
  const ConvexHull a = ellipsoid_hull(256), b = ellipsoid_hull(257);
  ProximityPair pair;
  pair.set_shape_a(a);
  pair.set_shape_b(b, translation(2.5, 0, 0));
  long warm_iterations = 0, cold_iterations = 0;
  for (int step = 0; step < 200; ++step) {
    // B moves by 1% of its size per step along a circle around A.
    const double angle = 0.02 * step;
    const Eigen::Isometry3d pose =
        pose_from_xyz_angles({2.5 * std::cos(angle), 2.5 * std::sin(angle), 0.1}, {0, 0, angle});
    pair.set_pose_b(pose);
    const double warm = pair.distance().distance;
    warm_iterations += pair.last_iterations();
    const DistanceResult cold = distance(a, Eigen::Isometry3d::Identity(), b, pose);
    cold_iterations += cold.iterations;
    ASSERT_NEAR(warm, cold.distance, 1e-9);
  }
  EXPECT_LT(warm_iterations, cold_iterations);
  RecordProperty("warm_iterations", static_cast<int>(warm_iterations));
  RecordProperty("cold_iterations", static_cast<int>(cold_iterations));
}

}  // namespace
}  // namespace hullcheck

namespace hullcheck {
namespace {

// The warm start re-evaluates the last simplex from vertex indices (hulls, boxes, capsules,
// spheres) or reuses only the direction (cylinders); either way the answers must equal the cold
// free functions' on every pose, through contact and back.
TEST(ProximityPair, WarmStartedAnswersEqualColdOnesForEveryShapeKind) {
  const std::vector<Shape> shapes = {ellipsoid_hull(60),
                                     ellipsoid_hull(300),
                                     Box(0.8, 0.5, 0.3),
                                     Capsule(0.2, 0.6),
                                     Sphere(0.3),
                                     Cylinder(0.25, 0.7),
                                     Shape(Box(0.4, 0.4, 0.4)).inflated(0.05)};
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    for (std::size_t j = 0; j < shapes.size(); ++j) {
      ProximityPair pair;
      pair.set_shape_a(shapes[i]);
      pair.set_shape_b(shapes[j], translation(2.0, 0, 0));
      for (int step = 0; step < 120; ++step) {
        const double x = 2.0 - 0.02 * step;  // through contact to deep overlap
        const Eigen::Isometry3d pose = pose_from_xyz_angles({x, 0.1 * std::sin(0.1 * step), 0.05},
                                                            {0.01 * step, 0, 0.02 * step});
        pair.set_pose_b(pose);
        const Eigen::Isometry3d id = Eigen::Isometry3d::Identity();
        const double tol = 1e-9 * 2.0;
        if (step % 3 == 0) {
          ASSERT_EQ(pair.in_collision(), intersect(shapes[i], id, shapes[j], pose))
              << i << j << step;
        }
        const SignedDistanceResult cold = signed_distance(shapes[i], id, shapes[j], pose);
        const SignedDistanceResult& warm = pair.signed_distance();
        // Cylinders are curved: both answers are within tolerance of the truth.
        const double allowed = (i == 5 || j == 5) ? 1e-7 : tol;
        ASSERT_NEAR(warm.signed_distance, cold.signed_distance, allowed)
            << i << " " << j << " " << step;
        ASSERT_NEAR(pair.distance().distance, std::max(0.0, cold.signed_distance), allowed);
      }
    }
  }
}

}  // namespace
}  // namespace hullcheck
