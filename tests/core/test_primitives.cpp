// Analytic answers for exact primitives: sphere, box, capsule, cylinder, margins.
#include <gtest/gtest.h>

#include <hullcheck/core.hpp>

#include "test_support.hpp"

namespace hullcheck {
namespace {

using test::random_pose;
using test::translation;

constexpr double kRel = 1e-9;

TEST(SphereSphere, RandomPairsMatchClosedForm) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> radius(0.01, 2.0);
  for (int i = 0; i < 2000; ++i) {
    const double scale = std::pow(10.0, (i % 7) - 3);  // 1e-3 .. 1e3
    const double ra = radius(rng) * scale, rb = radius(rng) * scale;
    const Eigen::Isometry3d pa = random_pose(rng, 2 * scale), pb = random_pose(rng, 2 * scale);
    const Eigen::Vector3d c = pb.translation() - pa.translation();
    const double expected = c.norm() - ra - rb;
    const double tol = kRel * std::max(ra, rb);
    const SignedDistanceResult s = signed_distance(Sphere(ra), pa, Sphere(rb), pb);
    ASSERT_NEAR(s.signed_distance, expected, tol) << i;
    EXPECT_TRUE(s.normal.isApprox(c.normalized(), 1e-9)) << i;
    EXPECT_NEAR((s.point_a - pa.translation()).norm(), ra, tol);
    EXPECT_NEAR((s.point_b - pb.translation()).norm(), rb, tol);
    EXPECT_LT((s.point_b - s.point_a - s.signed_distance * s.normal).norm(), tol);
    const DistanceResult d = distance(Sphere(ra), pa, Sphere(rb), pb);
    EXPECT_NEAR(d.distance, std::max(0.0, expected), tol);
    const PenetrationResult p = penetration(Sphere(ra), pa, Sphere(rb), pb);
    EXPECT_NEAR(p.depth, std::max(0.0, -expected), tol);
    if (std::abs(expected) > tol) {
      EXPECT_EQ(intersect(Sphere(ra), pa, Sphere(rb), pb), expected < 0) << i;
    }
  }
}

TEST(SphereSphere, ConcentricHasDepthOfRadiusSum) {
  const PenetrationResult p =
      penetration(Sphere(1.0), translation(1, 2, 3), Sphere(0.5), translation(1, 2, 3));
  EXPECT_NEAR(p.depth, 1.5, 1e-12);
  EXPECT_NEAR(p.normal.norm(), 1.0, 1e-12);
}

/// Distance from a point to an axis-aligned box (negative inside: minus the distance to the
/// nearest face).
double point_box_signed_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& half) {
  const Eigen::Vector3d q = p.cwiseAbs() - half;
  if ((q.array() <= 0.0).all()) return q.maxCoeff();
  return q.cwiseMax(0.0).norm();
}

TEST(SphereBox, RandomPairsMatchClosedForm) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-2.0, 2.0), size(0.1, 2.0), radius(0.05, 1.0);
  for (int i = 0; i < 3000; ++i) {
    const Box box(size(rng), size(rng), size(rng));
    const double r = radius(rng);
    const Eigen::Isometry3d pose_box = random_pose(rng, 1.0);
    const Eigen::Vector3d centre_local(u(rng), u(rng), u(rng));
    const Eigen::Isometry3d pose_sphere(Eigen::Translation3d(pose_box * centre_local));
    const double expected = point_box_signed_distance(centre_local, box.half_extents) - r;
    const double tol = kRel * std::max(box.half_extents.norm(), r);
    const SignedDistanceResult s = signed_distance(box, pose_box, Sphere(r), pose_sphere);
    ASSERT_NEAR(s.signed_distance, expected, tol) << i;
    EXPECT_EQ(s.status, Status::kConverged);
    if (std::abs(expected) > tol) {
      EXPECT_EQ(intersect(box, pose_box, Sphere(r), pose_sphere), expected < 0) << i;
    }
  }
}

