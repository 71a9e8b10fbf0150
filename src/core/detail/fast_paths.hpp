// Fast paths of intersect() and penetration() without a warm start: the ball tests and the
// boolean GJK's first iteration in the world frame (pairs settled there never build the relative
// rotation), then the boolean GJK (Casalino algorithm 2) and EPA (algorithm 3) in A's frame.
// When the boolean GJK cannot decide, the general engine continues from its distance GJK
// (query_engine.hpp, run_query_after_boolean) without repeating what was done here.
#pragma once

#include <hullcheck/core/query_options.hpp>
#include <hullcheck/core/shape.hpp>

#include "answer.hpp"
#include "cores.hpp"
#include "gjk_boolean.hpp"
#include "inline.hpp"
#include "minkowski.hpp"
#include "query_engine.hpp"

namespace hullcheck::detail {

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
/// of its own, returning only the verdict; the general engine from its distance GJK on (and its
/// tolerance) only when they cannot decide.
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
  // The ball tests and the boolean GJK are done: the distance GJK decides.
  return run_query_after_boolean(core_a, radius_a, pose_a, core_b, radius_b, pose_b,
                                 QueryKind::kIntersect, options)
      .overlapping;
}

/// penetration() without a warm start: centre_line_prelude (no inner balls: the depth is
/// needed), boolean GJK, EPA from its tetrahedron, in a frame of their own; the general engine
/// from its distance GJK on only when the boolean GJK cannot decide.
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
  // The ball test and the boolean GJK are done: the distance GJK decides.
  return run_query_after_boolean(core_a, radius_a, pose_a, core_b, radius_b, pose_b,
                                 QueryKind::kPenetration, options);
}

/// run_intersect on two shapes.
inline bool intersect_query(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                            const Eigen::Isometry3d& pose_b, const QueryOptions& options) {
  return with_cores(
      a, b, [&](const auto& core_a, double radius_a, const auto& core_b, double radius_b) {
        return run_intersect(core_a, radius_a, pose_a, core_b, radius_b, pose_b, options);
      });
}

/// run_intersect on A grown by `distance` and B: are they at most `distance` apart?
inline bool within_distance_query(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                                  const Eigen::Isometry3d& pose_b, double distance,
                                  const QueryOptions& options) {
  return with_cores(a, b,
                    [&](const auto& core_a, double radius_a, const auto& core_b, double radius_b) {
                      return run_intersect(core_a, radius_a + distance, pose_a, core_b, radius_b,
                                           pose_b, options);
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

}  // namespace hullcheck::detail
