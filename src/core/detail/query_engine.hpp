// One engine behind every query: GJK on the cores, radii added analytically, EPA when the cores
// overlap. Templated on the two core types so support functions inline.
#pragma once

#include <hullcheck/core/limits.hpp>
#include <hullcheck/core/query_options.hpp>
#include <hullcheck/core/query_result.hpp>
#include <hullcheck/core/shape.hpp>
#include <hullcheck/core/warm_start.hpp>
#include <type_traits>

#include "epa.hpp"
#include "gjk.hpp"
#include "gjk_boolean.hpp"
#include "support.hpp"

namespace hullcheck::detail {

/// How much of the answer a query needs.
enum class QueryKind { kIntersect, kDistance, kPenetration, kSignedDistance };

/// Everything a query can produce, in the world frame.
struct Answer {
  bool overlapping = false;
  double signed_distance = 0.0;  ///< distance when apart, -depth when overlapping
  Eigen::Vector3d point_a{0, 0, 0}, point_b{0, 0, 0};
  Eigen::Vector3d normal{0, 0, 0};  ///< unit, from A to B
  Status status = Status::kConverged;
  int iterations = 0;
  int epa_iterations = 0;
};

template <class Core>
double core_extent(const Core& core);
inline double core_extent(const PointCore&) { return 0.0; }
inline double core_extent(const SegmentCore& c) { return c.half_length; }
inline double core_extent(const BoxCore& c) { return c.half.norm(); }
inline double core_extent(const CylinderCore& c) {
  return std::sqrt(c.radius * c.radius + c.half_length * c.half_length);
}
inline double core_extent(const HullCore& c) { return c.data->extent; }

/// Calls f(core, radius) with the shape's core and its total radius (own + margin).
template <class F>
decltype(auto) with_core(const Shape& shape, F&& f) {
  const double margin = shape.margin();
  switch (shape.kind()) {
    case ShapeKind::kSphere:
      return f(PointCore{}, std::get<Sphere>(shape.geometry()).radius + margin);
    case ShapeKind::kCapsule: {
      const Capsule& c = std::get<Capsule>(shape.geometry());
      return f(SegmentCore{c.half_length}, c.radius + margin);
    }
    case ShapeKind::kBox:
      return f(BoxCore{std::get<Box>(shape.geometry()).half_extents}, margin);
    case ShapeKind::kCylinder: {
      const Cylinder& c = std::get<Cylinder>(shape.geometry());
      return f(CylinderCore{c.radius, c.half_length}, margin);
    }
    case ShapeKind::kConvexHull:
    default:
      return f(HullCore{&std::get<ConvexHull>(shape.geometry()).data()}, margin);
  }
}

/// EPA from a simplex enclosing the origin (any size; grown to a tetrahedron), radii added,
/// results in the world frame written into `answer` (overlapping, signed distance -depth).
/// `cutoff` (signed distance): once the signed distance is proven above it, EPA stops and the
/// answer has status kAboveCutoff with that proven lower bound and no points.
template <class MD>
void add_penetration(MD& md, Simplex simplex, double radius_a, double radius_b,
                     const Eigen::Isometry3d& pose_a, double tolerance, const QueryOptions& options,
                     Answer& answer, double cutoff = INFINITY) {
  Eigen::Vector3d flat_normal;
  EpaOutput e;
  const Eigen::Vector3d common_point = simplex.point_a();
  if (epa_initial_tetrahedron(md, simplex, tolerance, flat_normal)) {
    thread_local EpaWorkspace workspace;
    // Signed distance -(depth + radii) > cutoff <=> depth < -cutoff - radii.
    e = epa(md, simplex, tolerance, options.max_epa_iterations, workspace,
            -cutoff - radius_a - radius_b);
  } else {
    // The difference is flat and contains the origin: depth 0 across its plane.
    e.depth = 0.0;
    e.normal = flat_normal;
    e.point_a = common_point;
    e.point_b = common_point;
    e.iterations = 0;
  }
  // EPA's normal n is the outward normal of A - B at the nearest boundary point p = a - b;
  // moving B by p separates, so n points from A to B.
  answer.overlapping = true;
  answer.epa_iterations = e.iterations;
  answer.iterations += e.iterations;
  if (e.status != Status::kConverged) answer.status = e.status;
  answer.signed_distance = -(e.depth + radius_a + radius_b);
  if (e.status == Status::kAboveCutoff) return;
  answer.normal = pose_a.linear() * e.normal;
  answer.point_a = pose_a * (e.point_a + radius_a * e.normal);
  answer.point_b = pose_a * (e.point_b - radius_b * e.normal);
}

/// The boolean GJK's tetrahedron around the origin as a GJK simplex (for EPA; no vertex indices).
inline Simplex enclosing_simplex(const SimplexVertex (&tetrahedron)[4]) {
  Simplex simplex;
  simplex.size = 4;
  for (int i = 0; i < 4; ++i) {
    simplex.set_vertex(i, tetrahedron[i]);
    simplex.lambda[i] = i == 0 ? 1.0 : 0.0;
    simplex.index_a[i] = simplex.index_b[i] = -1;
  }
  return simplex;
}

/// The absolute tolerance of a query (QueryOptions' model): relative to the larger shape, and
/// no smaller than what rounding of the difference's coordinates allows (they are as large as
/// the offset `translation` between the shapes).
template <class CoreA, class CoreB>
double query_tolerance(const CoreA& core_a, double radius_a, const CoreB& core_b, double radius_b,
                       const Eigen::Vector3d& translation, const QueryOptions& options) {
  const double scale =
      std::max({core_extent(core_a) + radius_a, core_extent(core_b) + radius_b, kMinScale});
  const double rounding =
      16.0 * std::numeric_limits<double>::epsilon() * (translation.norm() + 2.0 * scale);
  return std::max(options.relative_tolerance * scale, rounding);
}

/// Core query between two placed cores. `warm` (optional) supplies and receives the warm start.
/// `cutoff` (kSignedDistance only): the caller needs the answer only when the signed distance
/// is below it; once it is proven to be at least the cutoff, the query stops with status
/// kAboveCutoff and signed_distance = the proven lower bound (no points, no normal).
template <class CoreA, class CoreB>
Answer run_query(const CoreA& core_a, double radius_a, const Eigen::Isometry3d& pose_a,
                 const CoreB& core_b, double radius_b, const Eigen::Isometry3d& pose_b,
                 QueryKind kind, const QueryOptions& options, WarmStart* warm,
                 double cutoff = INFINITY) {
  const double radius = radius_a + radius_b;
  const Eigen::Matrix3d rotation_a_t = pose_a.linear().transpose();
  const Eigen::Vector3d offset_world = pose_b.translation() - pose_a.translation();
  // Ball tests first, from one matrix-vector product pair (the relative rotation is built only
  // when GJK runs). centres: A's ball centre minus B's, in A's frame.
  const Eigen::Vector3d centres =
      core_a.center() - rotation_a_t * (pose_b.linear() * core_b.center() + offset_world);
  const double centres_squared = centres.squaredNorm();
  if (kind != QueryKind::kSignedDistance) cutoff = INFINITY;  // only signed distances have one
  const bool has_cutoff = cutoff < INFINITY;
  if (has_cutoff) {
    // The balls around the cores bound the signed distance from below.
    const double outer = core_a.outer_radius() + core_b.outer_radius() + radius;
    const double reach = cutoff + outer;  // lower bound >= cutoff <=> |centres| >= reach
    if (reach <= 0.0 || centres_squared >= reach * reach) {
      Answer answer;
      answer.status = Status::kAboveCutoff;
      answer.signed_distance = std::sqrt(centres_squared) - outer;
      return answer;
    }
  }
  if (kind == QueryKind::kIntersect || kind == QueryKind::kPenetration) {
    // Balls around the cores prove separation.
    const double reach = core_a.outer_radius() + core_b.outer_radius() + radius;
    if (centres_squared > reach * reach) return Answer{};
  }
  if ((kind == QueryKind::kIntersect || kind == QueryKind::kDistance) &&
      core_a.inner_radius() >= 0.0 && core_b.inner_radius() >= 0.0) {
    // Balls inside the shapes (each core's centre lies inside it) prove overlap; the point
    // dividing their centres in the ratio of their radii is inside both.
    const double inner_a = core_a.inner_radius() + radius_a;
    const double inside = inner_a + core_b.inner_radius() + radius_b;
    if (centres_squared < inside * inside) {
      Answer answer;
      answer.overlapping = true;
      if (kind == QueryKind::kDistance) {
        answer.point_a = answer.point_b = pose_a * (core_a.center() - (inner_a / inside) * centres);
      }
      return answer;
    }
  }
  MinkowskiDifference<CoreA, CoreB> md(core_a, core_b, rotation_a_t * pose_b.linear(),
                                       rotation_a_t * offset_world);
  // First search point: the ball centres' difference, a point inside the difference near its
  // middle (mesh origins can lie far from the mesh), or the warm start's last direction.
  Eigen::Vector3d v0 = centres;
  Simplex warm_simplex;
  if (warm != nullptr && warm->valid && warm->direction.allFinite()) {
    v0 = warm->direction;
    if constexpr (CoreA::kIndexed && CoreB::kIndexed) {
      // Re-evaluate the last simplex's vertex pairs at the new poses (a caller's warm start
      // may hold anything: out-of-range indices leave the direction only).
      warm_simplex.size =
          warm->simplex_size >= 0 && warm->simplex_size <= 4 ? warm->simplex_size : 0;
      for (int i = 0; i < warm_simplex.size; ++i) {
        if (warm->index_a[i] < 0 || warm->index_a[i] >= core_a.vertex_count() ||
            warm->index_b[i] < 0 || warm->index_b[i] >= core_b.vertex_count()) {
          warm_simplex.size = 0;
        }
      }
      for (int i = 0; i < warm_simplex.size; ++i) {
        warm_simplex.index_a[i] = warm->index_a[i];
        warm_simplex.index_b[i] = warm->index_b[i];
        warm_simplex.a[i] = core_a.vertex(warm->index_a[i]);
        warm_simplex.b[i] = md.rotation * core_b.vertex(warm->index_b[i]) + md.translation;
        warm_simplex.w[i] = warm_simplex.a[i] - warm_simplex.b[i];
      }
    }
  }
  if (kind == QueryKind::kIntersect) {
    int boolean_iterations = 0;
    boolean_gjk::PointOnly simplex[4];
    const BooleanVerdict verdict =
        gjk_boolean(md, -v0, radius, options.max_gjk_iterations, boolean_iterations, simplex);
    if (verdict != BooleanVerdict::kUndecided) {
      Answer answer;
      answer.overlapping = verdict == BooleanVerdict::kOverlapping;
      answer.iterations = boolean_iterations;
      return answer;
    }
  }
  const double tolerance =
      query_tolerance(core_a, radius_a, core_b, radius_b, md.translation, options);
  if (kind == QueryKind::kPenetration || (has_cutoff && cutoff <= 0.0)) {
    // The cheap boolean GJK proves separation or yields a tetrahedron around the origin. (A
    // signed distance needed only below a cutoff <= 0 matters only when the shapes overlap.)
    SimplexVertex tetrahedron[4];
    int boolean_iterations = 0;
    const BooleanVerdict verdict =
        gjk_boolean(md, -v0, radius, options.max_gjk_iterations, boolean_iterations, tetrahedron);
    if (verdict == BooleanVerdict::kApart) {
      Answer answer;
      answer.iterations = boolean_iterations;
      if (has_cutoff) {  // proven apart: signed distance > 0 >= cutoff
        answer.status = Status::kAboveCutoff;
        answer.signed_distance = 0.0;
      }
      return answer;
    }
    if (verdict == BooleanVerdict::kOverlapping) {
      Simplex simplex = enclosing_simplex(tetrahedron);
      Answer answer;
      answer.iterations = boolean_iterations;
      add_penetration(md, simplex, radius_a, radius_b, pose_a, tolerance, options, answer, cutoff);
      return answer;
    }
  }
  const GjkGoal goal = kind == QueryKind::kIntersect     ? GjkGoal::kBoolean
                       : kind == QueryKind::kPenetration ? GjkGoal::kPenetration
                                                         : GjkGoal::kDistance;
  const GjkOutput g = gjk(md, v0, radius, tolerance, options.max_gjk_iterations, goal,
                          warm_simplex.size > 0 ? &warm_simplex : nullptr, cutoff + radius);

  Answer answer;
  answer.iterations = g.iterations;
  answer.status = g.status;
  if (warm != nullptr) {
    if (g.distance > 0.0) warm->direction = g.v;  // else keep the last separating direction
    warm->valid = true;
    warm->simplex_size = g.simplex.size;
    for (int i = 0; i < g.simplex.size; ++i) {
      warm->index_a[i] = g.simplex.index_a[i];
      warm->index_b[i] = g.simplex.index_b[i];
      // A curved core has no vertex indices: only the direction is kept.
      if (g.simplex.index_a[i] < 0 || g.simplex.index_b[i] < 0) warm->simplex_size = 0;
    }
  }
  if (kind != QueryKind::kIntersect && !g.cores_overlap &&
      (g.status == Status::kDegenerate || g.status == Status::kIterationCap) &&
      g.lower_bound <= radius + tolerance) {
    // GJK stopped short of its tolerance (curved cores converge geometrically near touching
    // contact; rounding ends progress) with a bracket [lower_bound, distance] on the core
    // distance that reaches the radii: the sign is undecided, and |v| may exceed the true value
    // by more than the tolerance. The boolean GJK proves overlap with a tetrahedron of support
    // points around the origin; then EPA gives the depth (distance queries: a common point).
    SimplexVertex tetrahedron[4];
    int boolean_iterations = 0;
    const BooleanVerdict verdict =
        gjk_boolean(md, -g.v, 0.0, options.max_gjk_iterations, boolean_iterations, tetrahedron);
    if (verdict == BooleanVerdict::kOverlapping) {
      Simplex simplex = enclosing_simplex(tetrahedron);
      Answer overlap;
      overlap.iterations = g.iterations + boolean_iterations;
      overlap.overlapping = true;
      if (kind == QueryKind::kDistance) {
        // The origin's barycentric weights in the tetrahedron give a point of A that is also a
        // point of B (sum of weights x (a_i - b_i) = 0).
        reduce_simplex(simplex);  // keeps all four (origin inside) or the nearest face
        overlap.point_a = overlap.point_b = pose_a * simplex.point_a();
        return overlap;
      }
      add_penetration(md, simplex, radius_a, radius_b, pose_a, tolerance, options, overlap, cutoff);
      return overlap;
    }
  }
  if (g.status == Status::kAboveCutoff) {  // the shapes are at least `cutoff` apart
    answer.signed_distance = g.lower_bound - radius;
    return answer;
  }
  if (kind == QueryKind::kIntersect) {
    answer.overlapping = g.cores_overlap || g.distance <= radius ||
                         (g.lower_bound <= radius && g.distance - radius <= tolerance);
    return answer;
  }
  const Eigen::Matrix3d& rotation_a = pose_a.linear();
  if (kind == QueryKind::kPenetration && !g.cores_overlap && g.lower_bound > radius) {
    return answer;  // proven apart: no penetration (points and normal are not needed)
  }
  if (!g.cores_overlap) {
    // Cores apart: the shapes are apart by |v| - radius, or overlap by radius - |v|.
    const Eigen::Vector3d core_a_point = g.simplex.point_a();
    const Eigen::Vector3d core_b_point = g.simplex.point_b();
    const Eigen::Vector3d n = -g.v / g.distance;  // from A to B, A's frame
    answer.signed_distance = g.distance - radius;
    answer.overlapping = answer.signed_distance < 0.0;
    if (kind == QueryKind::kDistance && answer.overlapping) {
      // One common point: on the segment between the core points, inside both shapes.
      const Eigen::Vector3d p =
          core_a_point + (radius > 0.0 ? g.distance * radius_a / radius : 0.0) * n;
      answer.point_a = answer.point_b = pose_a * p;
      answer.signed_distance = 0.0;
      return answer;
    }
    answer.point_a = pose_a * (core_a_point + radius_a * n);
    answer.point_b = pose_a * (core_b_point - radius_b * n);
    answer.normal = rotation_a * n;
    return answer;
  }
  // Cores overlap (or touch within tolerance).
  answer.overlapping = true;
  if (kind == QueryKind::kDistance) {
    answer.signed_distance = 0.0;
    answer.point_a = answer.point_b = pose_a * g.simplex.point_a();
    return answer;
  }
  add_penetration(md, g.simplex, radius_a, radius_b, pose_a, tolerance, options, answer, cutoff);
  return answer;
}

/// R * x for a pose's rotation R. Scalar code: Eigen's products with a block of an
/// Isometry3d become out-of-line calls in GCC once the caller is large.
HULLCHECK_ALWAYS_INLINE Eigen::Vector3d rotated(const Eigen::Isometry3d& pose,
                                                const Eigen::Vector3d& x) {
  const Eigen::Matrix4d& m = pose.matrix();
  return {m(0, 0) * x.x() + m(0, 1) * x.y() + m(0, 2) * x.z(),
          m(1, 0) * x.x() + m(1, 1) * x.y() + m(1, 2) * x.z(),
          m(2, 0) * x.x() + m(2, 1) * x.y() + m(2, 2) * x.z()};
}

/// R^T * x for a pose's rotation R: a world direction in the pose's local frame.
HULLCHECK_ALWAYS_INLINE Eigen::Vector3d unrotated(const Eigen::Isometry3d& pose,
                                                  const Eigen::Vector3d& x) {
  const Eigen::Matrix4d& m = pose.matrix();
  return {m(0, 0) * x.x() + m(1, 0) * x.y() + m(2, 0) * x.z(),
          m(0, 1) * x.x() + m(1, 1) * x.y() + m(2, 1) * x.z(),
          m(0, 2) * x.x() + m(1, 2) * x.y() + m(2, 2) * x.z()};
}

/// The Minkowski difference with B placed in A's frame (x_A = rotation * x_B + translation).
template <class CoreA, class CoreB>
MinkowskiDifference<CoreA, CoreB> placed_difference(const CoreA& core_a,
                                                    const Eigen::Isometry3d& pose_a,
                                                    const CoreB& core_b,
                                                    const Eigen::Isometry3d& pose_b) {
  const Eigen::Matrix4d& b = pose_b.matrix();
  Eigen::Matrix3d rotation;
  for (int j = 0; j < 3; ++j) {
    rotation.col(j) = unrotated(pose_a, Eigen::Vector3d(b(0, j), b(1, j), b(2, j)));
  }
  return MinkowskiDifference<CoreA, CoreB>(
      core_a, core_b, rotation,
      unrotated(pose_a, Eigen::Vector3d(b(0, 3), b(1, 3), b(2, 3)) - pose_a.translation()));
}

/// What the tests before the boolean GJK decided.
enum class Prelude {
  kApart,        // proven apart: balls, or a plane normal to the centres' line
  kOverlapping,  // proven overlapping: balls inside the shapes
  kUndecided,    // cores apart along the centres' line, but maybe within the radii
  kContinue,     // run the boolean GJK from `first` (its first support point)
};

/// The parts of the first support point of A - B, each in its own core's frame.
struct FirstSupport {
  Eigen::Vector3d a, b;
};

/// Ball tests and the boolean GJK's first iteration, in the world frame: everything the
/// relative rotation of B in A's frame is not needed for, so that pairs settled here (most
/// pairs of a broad phase's output) never build it. The first search direction is the line
/// from A's ball centre to B's (a point inside the difference near its middle: mesh origins can
/// lie far from the mesh). `inner_test`: use the balls inside the shapes (intersect only).
/// On kContinue, `first` holds the support points along that line.
template <class CoreA, class CoreB>
Prelude centre_line_prelude(const CoreA& core_a, double radius_a, const Eigen::Isometry3d& pose_a,
                            const CoreB& core_b, double radius_b, const Eigen::Isometry3d& pose_b,
                            bool inner_test, FirstSupport& first) {
  const double radius = radius_a + radius_b;
  Eigen::Vector3d u = rotated(pose_b, core_b.center()) + pose_b.translation() -
                      (rotated(pose_a, core_a.center()) + pose_a.translation());
  const double u2 = u.squaredNorm();
  const double reach = core_a.outer_radius() + core_b.outer_radius() + radius;
  if (u2 > reach * reach) return Prelude::kApart;
  if (inner_test && core_a.inner_radius() >= 0.0 && core_b.inner_radius() >= 0.0) {
    const double inside = core_a.inner_radius() + radius_a + core_b.inner_radius() + radius_b;
    if (u2 < inside * inside) return Prelude::kOverlapping;  // balls inside the shapes overlap
  }
  if (!(u2 > 0.0)) u = Eigen::Vector3d::UnitX();
  // Support of A along u and of B along -u; w = a - b, apart when u.w < -radius |u|.
  const Eigen::Vector3d d_a = unrotated(pose_a, u);
  const Eigen::Vector3d d_b = -unrotated(pose_b, u);
  int index = -1;  // the cores' vertex indices are not needed here
  first.a = core_a.support(d_a, index);
  first.b = core_b.support(d_b, index);
  const double uw =
      d_a.dot(first.a) + d_b.dot(first.b) - u.dot(pose_b.translation() - pose_a.translation());
  if (uw < 0.0) {
    return uw * uw > radius * radius * u.squaredNorm() ? Prelude::kApart : Prelude::kUndecided;
  }
  return Prelude::kContinue;
}

/// The boolean GJK after centre_line_prelude's first iteration (kContinue), in A's frame.
template <class MD, class V>
BooleanVerdict boolean_gjk_after(MD& md, const FirstSupport& first, double radius,
                                 const QueryOptions& options, int& iterations, V (&simplex)[4]) {
  const Eigen::Vector3d b = md.place_b(first.b);
  simplex[0].set(first.a - b, first.a, b);
  return gjk_boolean_continue(md, b - first.a, 1, radius, options.max_gjk_iterations, iterations,
                              simplex);
}

/// intersect() without a warm start: centre_line_prelude, then the boolean GJK in a small frame
/// of its own, returning only the verdict; run_query (the distance GJK and its tolerance) only
/// when they cannot decide.
template <class CoreA, class CoreB>
bool run_intersect(const CoreA& core_a, double radius_a, const Eigen::Isometry3d& pose_a,
                   const CoreB& core_b, double radius_b, const Eigen::Isometry3d& pose_b,
                   const QueryOptions& options) {
  FirstSupport first;
  const Prelude prelude =
      centre_line_prelude(core_a, radius_a, pose_a, core_b, radius_b, pose_b, true, first);
  if (prelude == Prelude::kContinue) {
    auto md = placed_difference(core_a, pose_a, core_b, pose_b);
    int iterations = 0;
    boolean_gjk::PointOnly simplex[4];
    const BooleanVerdict verdict =
        boolean_gjk_after(md, first, radius_a + radius_b, options, iterations, simplex);
    if (verdict != BooleanVerdict::kUndecided) return verdict == BooleanVerdict::kOverlapping;
  } else if (prelude != Prelude::kUndecided) {
    return prelude == Prelude::kOverlapping;
  }
  return run_query(core_a, radius_a, pose_a, core_b, radius_b, pose_b, QueryKind::kIntersect,
                   options, nullptr)
      .overlapping;
}

/// penetration() without a warm start: centre_line_prelude (no inner balls: the depth is
/// needed), boolean GJK, EPA from its tetrahedron, in a frame of their own; run_query only when
/// the boolean GJK cannot decide.
template <class CoreA, class CoreB>
Answer run_penetration(const CoreA& core_a, double radius_a, const Eigen::Isometry3d& pose_a,
                       const CoreB& core_b, double radius_b, const Eigen::Isometry3d& pose_b,
                       const QueryOptions& options) {
  Answer answer;
  FirstSupport first;
  const Prelude prelude =
      centre_line_prelude(core_a, radius_a, pose_a, core_b, radius_b, pose_b, false, first);
  if (prelude == Prelude::kApart) return answer;
  if (prelude == Prelude::kContinue) {
    auto md = placed_difference(core_a, pose_a, core_b, pose_b);
    SimplexVertex tetrahedron[4];
    const BooleanVerdict verdict =
        boolean_gjk_after(md, first, radius_a + radius_b, options, answer.iterations, tetrahedron);
    if (verdict == BooleanVerdict::kApart) return answer;
    if (verdict == BooleanVerdict::kOverlapping) {
      add_penetration(md, enclosing_simplex(tetrahedron), radius_a, radius_b, pose_a,
                      query_tolerance(core_a, radius_a, core_b, radius_b, md.translation, options),
                      options, answer);
      return answer;
    }
  }
  return run_query(core_a, radius_a, pose_a, core_b, radius_b, pose_b, QueryKind::kPenetration,
                   options, nullptr);
}

/// Calls f(core_a, radius_a, core_b, radius_b) with both shapes' cores and radii.
template <class F>
decltype(auto) with_cores(const Shape& a, const Shape& b, F&& f) {
  return with_core(a, [&](const auto& core_a, double radius_a) {
    return with_core(b, [&](const auto& core_b, double radius_b) {
      return f(core_a, radius_a, core_b, radius_b);
    });
  });
}

/// run_intersect on two shapes.
inline bool intersect_query(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                            const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  return with_cores(
      a, b, [&](const auto& core_a, double radius_a, const auto& core_b, double radius_b) {
        return run_intersect(core_a, radius_a, pose_a, core_b, radius_b, pose_b, options);
      });
}

/// run_penetration on two shapes.
inline Answer penetration_query(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                                const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  return with_cores(
      a, b, [&](const auto& core_a, double radius_a, const auto& core_b, double radius_b) {
        return run_penetration(core_a, radius_a, pose_a, core_b, radius_b, pose_b, options);
      });
}

/// run_query on two shapes.
inline Answer query(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                    const Eigen::Isometry3d& pose_b, QueryKind kind, const QueryOptions& options,
                    WarmStart* warm, double cutoff = INFINITY) {
  return with_cores(a, b,
                    [&](const auto& core_a, double radius_a, const auto& core_b, double radius_b) {
                      return run_query(core_a, radius_a, pose_a, core_b, radius_b, pose_b, kind,
                                       options, warm, cutoff);
                    });
}

}  // namespace hullcheck::detail

namespace hullcheck::detail {

inline DistanceResult to_distance_result(const Answer& a) {
  DistanceResult r;
  r.distance = a.overlapping ? 0.0 : a.signed_distance;
  r.point_a = a.point_a;
  r.point_b = a.point_b;
  r.normal = a.overlapping ? Eigen::Vector3d::Zero() : a.normal;
  r.status = a.status;
  r.iterations = a.iterations;
  return r;
}

inline PenetrationResult to_penetration_result(const Answer& a) {
  PenetrationResult r;
  r.status = a.status;
  r.iterations = a.iterations;
  r.epa_iterations = a.epa_iterations;
  if (!a.overlapping) return r;
  r.depth = -a.signed_distance;
  r.normal = a.normal;
  r.point_a = a.point_a;
  r.point_b = a.point_b;
  return r;
}

inline SignedDistanceResult to_signed_distance_result(const Answer& a) {
  SignedDistanceResult r;
  r.signed_distance = a.signed_distance;
  r.point_a = a.point_a;
  r.point_b = a.point_b;
  r.normal = a.normal;
  r.status = a.status;
  r.iterations = a.iterations;
  r.epa_iterations = a.epa_iterations;
  return r;
}

}  // namespace hullcheck::detail