TEST(BoxBox, AlignedMatchesPerAxisGaps) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0), size(0.1, 2.0);
  for (int i = 0; i < 3000; ++i) {
    const Box a(size(rng), size(rng), size(rng)), b(size(rng), size(rng), size(rng));
    const Eigen::Vector3d c(u(rng), u(rng), u(rng));
    const Eigen::Vector3d half = a.half_extents + b.half_extents;
    // The Minkowski difference of aligned boxes is the box of half extents ha + hb.
    const double expected = point_box_signed_distance(c, half);
    const Eigen::Isometry3d common = random_pose(rng, 5.0);  // rigid move of both
    const Eigen::Isometry3d pa = common, pb = common * translation(c.x(), c.y(), c.z());
    const double tol = kRel * 2.0 * half.norm();
    const SignedDistanceResult s = signed_distance(a, pa, b, pb);
    ASSERT_NEAR(s.signed_distance, expected, tol) << i;
    EXPECT_EQ(s.status, Status::kConverged) << i;
    EXPECT_LT((s.point_b - s.point_a - s.signed_distance * s.normal).norm(), tol);
    if (std::abs(expected) > tol) {
      EXPECT_EQ(intersect(a, pa, b, pb), expected < 0) << i;
    }
  }
}

TEST(BoxBox, RotatedEdgeFacingFace) {
  // B is a cube of half side h turned 45 degrees about z: its vertical edge faces A's +x face.
  const double h = 0.5;
  for (double gap : {1.0, 0.1, 1e-6, -1e-6, -0.05, -0.2}) {
    const double d = 0.5 + h * std::sqrt(2.0) + gap;
    const Eigen::Isometry3d pb = pose_from_xyz_angles({d, 0.1, 0.0}, {0, 0, M_PI / 4});
    const SignedDistanceResult s =
        signed_distance(Box(1, 1, 1), Eigen::Isometry3d::Identity(), Box(2 * h, 2 * h, 2 * h), pb);
    EXPECT_NEAR(s.signed_distance, gap, 1e-12) << gap;
    EXPECT_TRUE(s.normal.isApprox(Eigen::Vector3d::UnitX(), 1e-9)) << s.normal.transpose();
  }
}

/// Distance between segments p0 + s*(p1-p0) and q0 + t*(q1-q0), by dense sampling refined by
/// ternary search (independent of GJK).
double segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                        const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  auto best_t = [&](const Eigen::Vector3d& p) {
    double lo = 0, hi = 1;
    for (int k = 0; k < 200; ++k) {
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      if ((q0 + m1 * (q1 - q0) - p).norm() < (q0 + m2 * (q1 - q0) - p).norm())
        hi = m2;
      else
        lo = m1;
    }
    return (q0 + 0.5 * (lo + hi) * (q1 - q0) - p).norm();
  };
  double lo = 0, hi = 1;
  for (int k = 0; k < 200; ++k) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (best_t(p0 + m1 * (p1 - p0)) < best_t(p0 + m2 * (p1 - p0)))
      hi = m2;
    else
      lo = m1;
  }
  return best_t(p0 + 0.5 * (lo + hi) * (p1 - p0));
}

TEST(CapsuleCapsule, MatchesSegmentDistance) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> radius(0.05, 0.5), length(0.0, 2.0);
  for (int i = 0; i < 500; ++i) {
    const Capsule a(radius(rng), length(rng)), b(radius(rng), length(rng));
    const Eigen::Isometry3d pa = random_pose(rng, 1.0), pb = random_pose(rng, 1.0);
    const Eigen::Vector3d a0 = pa * Eigen::Vector3d(0, 0, -a.half_length);
    const Eigen::Vector3d a1 = pa * Eigen::Vector3d(0, 0, a.half_length);
    const Eigen::Vector3d b0 = pb * Eigen::Vector3d(0, 0, -b.half_length);
    const Eigen::Vector3d b1 = pb * Eigen::Vector3d(0, 0, b.half_length);
    const double core = segment_distance(a0, a1, b0, b1);
    const double expected = core - a.radius - b.radius;
    const double tol = 1e-9 * 2.0;
    if (core < 1e-6) continue;  // crossing cores: depth is not the segment formula
    const SignedDistanceResult s = signed_distance(a, pa, b, pb);
    ASSERT_NEAR(s.signed_distance, expected, tol) << i;
    EXPECT_EQ(intersect(a, pa, b, pb), expected < 0) << i;
  }
}

