// sphere_box_rows: one sphere against many oriented boxes, SIMD across the boxes. Checked
// against each box's closest point found independently (the centre taken into the box frame by
// the inverse pose, clamped to the half extents), for box counts that fill no, one or several
// 64-bit words, at the best SIMD target and forced down to scalar code.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "ball_tests_block.hpp"
#include "sphere_box_rows.hpp"

namespace hullcheck {
namespace {

struct TestBox {
  Eigen::Isometry3d pose;  // box frame -> world
  Eigen::Vector3d half;
};

// Signed gap from the sphere to the box as box_gap defines it: outside, the centre's distance
// to the box minus the radius; inside, minus the radius and the centre's depth below the
// nearest face.
double oracle_gap(const TestBox& box, const Eigen::Vector3d& c, double radius) {
  const Eigen::Vector3d local = box.pose.inverse() * c;
  const Eigen::Vector3d nearest = local.cwiseMax(-box.half).cwiseMin(box.half);
  const double outside = (local - nearest).norm();
  if (outside > 0.0) return outside - radius;
  return -(box.half - local.cwiseAbs()).minCoeff() - radius;
}

void check_counts(std::mt19937_64& rng, int* near_threshold) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), size(0.01, 0.5);
  for (const std::size_t count : {1u, 7u, 8u, 13u, 64u, 70u, 150u}) {
    std::vector<TestBox> boxes;
    std::vector<double> packed;
    for (std::size_t j = 0; j < count; ++j) {
      TestBox b{Eigen::Isometry3d::Identity(), Eigen::Vector3d(size(rng), size(rng), size(rng))};
      b.pose.linear() =
          Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized().matrix();
      b.pose.translation() = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      boxes.push_back(b);
      // ball_tests_block.hpp's packing: world-to-box rotation row by row, centre, half extents.
      const Eigen::Matrix3d to_box = b.pose.linear().transpose();
      for (int i = 0; i < 9; ++i) packed.push_back(to_box(i / 3, i % 3));
      for (int i = 0; i < 3; ++i) packed.push_back(b.pose.translation()[i]);
      for (int i = 0; i < 3; ++i) packed.push_back(b.half[i]);
    }
    const std::size_t padded = detail::box_rows_padded(count);
    ASSERT_EQ(padded % 8, 0u);
    ASSERT_GE(padded, count);
    const std::vector<double> rows = detail::pack_box_rows(packed.data(), count);
    ASSERT_EQ(rows.size(), detail::kBoxValues * padded);
    std::vector<std::uint64_t> bits((padded + 63) / 64);
    std::vector<double> gaps(padded);
    for (int trial = 0; trial < 40; ++trial) {
      const Eigen::Vector3d c = 1.3 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      const double radius = 0.3 * (unit(rng) + 1.0);
      const double slack = trial % 2 == 0 ? 0.0 : 1e-9;
      detail::sphere_clear_of_box_rows(rows.data(), padded, c.data(), radius, slack, bits.data());
      detail::sphere_box_row_gaps(rows.data(), padded, c.data(), radius, gaps.data());
      for (std::size_t j = 0; j < count; ++j) {
        const double truth = oracle_gap(boxes[j], c, radius);
        EXPECT_NEAR(gaps[j], truth, 1e-12) << "box " << j << " of " << count;
        const bool clear = (bits[j / 64] >> (j % 64)) & 1u;
        if (std::abs(truth - slack) < 1e-12) {
          ++*near_threshold;  // either verdict: within rounding of the threshold
          continue;
        }
        EXPECT_EQ(clear, truth > slack) << "box " << j << " of " << count;
      }
    }
  }
}

TEST(SphereBoxRows, AgreeWithClosestPoints) {
  std::mt19937_64 rng(20261208);
  int near_threshold = 0;
  check_counts(rng, &near_threshold);
  // The same with the SIMD forced down to plain scalar code (a CPU without AVX2).
  hwy::SetSupportedTargetsForTest(HWY_SCALAR);
  check_counts(rng, &near_threshold);
  hwy::SetSupportedTargetsForTest(0);
  EXPECT_LT(near_threshold, 5);
}

}  // namespace
}  // namespace hullcheck
