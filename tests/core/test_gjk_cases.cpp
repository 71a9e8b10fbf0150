// Unit tests of GJK (detail/gjk.hpp, detail/gjk_boolean.hpp) on hand-built Minkowski differences
// of point, segment and box cores, following Casalino ("How to use the GJK_EPA
// class", 2019): the plex update cases a (segment), b (triangular facet) and c (tetrahedron),
// algorithm 1 (closest region) and algorithm 2 (boolean test: "collision absent" on <D, P*> < 0,
// "collision detected" on an enclosing tetrahedron). Every expected distance, closest point and
// verdict is derived analytically in the test.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "detail/gjk.hpp"
#include "detail/gjk_boolean.hpp"
#include "detail/minkowski.hpp"
#include "detail/support.hpp"

namespace hullcheck::detail {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using BoxBox = MinkowskiDifference<BoxCore, BoxCore>;
constexpr double kTol = 1e-12;

// A Minkowski difference that counts its support calls.
template <class MD>
struct Counting {
  MD& md;
  int calls = 0;
  int index_a = -1, index_b = -1;
  void support(const Vector3d& d, Vector3d& w, Vector3d& pa, Vector3d& pb) {
    ++calls;
    md.support(d, w, pa, pb);
    index_a = md.index_a;
    index_b = md.index_b;
  }
};

template <class MD>
GjkOutput run(MD& md, double radius = 0.0, GjkGoal goal = GjkGoal::kDistance, int cap = 64,
              const Simplex* initial = nullptr, double stop = INFINITY) {
  return gjk(md, -md.translation, radius, kTol, cap, goal, initial, stop);
}

// The output's simplex is made of support points of `md` (w = a - b, a and b the cores' vertices
// its indices name), with weights of a convex combination whose point is v.
template <class MD>
void expect_consistent(const MD& md, const GjkOutput& out) {
  const Simplex& s = out.simplex;
  ASSERT_GE(s.size, 1);
  ASSERT_LE(s.size, 4);
  double weight = 0.0;
  for (int i = 0; i < s.size; ++i) {
    EXPECT_EQ(s.w[i], s.a[i] - s.b[i]);
    EXPECT_EQ(s.a[i], md.a.vertex(s.index_a[i]));
    EXPECT_EQ(s.b[i], md.place_b(md.b.vertex(s.index_b[i])));
    EXPECT_GE(s.lambda[i], 0.0);
    weight += s.lambda[i];
  }
  EXPECT_NEAR(weight, 1.0, 1e-12);
  EXPECT_LT((s.closest_point() - out.v).norm(), 1e-12);
  EXPECT_LT((s.point_a() - s.point_b() - out.v).norm(), 1e-12);
  EXPECT_NEAR(out.v.norm(), out.distance, 1e-12);
  EXPECT_LE(out.lower_bound, out.distance);
}

// Crossed edges: A is the cube [-1, 1]^3; B, the same cube turned so that its edge through
// B-frame corners (-1, -1, *) runs along u = (1, -1, 0)/sqrt2 facing A's edge (1, 1, *) along h1
// = (1, 1, 0)/sqrt2, shifted by 0.3 along z and 0.4 along u. The edges cross (seen along h1) at
// A's (1, 1, 0.3) and B's (T - sqrt2) h1 + 0.3 z: distance T - 2 sqrt2, unique closest points.
struct CrossedEdges {
  const double s2 = std::sqrt(2.0);
  const Vector3d h1 = Vector3d(1, 1, 0) / std::sqrt(2.0);
  const Vector3d u = Vector3d(1, -1, 0) / std::sqrt(2.0);
  const double gap = 0.75;
  BoxCore a{Vector3d(1, 1, 1)}, b{Vector3d(1, 1, 1)};
  Matrix3d rotation() const {
    Matrix3d g, h;  // B frame basis -> A frame basis
    g << (Vector3d(1, 1, 0) / s2), -(Vector3d(1, -1, 0) / s2), Vector3d::UnitZ();
    h << h1, Vector3d::UnitZ(), u;
    return h * g.transpose();
  }
  Vector3d translation() const { return (2 * s2 + gap) * h1 + 0.3 * Vector3d::UnitZ() + 0.4 * u; }
  BoxBox md() const { return BoxBox(a, b, rotation(), translation()); }
  Vector3d point_a() const { return Vector3d(1, 1, 0.3); }
  Vector3d point_b() const { return (s2 + gap) * h1 + 0.3 * Vector3d::UnitZ(); }
};

// Case a, vertex region (Casalino eq. 18): corner against corner, the plex ends as one point made
// of A's corner 7 (+,+,+) and B's corner 0 (-,-,-).
TEST(GjkCaseA, CornerToCornerEndsOnOneVertex) {
  const BoxCore a{Vector3d(1, 1, 1)}, b{Vector3d(0.5, 0.5, 0.5)};
  BoxBox md(a, b, Matrix3d::Identity(), Vector3d(3, 3, 3));
  const GjkOutput out = run(md);
  expect_consistent(md, out);
  EXPECT_EQ(out.status, Status::kConverged);
  EXPECT_FALSE(out.cores_overlap);
  EXPECT_NEAR(out.distance, 1.5 * std::sqrt(3.0), 1e-12);
  EXPECT_GE(out.lower_bound, out.distance - kTol);
  ASSERT_EQ(out.simplex.size, 1);
  EXPECT_EQ(out.simplex.index_a[0], 7);
  EXPECT_EQ(out.simplex.index_b[0], 0);
}

// Case a, segment interior (Casalino eq. 16): a point against a segment (a sphere's core against a
// capsule's) lying along x at (0.4, 2, 0): nearest (0, 2, 0), weights 0.7 / 0.3 on its ends.
TEST(GjkCaseA, PointAgainstSegmentEndsOnTheSegment) {
  const PointCore a;
  const SegmentCore b{1.0};
  const Matrix3d z_to_x = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()).toRotationMatrix();
  MinkowskiDifference<PointCore, SegmentCore> md(a, b, z_to_x, Vector3d(0.4, 2, 0));
  const GjkOutput out = run(md);
  expect_consistent(md, out);
  EXPECT_NEAR(out.distance, 2.0, 1e-12);
  ASSERT_EQ(out.simplex.size, 2);
  EXPECT_LT((out.simplex.point_b() - Vector3d(0, 2, 0)).norm(), 1e-12);
  // B's vertex 1 is (0,0,h) in its frame, (h,0,0) placed: the end at x = 1.4 has weight 0.3.
  const int far_end = out.simplex.index_b[0] == 1 ? 0 : 1;
  EXPECT_NEAR(out.simplex.lambda[far_end], 0.3, 1e-12);
}