TEST(CapsuleCapsule, ParallelAndCrossed) {
  // Parallel, side by side.
  EXPECT_NEAR(
      distance(Capsule(0.1, 1.0), translation(0, 0, 0), Capsule(0.2, 1.0), translation(0.5, 0, 0.3))
          .distance,
      0.2, 1e-12);
  // Crossed at right angles (axes along x and y), 0.1 apart in z: depth 0.3 - 0.1.
  const Eigen::Isometry3d along_x = pose_from_xyz_angles({0, 0, 0}, {0, M_PI / 2, 0});
  const Eigen::Isometry3d along_y = pose_from_xyz_angles({0, 0, 0.1}, {M_PI / 2, 0, 0});
  const PenetrationResult p = penetration(Capsule(0.15, 2.0), along_x, Capsule(0.15, 2.0), along_y);
  EXPECT_NEAR(p.depth, 0.2, 1e-12);
  EXPECT_TRUE(p.normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-9)) << p.normal.transpose();
}

TEST(Cylinder, SphereBesideAndAboveAndDeep) {
  const Cylinder cyl(0.5, 2.0);
  // Beside the curved surface, in an arbitrary azimuth.
  for (double azimuth = 0.0; azimuth < 6.28; azimuth += 0.37) {
    const Eigen::Vector3d c(1.2 * std::cos(azimuth), 1.2 * std::sin(azimuth), 0.3);
    const DistanceResult d =
        distance(cyl, Eigen::Isometry3d::Identity(), Sphere(0.2), translation(c.x(), c.y(), c.z()));
    EXPECT_NEAR(d.distance, 0.5, 1e-9) << azimuth;
  }
  // Above the cap.
  EXPECT_NEAR(distance(cyl, Eigen::Isometry3d::Identity(), Sphere(0.2), translation(0.3, 0.1, 1.5))
                  .distance,
              0.3, 1e-9);
  // Sphere centre inside, nearest the curved side: depth = r + (R - rho).
  const PenetrationResult p =
      penetration(cyl, Eigen::Isometry3d::Identity(), Sphere(0.1), translation(0.4, 0.0, 0.2));
  EXPECT_NEAR(p.depth, 0.2, 1e-9);
  // On a curved surface a depth exact to eps fixes the normal to ~sqrt(2 eps / R).
  EXPECT_TRUE(p.normal.isApprox(Eigen::Vector3d::UnitX(), 1e-4)) << p.normal.transpose();
}

TEST(Cylinder, ParallelCylindersSideBySide) {
  for (double gap : {0.5, 1e-3, -1e-3, -0.2}) {
    const SignedDistanceResult s = signed_distance(
        Cylinder(0.5, 1.0), Eigen::Isometry3d::Identity(), Cylinder(0.5, 1.0),
        pose_from_xyz_angles({(1.0 + gap) * std::cos(0.3), (1.0 + gap) * std::sin(0.3), 0.2},
                             {0, 0, 0.7}));
    EXPECT_NEAR(s.signed_distance, gap, 1e-8) << gap;
  }
}

TEST(Margin, InflationShiftsDistanceAndDepth) {
  const Shape box = Box(1, 1, 1);
  const Shape padded = box.inflated(0.05);
  EXPECT_DOUBLE_EQ(padded.margin(), 0.05);
  const double d0 = distance(box, translation(0, 0, 0), box, translation(1.3, 0.2, 0)).distance;
  const double d1 =
      distance(padded, translation(0, 0, 0), padded, translation(1.3, 0.2, 0)).distance;
  EXPECT_NEAR(d0, 0.3, 1e-12);
  EXPECT_NEAR(d1, 0.2, 1e-12);
  // Corner to corner: the inflated box is rounded, distance shrinks by the margin exactly.
  const double dc =
      distance(padded, translation(0, 0, 0), Sphere(0.0), translation(1, 1, 1)).distance;
  EXPECT_NEAR(dc, std::sqrt(3.0) * 0.5 - 0.05, 1e-12);
  // Overlap across the margins only: depth = 2 margin - gap.
  const PenetrationResult p =
      penetration(padded, translation(0, 0, 0), padded, translation(1.04, 0, 0));
  EXPECT_NEAR(p.depth, 0.06, 1e-12);
  // Deep overlap of the cores: core depth + both margins.
  const PenetrationResult q =
      penetration(padded, translation(0, 0, 0), padded, translation(0.7, 0, 0));
  EXPECT_NEAR(q.depth, 0.4, 1e-12);
  EXPECT_TRUE(intersect(padded, translation(0, 0, 0), padded, translation(1.09, 0, 0)));
  EXPECT_FALSE(intersect(padded, translation(0, 0, 0), padded, translation(1.11, 0, 0)));
}

