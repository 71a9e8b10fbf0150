// Unit tests of the boolean GJK (detail/gjk_boolean.hpp), Casalino's algorithm 2 (A. Casalino,
// "How to use the GJK_EPA class", 2019): its plex updates for case a (segment), case b
// (triangular facet) and case c (tetrahedron, enclosing test of eq. 26-28) called directly on
// hand-placed simplices, then the whole loop on box cores: "collision absent" when <D, P*> < 0
// (with the radius margin), "collision detected" on a tetrahedron enclosing the origin, and the
// undecided exits. Expected regions and verdicts are derived analytically in the test.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "detail/gjk_boolean.hpp"
#include "detail/minkowski.hpp"
#include "detail/support.hpp"

namespace hullcheck::detail {
namespace {

using boolean_gjk::PointOnly;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using BoxBox = MinkowskiDifference<BoxCore, BoxCore>;

PointOnly pt(const Vector3d& w) { return PointOnly{w}; }

// True when d is a positive multiple of `expected`.
bool same_direction(const Vector3d& d, const Vector3d& expected) {
  return d.norm() > 0.0 && (d.normalized() - expected.normalized()).norm() < 1e-12;
}

// Case a: the origin beside the segment keeps it, with d orthogonal to it towards the origin;
// the origin behind the newest point keeps that point alone, with d = -a.
TEST(GjkBooleanCaseA, SegmentOrVertex) {
  PointOnly s[4] = {pt(Vector3d(1, 1, 0)), pt(Vector3d(-1, 1, 0))};
  int n = 2;
  Vector3d d;
  boolean_gjk::line(s, n, d);
  EXPECT_EQ(n, 2);
  EXPECT_TRUE(same_direction(d, Vector3d(0, -1, 0))) << d.transpose();

  PointOnly t[4] = {pt(Vector3d(1, 1, 0)), pt(Vector3d(3, 1, 0))};
  n = 2;
  boolean_gjk::line(t, n, d);
  EXPECT_EQ(n, 1);
  EXPECT_EQ(d, Vector3d(-1, -1, 0));
}

// Case b on the triangle a = (0,0), b = (3,0), c = (0,3) in the plane z = 1, shifted so that the
// origin projects into each region: the face (from below and from above: the winding flips so
// that d = (b-a) x (c-a) faces the origin), edges ac and ab, and the newest vertex a.
TEST(GjkBooleanCaseB, EveryRegionOfTheNewestVertex) {
  const Vector3d a0(0, 0, 0), b0(3, 0, 0), c0(0, 3, 0);
  const auto make = [&](double x, double y, double z, PointOnly* s) {
    const Vector3d q(x, y, -z);  // the origin's position relative to the reference triangle
    s[0] = pt(a0 - q);
    s[1] = pt(b0 - q);
    s[2] = pt(c0 - q);
  };
  PointOnly s[4];
  Vector3d d;
  int n = 3;
  make(1, 1, 1, s);  // face, origin below the plane z = 1: winding flipped
  const Vector3d b = s[1].w, c = s[2].w;
  boolean_gjk::triangle(s, n, d);
  EXPECT_EQ(n, 3);
  EXPECT_TRUE(same_direction(d, Vector3d(0, 0, -1))) << d.transpose();
  EXPECT_EQ(s[1].w, c);
  EXPECT_EQ(s[2].w, b);
  EXPECT_GT((s[1].w - s[0].w).cross(s[2].w - s[0].w).dot(-s[0].w), 0.0);

  n = 3;
  make(1, 1, -1, s);  // face, origin above: winding kept
  const Vector3d b2 = s[1].w;
  boolean_gjk::triangle(s, n, d);
  EXPECT_EQ(n, 3);
  EXPECT_TRUE(same_direction(d, Vector3d(0, 0, 1))) << d.transpose();
  EXPECT_EQ(s[1].w, b2);

  n = 3;
  make(-2, 1.5, 1, s);  // beyond edge ac (x = 0): kept a, c; d orthogonal to ac, towards O
  const Vector3d c3 = s[2].w;
  boolean_gjk::triangle(s, n, d);
  EXPECT_EQ(n, 2);
  EXPECT_EQ(s[1].w, c3);
  EXPECT_TRUE(same_direction(d, Vector3d(-2, 0, -1))) << d.transpose();

  n = 3;
  make(1.5, -2, 1, s);  // beyond edge ab (y = 0)
  const Vector3d b4 = s[1].w;
  boolean_gjk::triangle(s, n, d);
  EXPECT_EQ(n, 2);
  EXPECT_EQ(s[1].w, b4);
  EXPECT_TRUE(same_direction(d, Vector3d(0, -2, -1))) << d.transpose();

  n = 3;
  make(-1, -2, 1, s);  // vertex a's region
  boolean_gjk::triangle(s, n, d);
  EXPECT_EQ(n, 1);
  EXPECT_TRUE(same_direction(d, Vector3d(-1, -2, -1))) << d.transpose();
}

// Case c: tetrahedron with apex a (newest) over the base b, c, d wound to face it. Origin
// inside: enclosed. Origin beyond one of the faces through a (abc, acd, adb): not enclosed, the
// simplex reduced to that face's three vertices and d along its outward normal. Casalino's
// claim that face bcd cannot be the nearest is the precondition, not tested.
TEST(GjkBooleanCaseC, EnclosedOrBeyondAFaceThroughTheApex) {
  const Vector3d ref[4] = {Vector3d(0, 0, 2), Vector3d(-1, -1, -1), Vector3d(2, -1, -1),
                           Vector3d(-1, 2, -1)};
  Vector3d d;
  int n = 4;
  PointOnly s[4] = {pt(ref[0]), pt(ref[1]), pt(ref[2]), pt(ref[3])};
  EXPECT_TRUE(boolean_gjk::tetrahedron(s, n, d));

  const int faces[3][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}};
  for (const auto& f : faces) {
    const int other = 6 - f[0] - f[1] - f[2];
    Vector3d normal = (ref[f[1]] - ref[f[0]]).cross(ref[f[2]] - ref[f[0]]).normalized();
    if (normal.dot(ref[other] - ref[f[0]]) > 0.0) normal = -normal;  // outward
    const Vector3d q = (ref[f[0]] + ref[f[1]] + ref[f[2]]) / 3.0 + 0.5 * normal;
    for (int i = 0; i < 4; ++i) s[i] = pt(ref[i] - q);
    n = 4;
    SCOPED_TRACE(testing::Message() << "face " << f[0] << f[1] << f[2]);
    EXPECT_FALSE(boolean_gjk::tetrahedron(s, n, d));
    ASSERT_EQ(n, 3);
    EXPECT_TRUE(same_direction(d, normal)) << d.transpose();
    int found = 0;  // the kept vertices are the face's
    for (int i = 0; i < 3; ++i) {
      for (const int j : f) found += s[i].w == ref[j] - q;
    }
    EXPECT_EQ(found, 3);
  }
}

// The whole loop on boxes 1.5 apart along x: "collision absent" as soon as a support plane
// separates by more than the radius; within the radius it cannot be proven (undecided), and a
// radius of exactly the distance is no proof either.
TEST(GjkBooleanLoop, ApartOnlyWithASeparatingMarginAboveTheRadius) {
  const BoxCore a{Vector3d(1, 1, 1)}, b{Vector3d(0.5, 0.5, 0.5)};
  BoxBox md(a, b, Matrix3d::Identity(), Vector3d(3, 0.2, -0.1));
  PointOnly s[4];
  int iterations = 0;
  EXPECT_EQ(gjk_boolean(md, Vector3d(3, 0.2, -0.1), 0.0, 64, iterations, s),
            BooleanVerdict::kApart);
  EXPECT_EQ(iterations, 1);  // the first support point is on the plane x = -1.5
  for (const double radius : {1.5, 2.0}) {
    EXPECT_EQ(gjk_boolean(md, Vector3d(3, 0.2, -0.1), radius, 64, iterations, s),
              BooleanVerdict::kUndecided)
        << radius;
  }
  // From a poor direction, kApart still needs a plane separating by more than the radius.
  for (const double radius : {0.5, 1.0, 1.4}) {
    const BooleanVerdict v = gjk_boolean(md, Vector3d(0, 1, 1), radius, 64, iterations, s);
    EXPECT_NE(v, BooleanVerdict::kOverlapping) << radius;
    EXPECT_LE(iterations, 64);
  }
}

// "Collision detected": overlapping boxes end on a tetrahedron of support points enclosing
// the origin (barycentric coordinates solved here), and not before four support calls.
TEST(GjkBooleanLoop, OverlapIsProvenByAnEnclosingTetrahedron) {
  const BoxCore a{Vector3d(1, 1, 1)}, b{Vector3d(0.5, 0.7, 0.9)};
  BoxBox md(a, b, Eigen::AngleAxisd(0.4, Vector3d(1, 2, 2).normalized()).toRotationMatrix(),
            Vector3d(0.5, 0.2, 0.1));
  SimplexVertex s[4];
  int iterations = 0;
  ASSERT_EQ(gjk_boolean(md, Vector3d::Zero(), 0.0, 64, iterations, s),
            BooleanVerdict::kOverlapping);
  EXPECT_GE(iterations, 4);
  Matrix3d m;
  m << s[1].w - s[0].w, s[2].w - s[0].w, s[3].w - s[0].w;
  const Vector3d beta = m.fullPivLu().solve(-s[0].w);
  EXPECT_GE(beta.minCoeff(), 0.0);
  EXPECT_LE(beta.sum(), 1.0);
  for (const SimplexVertex& v : s) EXPECT_EQ(v.w, v.a - v.b);  // support points with parts

  // Fewer than four support calls cannot prove it.
  for (int cap = 1; cap <= 3; ++cap) {
    EXPECT_EQ(gjk_boolean(md, Vector3d(1, 0, 0), 0.0, cap, iterations, s),
              BooleanVerdict::kUndecided);
    EXPECT_LE(iterations, cap);
  }
}

// Undecided exits: a zero direction when continuing (origin on the simplex) returns at once;
// touching boxes (face on face) are never proven apart.
TEST(GjkBooleanLoop, DegenerateExits) {
  const BoxCore a{Vector3d(1, 1, 1)};
  BoxBox touching(a, a, Matrix3d::Identity(), Vector3d(2, 0.3, -0.2));
  PointOnly s[4];
  int iterations = -1;
  EXPECT_EQ(gjk_boolean_continue(touching, Vector3d::Zero(), 2, 0.0, 64, iterations, s),
            BooleanVerdict::kUndecided);
  EXPECT_EQ(iterations, 2);
  for (const Vector3d& d : {Vector3d(1, 0, 0), Vector3d(-1, 0, 0), Vector3d(0.3, -1, 2)}) {
    EXPECT_NE(gjk_boolean(touching, d, 0.0, 64, iterations, s), BooleanVerdict::kApart)
        << d.transpose();
  }
}

}  // namespace
}  // namespace hullcheck::detail