// Case b, facet interior (Casalino eq. 22): a point below a box face, off its centre so that the
// nearest point lies on no diagonal; and crossed box edges, whose difference is a parallelogram.
TEST(GjkCaseB, FacetInteriorPointAndCrossedEdges) {
  const PointCore p;
  const BoxCore box{Vector3d(1, 1, 1)};
  MinkowskiDifference<PointCore, BoxCore> md(p, box, Matrix3d::Identity(), Vector3d(0.3, -0.2, 3));
  const GjkOutput out = run(md);
  expect_consistent(md, out);
  EXPECT_NEAR(out.distance, 2.0, 1e-12);
  EXPECT_EQ(out.simplex.size, 3);
  EXPECT_LT((out.simplex.point_b() - Vector3d(0, 0, 2)).norm(), 1e-12);

  const CrossedEdges c;
  BoxBox md2 = c.md();
  const GjkOutput e = run(md2);
  expect_consistent(md2, e);
  EXPECT_EQ(e.status, Status::kConverged);
  EXPECT_NEAR(e.distance, c.gap, 1e-12);
  EXPECT_GE(e.lower_bound, c.gap - kTol);
  EXPECT_EQ(e.simplex.size, 3);
  EXPECT_LT((e.simplex.point_a() - c.point_a()).norm(), 1e-12);
  EXPECT_LT((e.simplex.point_b() - c.point_b()).norm(), 1e-12);
}

