// Unit tests of the cores' support functions (detail/support.hpp) and Shape::support: for many
// directions the returned point maximises the dot product, checked against brute force written
// here (all input points of a hull, all corners of a box, a dense sampling of a cylinder's rims
// and its analytic maximum); returned vertex indices give the point back through vertex();
// hill climbing (hulls from ConvexHull::kHillClimbingThreshold vertices) agrees with the linear
// scan from every start; and edge cases: zero direction, axis directions, exactly tied vertices.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <hullcheck/core/convex_hull.hpp>
#include <hullcheck/core/shape.hpp>
#include <vector>

#include "detail/support.hpp"
#include "oracles.hpp"
#include "rng.hpp"

namespace hullcheck::detail {
namespace {

using Eigen::Vector3d;

// Directions: random unit and scaled vectors, the six axis directions, diagonals.
std::vector<Vector3d> directions(std::uint64_t seed, int random_count) {
  oracle::Rng rng(seed);
  std::vector<Vector3d> out;
  for (int i = 0; i < 3; ++i) {
    out.push_back(Vector3d::Unit(i));
    out.push_back(-Vector3d::Unit(i));
  }
  out.push_back(Vector3d(1, 1, 1));
  out.push_back(Vector3d(-1, 1, 0));
  out.push_back(Vector3d(0, -1e-300, 1));
  for (int i = 0; i < random_count; ++i) out.push_back(rng.unit_vector() * rng.uniform(1e-3, 1e3));
  return out;
}

// Largest dot product of d over a point set (brute force).
double brute_max(const std::vector<Vector3d>& points, const Vector3d& d) {
  double best = -INFINITY;
  for (const Vector3d& p : points) best = std::max(best, p.dot(d));
  return best;
}

// The point and sphere core: always the origin, vertex 0.
TEST(SupportPointCore, AlwaysTheOrigin) {
  const PointCore core;
  for (const Vector3d& d : directions(1, 20)) {
    int index = -1;
    EXPECT_EQ(core.support(d, index), Vector3d::Zero());
    EXPECT_EQ(index, 0);
  }
  EXPECT_EQ(core.vertex(0), Vector3d::Zero());
}

// Segment and box cores: the maximum over their end points / eight corners (enumerated here,
// not through vertex()), and the index names the returned point.
TEST(SupportSegmentAndBoxCores, MaximiseOverTheirVertices) {
  const SegmentCore segment{0.7};
  const std::vector<Vector3d> ends = {Vector3d(0, 0, -0.7), Vector3d(0, 0, 0.7)};
  const BoxCore box{Vector3d(0.5, 1.5, 2.5)};
  std::vector<Vector3d> corners;
  for (const double x : {-0.5, 0.5}) {
    for (const double y : {-1.5, 1.5}) {
      for (const double z : {-2.5, 2.5}) corners.emplace_back(x, y, z);
    }
  }
  for (const Vector3d& d : directions(2, 500)) {
    int index = -1;
    const Vector3d p = segment.support(d, index);
    EXPECT_EQ(p.dot(d), brute_max(ends, d)) << d.transpose();
    ASSERT_TRUE(index == 0 || index == 1);
    EXPECT_EQ(segment.vertex(index), p);
    index = -1;
    const Vector3d q = box.support(d, index);
    EXPECT_EQ(q.dot(d), brute_max(corners, d)) << d.transpose();
    ASSERT_TRUE(index >= 0 && index < 8);
    EXPECT_EQ(box.vertex(index), q);
  }
  // vertex() by sign bits: bit 0 +x, bit 1 +y, bit 2 +z.
  EXPECT_EQ(box.vertex(0), Vector3d(-0.5, -1.5, -2.5));
  EXPECT_EQ(box.vertex(6), Vector3d(-0.5, 1.5, 2.5));
  // Zero direction: some vertex, named by its index.
  int index = -1;
  const Vector3d z = box.support(Vector3d::Zero(), index);
  EXPECT_EQ(box.vertex(index), z);
}

// Cylinder core: the analytic maximum r |d_xy| + h |d_z|, never beaten by 4096 points of each
// rim, and the point lies on the cylinder; along the axis, a point of the cap.
TEST(SupportCylinderCore, AnalyticMaximumAndDenseRims) {
  const CylinderCore core{0.8, 1.3};
  std::vector<Vector3d> rims;
  for (int i = 0; i < 4096; ++i) {
    const double t = 2.0 * M_PI * i / 4096;
    rims.emplace_back(0.8 * std::cos(t), 0.8 * std::sin(t), 1.3);
    rims.emplace_back(0.8 * std::cos(t), 0.8 * std::sin(t), -1.3);
  }
  for (const Vector3d& d : directions(3, 300)) {
    int index = 42;
    const Vector3d p = core.support(d, index);
    const double analytic = 0.8 * std::hypot(d.x(), d.y()) + 1.3 * std::abs(d.z());
    const double scale = d.norm();
    EXPECT_NEAR(p.dot(d), analytic, 1e-14 * scale) << d.transpose();
    EXPECT_GE(p.dot(d), brute_max(rims, d) - 1e-14 * scale) << d.transpose();
    EXPECT_LE(std::hypot(p.x(), p.y()), 0.8 * (1 + 1e-15));
    EXPECT_EQ(std::abs(p.z()), 1.3);
    EXPECT_EQ(index, 42);  // a curved core leaves the index alone
  }
  int index = 0;
  EXPECT_EQ(core.support(Vector3d(0, 0, -2), index), Vector3d(0, 0, -1.3));
  EXPECT_EQ(core.support(Vector3d(3, 0, 0), index), Vector3d(0.8, 0, 1.3));
  const Vector3d zero = core.support(Vector3d::Zero(), index);
  EXPECT_TRUE(zero.allFinite());
  EXPECT_EQ(std::abs(zero.z()), 1.3);
}

// Checks every support answer of a hull: maximum over all input points, index maps back, and
// the answer agrees with the linear scan; returns the number of checks.
int check_hull(const std::vector<Vector3d>& points, std::uint64_t seed, int random_count) {
  const ConvexHull hull(points);
  const HullCore core{&hull.data()};
  const HullData& h = hull.data();
  double extent = 0.0;
  for (const Vector3d& p : points) extent = std::max(extent, p.norm());
  int checks = 0;
  for (const Vector3d& d : directions(seed, random_count)) {
    const double slack = 1e-13 * extent * d.norm();
    int index = -1;
    const Vector3d p = core.support(d, index);
    EXPECT_TRUE(index >= 0 && index < core.vertex_count());
    EXPECT_EQ(core.vertex(index), p);
    const double best = brute_max(points, d);
    EXPECT_GE(p.dot(d), best - slack) << "n = " << points.size() << ", d = " << d.transpose();
    const int scanned = scan_support_index(h, d);
    EXPECT_GE(core.vertex(scanned).dot(d), best - slack);
    EXPECT_EQ(hull.support_index(d), index);
    // support_near: any hint (none, out of range, valid) gives a maximiser too.
    for (const int hint : {-1, core.vertex_count(), 7 % core.vertex_count()}) {
      int near = -1;
      const Vector3d q = support_near(core, d, hint, near);
      EXPECT_EQ(core.vertex(near), q);
      EXPECT_GE(q.dot(d), best - slack) << "hint " << hint;
    }
    ++checks;
  }
  return checks;
}

// Hulls below the hill-climbing threshold (linear scan), at it and above (hill climbing), with
// interior points (not vertices) in the input: the brute-force maximum over the input points.
TEST(SupportHullCore, MaximisesOverAllInputPoints) {
  oracle::Rng rng(4);
  const int n_threshold = static_cast<int>(ConvexHull::kHillClimbingThreshold);
  for (const int n : {4, 10, n_threshold - 1, n_threshold, n_threshold + 1, 60, 400}) {
    SCOPED_TRACE(testing::Message() << "n = " << n);
    std::vector<Vector3d> points = oracle::random_hull_points(100 + n, n, 2.0);
    ASSERT_EQ(ConvexHull(points).vertex_count(), static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) points.push_back(rng.in_box(0.3));  // inside: no new vertex
    EXPECT_GT(check_hull(points, 200 + n, 400), 400);
  }
}

// Hill climbing agrees with the linear scan from every start vertex (not only the cube map's).
TEST(SupportHullCore, HillClimbingFromAnyStartAgreesWithTheScan) {
  for (const int n : {static_cast<int>(ConvexHull::kHillClimbingThreshold), 80}) {
    const ConvexHull hull(oracle::random_hull_points(300 + n, n));
    const HullData& h = hull.data();
    for (const Vector3d& d : directions(400 + n, 60)) {
      const double best = h.vertices[scan_support_index(h, d)].dot(d);
      for (int start = 0; start < h.vertex_count; ++start) {
        const int climbed = climb_support_index(h, d, start);
        ASSERT_TRUE(climbed >= 0 && climbed < h.vertex_count);
        EXPECT_GE(h.vertices[climbed].dot(d), best - 1e-14 * d.norm())
            << "n = " << n << ", start " << start << ", d = " << d.transpose();
      }
    }
  }
}

// The cube map: each cell's centre direction falls in that cell, and the hill-climbing start
// table holds a support vertex of that direction (brute force over the vertices).
TEST(SupportHullCore, CubeMapCellsAndStartTable) {
  const ConvexHull hull(oracle::random_hull_points(5, 100));
  const HullData& h = hull.data();
  constexpr int kCellCount = 6 * HullData::kCells * HullData::kCells;
  ASSERT_EQ(h.start_table.size(), static_cast<std::size_t>(kCellCount));
  for (int cell = 0; cell < kCellCount; ++cell) {
    const Vector3d d = cube_map_direction(cell);
    EXPECT_EQ(cube_map_cell(d), cell);
    EXPECT_EQ(cube_map_cell(3.5 * d), cell);
    EXPECT_GE(h.vertices[h.start_table[cell]].dot(d), brute_max(h.vertices, d) - 1e-14);
  }
  EXPECT_EQ(cube_map_cell(Vector3d::Zero()), 0);
}

// Exact ties: a prism over a regular 30-gon (60 vertices: hill climbing) has 30 vertices tied
// along +-z and edges tied along each side's normal; the cube has faces and edges tied along
// axis and diagonal directions. The value is the exact maximum (coordinates exact in double).
TEST(SupportHullCore, ExactlyTiedVerticesAndAxisDirections) {
  std::vector<Vector3d> prism;
  for (int i = 0; i < 30; ++i) {
    const double t = 2.0 * M_PI * i / 30;
    prism.emplace_back(std::cos(t), std::sin(t), 0.5);
    prism.emplace_back(std::cos(t), std::sin(t), -0.5);
  }
  const ConvexHull p(prism);
  ASSERT_EQ(p.vertex_count(), 60u);
  const HullCore pc{&p.data()};
  int index = -1;
  EXPECT_EQ(pc.support(Vector3d(0, 0, 1), index).z(), 0.5);
  EXPECT_EQ(pc.support(Vector3d(0, 0, -3), index).z(), -0.5);
  EXPECT_EQ(pc.support(Vector3d(1, 0, 0), index).x(), 1.0);
  EXPECT_EQ(pc.support(Vector3d(0.2, 0, 1), index), Vector3d(1, 0, 0.5));
  check_hull(prism, 6, 300);
  pc.support(Vector3d(0, NAN, 1), index);  // NaN: no out-of-range index (hill climbing)
  EXPECT_TRUE(index >= 0 && index < 60);

  const std::vector<Vector3d> cube = {
      Vector3d(-1, -1, -1), Vector3d(1, -1, -1), Vector3d(-1, 1, -1), Vector3d(1, 1, -1),
      Vector3d(-1, -1, 1),  Vector3d(1, -1, 1),  Vector3d(-1, 1, 1),  Vector3d(1, 1, 1)};
  const ConvexHull c(cube);
  const HullCore cc{&c.data()};
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      EXPECT_EQ(cc.support(sign * Vector3d::Unit(axis), index)(axis), sign);
    }
  }
  EXPECT_EQ(cc.support(Vector3d(1, 1, 0), index).head<2>(), Eigen::Vector2d(1, 1));
  const Vector3d zero = cc.support(Vector3d::Zero(), index);  // zero direction: some vertex
  EXPECT_EQ(cc.vertex(index), zero);
  // A NaN direction must not index out of range.
  cc.support(Vector3d(NAN, 1, 0), index);
  EXPECT_TRUE(index >= 0 && index < 8);
}

