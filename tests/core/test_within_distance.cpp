// within_distance: is the distance between two shapes at most a given one? Checked against
// independent answers: the brute-force distance of hull pairs (tests/oracles, over hull
// features), with and without a margin on either shape, at distances on both sides of the
// oracle's (outside the tolerance band); spheres and boxes analytically; bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <hullcheck/core.hpp>
#include <limits>
#include <random>
#include <vector>

#include "oracles.hpp"
#include "test_support.hpp"

namespace hullcheck {
namespace {

TEST(WithinDistance, HullPairsAgreeWithBruteForce) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int near = 0, far = 0;
  for (const double size : {0.01, 1.0, 100.0}) {
    const auto pairs =
        oracle::make_hull_pairs(static_cast<std::uint64_t>(size * 1000) + 7, 150, 12, 0.3, size);
    for (const oracle::HullPair& pair : pairs) {
      const auto truth = oracle::brute_force_distance(oracle::transformed(pair.a, pair.pose_a),
                                                      oracle::transformed(pair.b, pair.pose_b));
      const double d = truth.overlapping ? 0.0 : truth.distance;
      // Margins on A, B, both or neither: the distance shrinks by their sum (not below 0).
      const double margin_a = rng() % 2 == 0 ? 0.0 : 0.05 * size * unit(rng);
      const double margin_b = rng() % 2 == 0 ? 0.0 : 0.05 * size * unit(rng);
      const Shape a = Shape(ConvexHull(pair.a)).inflated(margin_a);
      const Shape b = Shape(ConvexHull(pair.b)).inflated(margin_b);
      const double grown = std::max(0.0, d - margin_a - margin_b);
      const double band = 1e-8 * 4.0 * size;  // scale: hulls of about `size`, poses 2 x apart
      for (const double c : {0.0, 0.5 * grown, grown - 2.0 * band, grown + 2.0 * band,
                             2.0 * grown + band, 3.0 * size * unit(rng)}) {
        if (c < 0.0 || std::abs(c - grown) <= band) continue;
        const bool expected = c > grown;
        ASSERT_EQ(within_distance(a, pair.pose_a, b, pair.pose_b, c), expected)
            << "size " << size << ", distance " << grown << ", asked " << c;
        // Symmetric in A and B.
        ASSERT_EQ(within_distance(b, pair.pose_b, a, pair.pose_a, c), expected);
        (expected ? near : far) += 1;
      }
    }
  }
  EXPECT_GT(near, 500);
  EXPECT_GT(far, 500);
}

TEST(WithinDistance, SpheresAndBoxesAnalytically) {
  // Spheres of radii 0.3 and 0.2, centres 1 apart: 0.5 between them.
  const Shape small = Sphere(0.2), large = Sphere(0.3);
  const Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d one = test::translation(1.0, 0.0, 0.0);
  EXPECT_FALSE(within_distance(large, origin, small, one, 0.5 - 1e-6));
  EXPECT_TRUE(within_distance(large, origin, small, one, 0.5 + 1e-6));
  EXPECT_TRUE(within_distance(large, origin, small, test::translation(0.4, 0.0, 0.0), 0.0));
  // A unit box and a point-like sphere 0.2 beyond a corner along the diagonal: distance 0.2.
  const Shape box = Box(1.0, 1.0, 1.0), dot = Sphere(1e-9);
  const Eigen::Vector3d corner = Eigen::Vector3d::Constant(0.5);
  const Eigen::Vector3d beyond = corner + 0.2 * Eigen::Vector3d::Ones().normalized();
  const Eigen::Isometry3d at = test::translation(beyond.x(), beyond.y(), beyond.z());
  EXPECT_FALSE(within_distance(box, origin, dot, at, 0.2 - 1e-6));
  EXPECT_TRUE(within_distance(box, origin, dot, at, 0.2 + 1e-6));
  EXPECT_FALSE(within_distance(dot, at, box, origin, 0.2 - 1e-6));
  EXPECT_TRUE(within_distance(dot, at, box, origin, 0.2 + 1e-6));
}

TEST(WithinDistance, BadInputIsAnError) {
  const Shape a = Sphere(1.0);
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (const double bad : {-1e-3, std::nan(""), std::numeric_limits<double>::infinity(), 2e6}) {
    const std::string message =
        test::input_error_of([&] { within_distance(a, pose, a, pose, bad); });
    test::expect_contains(message, {"within_distance", "distance"});
  }
  Eigen::Isometry3d sheared = pose;
  sheared.linear()(0, 1) = 0.5;
  EXPECT_THROW(within_distance(a, sheared, a, pose, 0.1), InputError);
}

}  // namespace
}  // namespace hullcheck