// Face against face (closest points not unique): the distance, and both points on the facing
// faces x = 1 and x = 2.5, directly across from each other.
TEST(GjkCaseB, FaceAgainstFace) {
  const BoxCore a{Vector3d(1, 1, 1)}, b{Vector3d(0.5, 0.5, 0.5)};
  BoxBox md(a, b, Matrix3d::Identity(), Vector3d(3, 0.2, -0.1));
  const GjkOutput out = run(md);
  expect_consistent(md, out);
  EXPECT_NEAR(out.distance, 1.5, 1e-12);
  EXPECT_LT((out.v - Vector3d(-1.5, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(out.simplex.point_a().x(), 1.0, 1e-12);
  EXPECT_NEAR(out.simplex.point_b().x(), 2.5, 1e-12);
}

// Case c, origin enclosed (Casalino eq. 26-28): overlapping boxes end on a tetrahedron of support
// points whose barycentric coordinates of the origin (solved here) are all positive.
TEST(GjkCaseC, OverlappingBoxesEncloseTheOrigin) {
  const BoxCore a{Vector3d(1, 1, 1)}, b{Vector3d(0.5, 0.7, 0.9)};
  BoxBox md(a, b, Eigen::AngleAxisd(0.4, Vector3d(1, 2, 2).normalized()).toRotationMatrix(),
            Vector3d(0.5, 0.2, 0.1));
  const GjkOutput out = run(md);
  EXPECT_TRUE(out.cores_overlap);
  EXPECT_EQ(out.distance, 0.0);
  EXPECT_EQ(out.v, Vector3d::Zero());
  ASSERT_EQ(out.simplex.size, 4);
  const Simplex& s = out.simplex;
  Matrix3d m;
  m << s.w[1] - s.w[0], s.w[2] - s.w[0], s.w[3] - s.w[0];
  const Vector3d beta = m.fullPivLu().solve(-s.w[0]);
  EXPECT_GT(beta.minCoeff(), 0.0);
  EXPECT_LT(beta.sum(), 1.0);
}

// Touching cores (face on face, corner on corner): core distance 0, reported as overlapping.
TEST(GjkTermination, TouchingCoresCountAsOverlapping) {
  const BoxCore a{Vector3d(1, 1, 1)};
  for (const Vector3d& t : {Vector3d(2, 0.3, -0.2), Vector3d(2, 2, 2)}) {
    BoxBox md(a, a, Matrix3d::Identity(), t);
    const GjkOutput out = run(md);
    EXPECT_TRUE(out.cores_overlap) << t.transpose();
    EXPECT_LE(out.distance, kTol);
    EXPECT_LE(out.lower_bound, kTol);
  }
}

// Goals: the boolean goal stops once the distance is proven above the radius (lower bound >
// radius) or shown within it (|v| <= radius); the penetration goal stops on the former only.
TEST(GjkTermination, BooleanAndPenetrationGoalsStopAtTheRadius) {
  const CrossedEdges c;  // distance 0.75
  BoxBox md = c.md();
  const GjkOutput apart = run(md, 0.5, GjkGoal::kBoolean);
  EXPECT_GT(apart.lower_bound, 0.5);
  EXPECT_GE(apart.distance, c.gap - kTol);
  const GjkOutput within = run(md, 1.0, GjkGoal::kBoolean);
  EXPECT_FALSE(within.cores_overlap);
  EXPECT_LE(within.distance, 1.0);
  EXPECT_GE(within.distance, c.gap - kTol);
  EXPECT_LE(within.lower_bound, c.gap + kTol);
  const GjkOutput pen = run(md, 0.5, GjkGoal::kPenetration);
  EXPECT_GT(pen.lower_bound, 0.5);
  EXPECT_LE(pen.lower_bound, c.gap + kTol);
  // Not enough with the distance goal: it converges whatever the radius.
  const GjkOutput full = run(md, 0.5, GjkGoal::kDistance);
  EXPECT_NEAR(full.distance, c.gap, 1e-12);
  EXPECT_GE(full.lower_bound, c.gap - kTol);
}

// The iteration cap: never more support calls than allowed; one call cannot find the crossed
// edges' closest points (the first support point is a corner pair), so status kIterationCap.
TEST(GjkTermination, IterationCapBoundsSupportCalls) {
  const CrossedEdges c;
  BoxBox inner = c.md();
  for (int cap = 1; cap <= 8; ++cap) {
    Counting<BoxBox> md{inner};
    const GjkOutput out = gjk(md, -inner.translation, 0.0, kTol, cap, GjkGoal::kDistance);
    EXPECT_LE(md.calls, cap);
    EXPECT_EQ(out.iterations, md.calls);
    EXPECT_GE(out.distance, c.gap - kTol);  // |v| is an upper bound
    if (out.distance > c.gap + 1e-9 || cap == 1) {
      EXPECT_EQ(out.status, Status::kIterationCap) << cap;
    }
  }
}

// The cutoff exit: proven core distance >= stop_distance ends GJK with kAboveCutoff and that
// proof as lower bound; a cutoff above the distance changes nothing; overlapping cores never
// exit there (a lower bound proves nothing about their depth).
TEST(GjkTermination, CutoffExitCarriesTheProof) {
  const CrossedEdges c;
  BoxBox md = c.md();
  const GjkOutput above = run(md, 0.0, GjkGoal::kDistance, 64, nullptr, 0.5);
  EXPECT_EQ(above.status, Status::kAboveCutoff);
  EXPECT_GE(above.lower_bound, 0.5);
  EXPECT_LE(above.lower_bound, c.gap + kTol);
  const GjkOutput below = run(md, 0.0, GjkGoal::kDistance, 64, nullptr, 1.0);
  EXPECT_EQ(below.status, Status::kConverged);
  EXPECT_NEAR(below.distance, c.gap, 1e-12);

  const BoxCore a{Vector3d(1, 1, 1)};
  BoxBox overlap(a, a, Matrix3d::Identity(), Vector3d(0.5, 0.3, 0.1));
  const GjkOutput o = run(overlap, 0.0, GjkGoal::kDistance, 64, nullptr, -1.0);
  EXPECT_NE(o.status, Status::kAboveCutoff);
  EXPECT_TRUE(o.cores_overlap);
}

// Warm starts: the converged simplex fed back converges after one confirming support call; a
// tetrahedron around the origin returns overlap with no support call; a stale simplex (support
// points of another placement, re-evaluated here) still converges to this placement's answer.
TEST(GjkWarmStart, ConvergesFromAnyInitialSimplex) {
  const CrossedEdges c;
  BoxBox inner = c.md();
  const GjkOutput cold = run(inner);
  Counting<BoxBox> md{inner};
  const GjkOutput warm =
      gjk(md, Vector3d(1, 0, 0), 0.0, kTol, 64, GjkGoal::kDistance, &cold.simplex);
  EXPECT_EQ(md.calls, 1);
  EXPECT_NEAR(warm.distance, c.gap, 1e-12);

  // Stale: the corner-to-corner simplex of a far placement, re-evaluated from its indices.
  BoxBox far(c.a, c.b, Matrix3d::Identity(), Vector3d(5, 5, 5));
  const GjkOutput far_out = run(far);
  Simplex stale = far_out.simplex;
  for (int i = 0; i < stale.size; ++i) {
    stale.a[i] = c.a.vertex(stale.index_a[i]);
    stale.b[i] = inner.place_b(c.b.vertex(stale.index_b[i]));
    stale.w[i] = stale.a[i] - stale.b[i];
  }
  const GjkOutput restarted = run(inner, 0.0, GjkGoal::kDistance, 64, &stale);
  expect_consistent(inner, restarted);
  EXPECT_NEAR(restarted.distance, c.gap, 1e-12);
  EXPECT_LT((restarted.simplex.point_a() - c.point_a()).norm(), 1e-12);

  // Unit cubes offset by 0.1 along x: A - B is the cube [-2, 2]^3 shifted by -0.1 x. Its
  // corners of signs (+,+,+), (+,-,-), (-,+,-), (-,-,+) (A's corner with those signs minus B's
  // opposite corner) span a tetrahedron around its centre, hence around the origin.
  const BoxCore unit{Vector3d(1, 1, 1)};
  BoxBox overlap(unit, unit, Matrix3d::Identity(), Vector3d(0.1, 0, 0));
  Simplex tet;
  tet.size = 4;
  const int corners_a[4] = {7, 1, 2, 4}, corners_b[4] = {0, 6, 5, 3};
  for (int i = 0; i < 4; ++i) {
    tet.index_a[i] = corners_a[i];
    tet.index_b[i] = corners_b[i];
    tet.a[i] = unit.vertex(corners_a[i]);
    tet.b[i] = overlap.place_b(unit.vertex(corners_b[i]));
    tet.w[i] = tet.a[i] - tet.b[i];
  }
  Counting<BoxBox> counted{overlap};
  const GjkOutput enclosed =
      gjk(counted, Vector3d(1, 0, 0), 0.0, kTol, 64, GjkGoal::kDistance, &tet);
  EXPECT_TRUE(enclosed.cores_overlap);
  EXPECT_EQ(counted.calls, 0);
  EXPECT_EQ(enclosed.iterations, 0);
}

// Degenerate starts and exits: a zero initial vector (x is used instead) converges; two
// crossing segments (a flat difference around the origin, no tetrahedron can enclose it) are
// reported overlapping (touching) by the distance GJK, and never "apart" by the boolean one.
TEST(GjkDegenerate, ZeroStartAndFlatDifferenceThroughTheOrigin) {
  const CrossedEdges c;
  BoxBox md = c.md();
  const GjkOutput zero = gjk(md, Vector3d::Zero(), 0.0, kTol, 64, GjkGoal::kDistance);
  EXPECT_NEAR(zero.distance, c.gap, 1e-12);

  const SegmentCore seg{1.0};
  const Matrix3d z_to_x = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()).toRotationMatrix();
  MinkowskiDifference<SegmentCore, SegmentCore> cross(seg, seg, z_to_x, Vector3d(0.2, 0, 0.3));
  const GjkOutput flat = gjk(cross, Vector3d(1, 2, 3), 0.0, kTol, 64, GjkGoal::kDistance);
  EXPECT_TRUE(flat.cores_overlap);
  EXPECT_LE(flat.distance, kTol);
  boolean_gjk::PointOnly s[4];
  int iterations = 0;
  EXPECT_NE(gjk_boolean(cross, Vector3d(1, 2, 3), 0.0, 64, iterations, s), BooleanVerdict::kApart);
  EXPECT_LE(iterations, 64);
}

}  // namespace
}  // namespace hullcheck::detail
