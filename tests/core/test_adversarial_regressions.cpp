// Regression tests for the proximity core's findings of the adversarial run: each reproducer
// with its exact answer (analytic) or the clear error it must raise.
#include <gtest/gtest.h>

#include <cmath>
#include <hullcheck/core.hpp>
#include <limits>
#include <string>
#include <vector>

#include "oracles.hpp"

namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using hullcheck::InputError;
using hullcheck::Shape;
using hullcheck::Status;

const Isometry3d kIdentity = Isometry3d::Identity();

Isometry3d translated(const Vector3d& t) {
  Isometry3d pose = Isometry3d::Identity();
  pose.translation() = t;
  return pose;
}

/// The unit tetrahedron (origin and the three unit points).
hullcheck::ConvexHull unit_tetrahedron() {
  return hullcheck::ConvexHull(
      {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1)});
}

/// Depth of two identical unit tetrahedra at the same pose, from the oracle (qhull on the
/// Minkowski difference T - T): 1/sqrt(3), along (1,1,1)/sqrt(3).
double identical_tetrahedra_depth() {
  const std::vector<Vector3d> t = unit_tetrahedron().vertices();
  return hullcheck::oracle::minkowski_penetration(t, t).depth;
}

TEST(AdversarialRegression, ProximityPairAnswerDoesNotDependOnQueryOrder) {
  const Shape t = unit_tetrahedron();
  const double free = hullcheck::signed_distance(t, kIdentity, t, kIdentity).signed_distance;
  EXPECT_NEAR(free, -identical_tetrahedra_depth(), 1e-9);
  hullcheck::ProximityPair pair;
  pair.set_shape_a(t);
  pair.set_shape_b(t);
  EXPECT_EQ(pair.distance().distance, 0.0);
  const hullcheck::SignedDistanceResult sd = pair.signed_distance();
  EXPECT_EQ(sd.status, Status::kConverged);
  EXPECT_NEAR(sd.signed_distance, -identical_tetrahedra_depth(), 1e-9);
  EXPECT_TRUE(pair.in_collision());
}

TEST(AdversarialRegression, WarmStartAfterAMoveAndBackStillProvesOverlap) {
  // A point pushed inside a hull, then B moved away and back: the warm-started GJK begins next
  // to the origin and must not read that as a separation.
  const Shape hull = unit_tetrahedron();
  const Shape point = hullcheck::Sphere(0.0);
  const Isometry3d inside = translated(Vector3d(0.1, 0.1, 0.1));
  hullcheck::ProximityPair pair;
  pair.set_shape_a(hull);
  pair.set_shape_b(point, inside);
  for (int round = 0; round < 3; ++round) {
    pair.set_pose_b(translated(Vector3d(3, 0, 0)));
    EXPECT_FALSE(pair.in_collision());
    pair.set_pose_b(inside);
    EXPECT_TRUE(pair.in_collision()) << round;
    EXPECT_NEAR(pair.signed_distance().signed_distance, -0.1, 1e-9) << round;
    EXPECT_NEAR(pair.penetration().depth, 0.1, 1e-9) << round;
  }
}

TEST(AdversarialRegression, CutoffBelowTheMarginsIsNotReportedAbove) {
  // Cores overlap by 0.7 in x, margins 0.1 each: signed distance -0.9.
  const Shape a = Shape(hullcheck::Box(1, 1, 1)).inflated(0.1);
  const Isometry3d shifted = translated(Vector3d(0.3, 0, 0));
  EXPECT_NEAR(hullcheck::signed_distance(a, kIdentity, a, shifted).signed_distance, -0.9, 1e-9);
  for (const double cutoff : {-0.5, -0.2, -0.85, 0.0, 1.0}) {
    const hullcheck::SignedDistanceResult r =
        hullcheck::signed_distance_below(a, kIdentity, a, shifted, cutoff);
    EXPECT_NE(r.status, Status::kAboveCutoff) << cutoff;
    EXPECT_NEAR(r.signed_distance, -0.9, 1e-9) << cutoff;
  }
  // Below the answer: either the full answer or a proven bound between cutoff and answer.
  const hullcheck::SignedDistanceResult above =
      hullcheck::signed_distance_below(a, kIdentity, a, shifted, -0.95);
  if (above.status == Status::kAboveCutoff) {
    EXPECT_GE(above.signed_distance, -0.95);
    EXPECT_LE(above.signed_distance, -0.9 + 1e-9);
  } else {
    EXPECT_NEAR(above.signed_distance, -0.9, 1e-9);
  }
}

TEST(AdversarialRegression, WitnessesAgreeWithTheNormalForIdenticalShapes) {
  const Shape t = unit_tetrahedron();
  const Shape box = hullcheck::Box(1, 2, 3);
  for (const Shape* s : {&t, &box}) {
    const hullcheck::SignedDistanceResult r =
        hullcheck::signed_distance(*s, kIdentity, *s, kIdentity);
    EXPECT_LT((r.point_b - r.point_a - r.signed_distance * r.normal).norm(), 1e-9);
    const hullcheck::PenetrationResult p = hullcheck::penetration(*s, kIdentity, *s, kIdentity);
    EXPECT_LT((p.point_a - p.point_b - p.depth * p.normal).norm(), 1e-9);
  }
  // The difference is a 2 x 4 x 6 box around the origin: depth 1, its smallest half size.
  EXPECT_NEAR(hullcheck::penetration(box, kIdentity, box, kIdentity).depth, 1.0, 1e-9);
}

