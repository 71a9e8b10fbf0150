// signed_distance_below: the signed distance when it is below a cutoff, else a proven lower
// bound >= the cutoff. Checked against the full signed_distance() (itself checked against the
// analytic and brute-force oracles in the other suites) on random hulls and primitives, with and
// without margins, cutoffs on both sides of the answer, apart and overlapping.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <hullcheck/core.hpp>
#include <limits>
#include <random>
#include <vector>

#include "test_support.hpp"

namespace hullcheck {
namespace {

using test::random_pose;

Shape random_shape(std::mt19937_64& rng, double size) {
  std::uniform_real_distribution<double> u(0.2, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  Shape shape = Sphere(size);
  switch (rng() % 5) {
    case 0: {
      const int n = 4 + static_cast<int>(rng() % 60);
      const Eigen::Vector3d axes(u(rng), u(rng), u(rng));
      std::vector<Eigen::Vector3d> points;
      for (int i = 0; i < n; ++i) {
        points.push_back(size *
                         axes.cwiseProduct(Eigen::Vector3d(normal(rng), normal(rng), normal(rng))));
      }
      shape = ConvexHull(points);
      break;
    }
    case 1:
      shape = Box(size * u(rng), size * u(rng), size * u(rng));
      break;
    case 2:
      shape = Sphere(size * u(rng));
      break;
    case 3:
      shape = Capsule(size * 0.5 * u(rng), 2.0 * size * u(rng));
      break;
    default:
      shape = Cylinder(size * u(rng), 2.0 * size * u(rng));
      break;
  }
  return rng() % 3 == 0 ? shape.inflated(0.1 * size * u(rng)) : shape;
}

TEST(SignedDistanceBelow, AgreesWithSignedDistanceOrProvesTheCutoff) {
  std::mt19937_64 rng(20261122);
  int early_stops = 0, early_overlapping = 0, exact = 0;
  for (int i = 0; i < 3000; ++i) {
    const double size = std::pow(10.0, static_cast<int>(i % 5) - 2);  // 1e-2 .. 1e2
    const Shape a = random_shape(rng, size), b = random_shape(rng, size);
    const Eigen::Isometry3d pa = random_pose(rng, 1.2 * size), pb = random_pose(rng, 1.2 * size);
    const SignedDistanceResult full = signed_distance(a, pa, b, pb);
    ASSERT_NE(full.status, Status::kAboveCutoff);
    const double tol = 1e-9 * std::max(a.bounding_radius(), b.bounding_radius());
    const double d = full.signed_distance;
    const double cutoffs[] = {d - 0.5 * size,
                              d - 1e-3 * size,
                              d + 1e-3 * size,
                              d + 0.5 * size,
                              0.0,
                              -size,
                              size,
                              std::numeric_limits<double>::infinity()};
    for (const double cutoff : cutoffs) {
      const SignedDistanceResult r = signed_distance_below(a, pa, b, pb, cutoff);
      if (r.status == Status::kAboveCutoff) {
        // A proven lower bound at or above the cutoff: never above the truth.
        EXPECT_GE(r.signed_distance, cutoff - tol) << i << " cutoff " << cutoff;
        EXPECT_LE(r.signed_distance, d + tol) << i << " cutoff " << cutoff;
        EXPECT_GE(d, cutoff - tol) << i << " stopped although below the cutoff";
        ++early_stops;
        early_overlapping += d < 0.0 ? 1 : 0;
      } else {
        // Below the cutoff (or within tolerance of it): the full answer.
        EXPECT_NEAR(r.signed_distance, d, tol) << i << " cutoff " << cutoff;
        EXPECT_LT((r.point_b - r.point_a - r.signed_distance * r.normal).norm(), 10 * tol) << i;
        ++exact;
      }
      if (d < cutoff - tol) {
        EXPECT_NE(r.status, Status::kAboveCutoff) << i;
      }
    }
  }
  // Both outcomes occur, including early stops inside EPA or the boolean test on overlaps.
  EXPECT_GT(early_stops, 3000);
  EXPECT_GT(early_overlapping, 300);
  EXPECT_GT(exact, 3000);
}

// A caller's warm start is only a starting point: garbage in it (indices out of range,
// negative or too many, a non-finite direction) must give the cold answer, never a read out of
// bounds or a different distance. Analytic answer: unit cube at the origin, cube at x = 3,
// distance 2.
TEST(SignedDistanceBelow, GarbageWarmStartGivesTheColdAnswer) {
  const Shape cube(Box(1, 1, 1));
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i)
    corners.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  const Shape hull{ConvexHull(corners)};
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation().x() = 3.0;
  const double inf = std::numeric_limits<double>::infinity();
  for (int garbage = 0; garbage < 4; ++garbage) {
    WarmStart warm;
    warm.valid = true;
    warm.simplex_size = garbage == 2 ? 9 : 3;
    for (int i = 0; i < 4; ++i) {
      warm.index_a[i] = garbage == 0 ? 1000 + i : -7;
      warm.index_b[i] = garbage == 1 ? 1 << 30 : i;
    }
    warm.direction = garbage == 3 ? Eigen::Vector3d(NAN, 0, 0) : Eigen::Vector3d(0, 1, 0);
    const SignedDistanceResult r =
        signed_distance_below(hull, Eigen::Isometry3d::Identity(), hull, far, inf, warm);
    EXPECT_EQ(r.status, Status::kConverged) << garbage;
    EXPECT_NEAR(r.signed_distance, 2.0, 1e-9) << garbage;
    const SignedDistanceResult boxes =
        signed_distance_below(cube, Eigen::Isometry3d::Identity(), cube, far, inf, warm);
    EXPECT_NEAR(boxes.signed_distance, 2.0, 1e-9) << garbage;
  }
}

TEST(SignedDistanceBelow, NanCutoffIsAnError) {
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  EXPECT_THROW(signed_distance_below(Sphere(1.0), identity, Sphere(1.0), identity, NAN),
               InputError);
}

}  // namespace
}  // namespace hullcheck