// Flat hulls: a 40-gon (hill climbing over a polygon's edges) and a collinear set.
TEST(SupportHullCore, FlatAndCollinearHulls) {
  std::vector<Vector3d> polygon;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.3, Vector3d(1, -2, 0.5).normalized()).matrix();
  for (int i = 0; i < 40; ++i) {
    const double t = 2.0 * M_PI * (i + 0.1) / 40;
    polygon.push_back(r * Vector3d(1.5 * std::cos(t), std::sin(t), 0.0));
  }
  EXPECT_EQ(ConvexHull(polygon).dimension(), 2);
  check_hull(polygon, 7, 500);
  const std::vector<Vector3d> line = {Vector3d(0, 0, 0), Vector3d(1, 2, 3), Vector3d(0.5, 1, 1.5),
                                      Vector3d(-1, -2, -3)};
  check_hull(line, 8, 100);
}

// Shape::support (public): the core's support point plus the radius (sphere and capsule radius,
// margin) along the unit direction: its value is the analytic support value, and a zero
// direction gives the core's point.
TEST(SupportShape, PublicSupportAddsTheRadius) {
  const std::vector<Vector3d> points = oracle::random_hull_points(9, 30);
  struct Case {
    Shape shape;
    double radius;
    std::vector<Vector3d> core_points;  // empty: the cylinder (analytic)
  };
  const std::vector<Case> cases = {
      {Shape(Sphere(0.7)).inflated(0.1), 0.8, {Vector3d::Zero()}},
      {Capsule(0.3, 2.0), 0.3, {Vector3d(0, 0, -1), Vector3d(0, 0, 1)}},
      {Shape(Box(2, 4, 6)).inflated(0.25), 0.25, {}},
      {Shape(Cylinder(0.5, 3.0)).inflated(0.2), 0.2, {}},
      {Shape(ConvexHull(points)).inflated(0.05), 0.05, points},
  };
  std::vector<Vector3d> box;
  for (int i = 0; i < 8; ++i) box.emplace_back(i & 1 ? 1 : -1, i & 2 ? 2 : -2, i & 4 ? 3 : -3);
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    for (const Vector3d& d : directions(10 + k, 200)) {
      const double core_max = k == 2   ? brute_max(box, d)
                              : k == 3 ? 0.5 * std::hypot(d.x(), d.y()) + 1.5 * std::abs(d.z())
                                       : brute_max(c.core_points, d);
      const double expected = core_max + c.radius * d.norm();
      EXPECT_NEAR(c.shape.support(d).dot(d), expected, 1e-13 * (1 + std::abs(expected)))
          << "shape " << k << ", d = " << d.transpose();
    }
    EXPECT_TRUE(c.shape.support(Vector3d::Zero()).allFinite()) << "shape " << k;
  }
  EXPECT_EQ(Shape(Sphere(2.0)).support(Vector3d::Zero()), Vector3d::Zero());
}

}  // namespace
}  // namespace hullcheck::detail