TEST(Support, PrimitivesAreExact) {
  const Eigen::Vector3d d(0.3, -0.4, 0.5);
  EXPECT_TRUE(Shape(Sphere(2.0)).support(d).isApprox(2.0 * d.normalized()));
  EXPECT_TRUE(Shape(Box(2, 4, 6)).support(d).isApprox(Eigen::Vector3d(1, -2, 3)));
  EXPECT_TRUE(
      Shape(Capsule(1.0, 2.0)).support(d).isApprox(Eigen::Vector3d(0, 0, 1) + d.normalized()));
  EXPECT_TRUE(Shape(Cylinder(1.0, 2.0)).support(d).isApprox(Eigen::Vector3d(0.6, -0.8, 1.0)));
  EXPECT_NEAR(Shape(Box(2, 4, 6)).inflated(0.5).bounding_radius(), std::sqrt(14.0) + 0.5, 1e-12);
}

}  // namespace
}  // namespace hullcheck

namespace hullcheck {
namespace {

// A shape resting on a box's top face, lifted or sunk by a gap of at most 1e-7 x size: the
// signed distance is the gap between the shape's lowest point (support along -z) and the face,
// exactly (the box is wide and thick enough that no other direction separates sooner).
// Curved cores (cylinders, capsules) make GJK converge geometrically near touching contact;
// whatever the path, the sign must be right (outside the tolerance) and the value within 1e-9 x
// the larger size.
TEST(NearTouchingOnAFace, SignedDistanceIsTheHeightGap) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int degenerate = 0, wrong_sign = 0;
  double worst = 0.0;
  for (int i = 0; i < 4000; ++i) {
    const double size = std::pow(10.0, (i % 5) - 2);  // 1e-2 .. 1e2
    Shape shape = Sphere(size);
    switch (i % 4) {
      case 0:
        shape = Cylinder(0.5 * size, 1.3 * size);
        break;
      case 1:
        shape = Capsule(0.3 * size, 1.2 * size);
        break;
      case 2:
        shape = Shape(Cylinder(0.6 * size, 0.2 * size)).inflated(0.05 * size);
        break;
      default:
        shape = Box(0.7 * size, 0.4 * size, 1.1 * size);
        break;
    }
    Eigen::Isometry3d pose = random_pose(rng, size);
    const double lowest =
        (pose * shape.support(-(pose.linear().transpose() * Eigen::Vector3d::UnitZ()))).z();
    const double gap = 1e-7 * size * unit(rng);  // > 0: apart
    const Box floor(4 * size, 4 * size, 2 * size);
    const Eigen::Isometry3d floor_pose =
        translation(pose.translation().x(), pose.translation().y(), lowest - gap - size);
    const SignedDistanceResult r = signed_distance(shape, pose, floor, floor_pose);
    // The tolerance model's scale: the larger shape (QueryOptions).
    const double tol = 1e-9 * std::max(shape.bounding_radius(), Shape(floor).bounding_radius());
    const double error = std::abs(r.signed_distance - gap);
    worst = std::max(worst, error / size);
    degenerate += r.status != Status::kConverged ? 1 : 0;
    if (std::abs(gap) > tol && (r.signed_distance > 0.0) != (gap > 0.0)) ++wrong_sign;
    // Every answer meets the tolerance, including those where GJK could not close its duality
    // gap on a curved core (status kDegenerate / kIterationCap: the lower bound lags, the
    // distance itself is exact after GJK's restarts).
    EXPECT_LE(error, tol) << i << " gap " << gap << " got " << r.signed_distance << " status "
                          << to_string(r.status);
  }
  std::printf(
      "[ touching ] 4000 shapes on a face within 1e-7 x size: worst error %.2e x size, "
      "%d not converged, %d wrong signs\n",
      worst, degenerate, wrong_sign);
  EXPECT_EQ(wrong_sign, 0);
}

}  // namespace
}  // namespace hullcheck