TEST(AdversarialRegression, ShapesBeyondTheSizeRangeAreRejected) {
  EXPECT_THROW(hullcheck::Box(1e77, 1e77, 1e77), InputError);
  EXPECT_THROW(hullcheck::Cylinder(1e300, 0.0), InputError);
  EXPECT_THROW(hullcheck::Sphere(1e6 * (1 + 1e-9)), InputError);
  EXPECT_NO_THROW(hullcheck::Sphere(1e6));
  EXPECT_THROW(hullcheck::ConvexHull({Vector3d(0, 0, 0), Vector3d(2e6, 0, 0)}), InputError);
  EXPECT_THROW(Shape(hullcheck::Sphere(1)).inflated(2e6), InputError);
  EXPECT_THROW(Shape(hullcheck::Sphere(1)).inflated(6e5).inflated(6e5), InputError);
  // The largest accepted box against a unit box at the same pose: depth exact.
  const Shape big = hullcheck::Box(1e6, 1e6, 1e6);
  const hullcheck::PenetrationResult p =
      hullcheck::penetration(big, kIdentity, hullcheck::Box(1, 1, 1), kIdentity);
  EXPECT_EQ(p.status, Status::kConverged);
  EXPECT_NEAR(p.depth, 0.5e6 + 0.5, 1e-10 * 1e6);
}

TEST(AdversarialRegression, PublicFieldsSetInvalidAreCaughtWhenUsed) {
  hullcheck::Sphere sphere(1.0);
  sphere.radius = -std::numeric_limits<double>::infinity();
  EXPECT_THROW(Shape{sphere}, InputError);
  hullcheck::Box box(1, 1, 1);
  box.half_extents.x() = std::nan("");
  EXPECT_THROW(hullcheck::intersect(box, kIdentity, hullcheck::Sphere(1), kIdentity), InputError);
  hullcheck::Capsule capsule(1, 1);
  capsule.half_length = 1e300;
  EXPECT_THROW(Shape{capsule}, InputError);
  hullcheck::Cylinder cylinder(1, 1);
  cylinder.radius = -1;
  EXPECT_THROW(Shape{cylinder}, InputError);
}

TEST(AdversarialRegression, NonRigidPosesAreRejectedByEveryQuery) {
  const Shape a = hullcheck::Box(1, 1, 1);
  std::vector<std::pair<std::string, Isometry3d>> bad;
  Isometry3d pose = kIdentity;
  pose.linear() *= 2.0;
  bad.emplace_back("scaled", pose);
  pose = kIdentity;
  pose.linear()(0, 1) = 0.5;
  bad.emplace_back("sheared", pose);
  pose = kIdentity;
  pose.linear()(2, 2) = -1.0;
  bad.emplace_back("reflected", pose);
  pose = kIdentity;
  pose.linear().setZero();
  bad.emplace_back("zero", pose);
  pose = kIdentity;
  pose.translation().x() = std::nan("");
  bad.emplace_back("NaN translation", pose);
  pose = kIdentity;
  pose.translation().y() = 1e300;
  bad.emplace_back("huge translation", pose);
  for (const auto& [name, p] : bad) {
    SCOPED_TRACE(name);
    EXPECT_THROW(hullcheck::intersect(a, kIdentity, a, p), InputError);
    EXPECT_THROW(hullcheck::intersect(a, p, a, kIdentity), InputError);
    EXPECT_THROW(hullcheck::distance(a, kIdentity, a, p), InputError);
    EXPECT_THROW(hullcheck::penetration(a, p, a, kIdentity), InputError);
    EXPECT_THROW(hullcheck::signed_distance(a, kIdentity, a, p), InputError);
    EXPECT_THROW(hullcheck::signed_distance_below(a, kIdentity, a, p, 0.0), InputError);
    hullcheck::ProximityPair pair;
    EXPECT_THROW(pair.set_shape_a(a, p), InputError);
    try {
      hullcheck::distance(a, p, a, kIdentity);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("pose_a"), std::string::npos) << e.what();
    }
  }
  // Rounding-level deviations from a rotation are accepted.
  Isometry3d nearly = kIdentity;
  nearly.linear() = hullcheck::rotation_from_xyz_angles(0.3, -1.2, 2.0) * (1.0 + 1e-9);
  EXPECT_NO_THROW(hullcheck::distance(a, nearly, a, kIdentity));
}

TEST(AdversarialRegression, NonFiniteSearchDirectionsDoNotCrashTheSupport) {
  // 24 or more vertices: the support climbs from a cube-map cell of the direction.
  std::vector<Vector3d> points;
  for (int i = 0; i < 64; ++i) {
    const double phi = 0.1 * i, z = std::cos(0.37 * i);
    points.emplace_back(std::cos(phi), std::sin(phi), z);
  }
  const hullcheck::ConvexHull hull(points);
  ASSERT_GE(hull.vertex_count(), 24u);
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  for (const Vector3d& d : {Vector3d(nan, 1, 1), Vector3d(1, nan, 0), Vector3d(inf, 1, 1),
                            Vector3d(1, -inf, 2), Vector3d(nan, nan, nan)}) {
    const int index = hull.support_index(d);
    EXPECT_GE(index, 0);
    EXPECT_LT(index, static_cast<int>(hull.vertex_count()));
  }
}

TEST(AdversarialRegression, IdenticalCylindersAtTheSamePose) {
  // The difference is a cylinder of radius 2 and length 6: depth 2 (radially).
  const Shape c = hullcheck::Cylinder(1, 3);
  const hullcheck::SignedDistanceResult r = hullcheck::signed_distance(c, kIdentity, c, kIdentity);
  if (r.status == Status::kConverged) {
    EXPECT_NEAR(r.signed_distance, -2.0, 1e-9);
  } else {
    EXPECT_NEAR(r.signed_distance, -2.0, 1e-3);  // flagged: the best bound EPA reached
  }
}

}  // namespace
