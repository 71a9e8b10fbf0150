// The general engine behind every query: GJK on the cores (Casalino algorithms 1 and 2),
// radii added analytically, EPA when the cores overlap (Casalino algorithm 3). Templated on
// the two core types so that support functions inline; run_query is a sequence of stages, each
// forced inline (this is the hot path of distance and signed-distance queries), each settling
// the query when it can prove the answer:
//   ball tests -> warm-start simplex -> boolean stage -> distance GJK -> undecided-sign recovery
//   -> result assembly.
// run_query_after_boolean starts at the distance GJK, for the fast paths (fast_paths.hpp) that
// ran the stages before it themselves.
#pragma once

#include <algorithm>
#include <cmath>
#include <hullcheck/core/limits.hpp>
#include <hullcheck/core/query_options.hpp>
#include <hullcheck/core/query_result.hpp>
#include <hullcheck/core/shape.hpp>
#include <hullcheck/core/warm_start.hpp>
#include <limits>

#include "answer.hpp"
#include "cores.hpp"
#include "epa.hpp"
#include "gjk.hpp"
#include "gjk_boolean.hpp"
#include "inline.hpp"
#include "support.hpp"

namespace hullcheck::detail {

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

// ---- Placing the pair in A's frame ----

/// A's ball centre minus B's, in A's frame (rotation_a_t = A's rotation transposed,
/// offset_world = B's origin minus A's): the line of the ball tests and GJK's first search point
/// (a point inside the difference near its middle: mesh origins can lie far from the mesh).
template <class CoreA, class CoreB>
HULLCHECK_ALWAYS_INLINE Eigen::Vector3d centres_in_a(const CoreA& core_a, const CoreB& core_b,
                                                     const Eigen::Isometry3d& pose_b,
                                                     const Eigen::Matrix3d& rotation_a_t,
                                                     const Eigen::Vector3d& offset_world) {
  return core_a.center() - rotation_a_t * (pose_b.linear() * core_b.center() + offset_world);
}

/// The Minkowski difference A - B with B placed in A's frame (x_A = R_A^T R_B x_B + R_A^T t).
template <class CoreA, class CoreB>
HULLCHECK_ALWAYS_INLINE MinkowskiDifference<CoreA, CoreB> difference_in_a(
    const CoreA& core_a, const CoreB& core_b, const Eigen::Isometry3d& pose_b,
    const Eigen::Matrix3d& rotation_a_t, const Eigen::Vector3d& offset_world) {
  return MinkowskiDifference<CoreA, CoreB>(core_a, core_b, rotation_a_t * pose_b.linear(),
                                           rotation_a_t * offset_world);
}

// ---- Stage 1: ball tests (no support call) ----

/// signed distance below a cutoff: the balls around the cores bound the signed distance from
/// below by |centres| - (outer_a + outer_b + radii); when that bound reaches the cutoff the
/// query is settled (kAboveCutoff, with the bound). Returns true when it is.
template <class CoreA, class CoreB>
HULLCHECK_ALWAYS_INLINE bool cutoff_ball_test(const CoreA& core_a, const CoreB& core_b,
                                              double radius, double centres_squared, double cutoff,
                                              Answer& answer) {
  const double outer = core_a.outer_radius() + core_b.outer_radius() + radius;
  const double reach = cutoff + outer;  // lower bound >= cutoff <=> |centres| >= reach
  if (reach <= 0.0 || centres_squared >= reach * reach) {
    answer.status = Status::kAboveCutoff;
    answer.signed_distance = std::sqrt(centres_squared) - outer;
    return true;
  }
  return false;
}

/// Balls around the shapes that do not meet prove them apart (intersect and penetration, which
/// need no distance then).
template <class CoreA, class CoreB>
HULLCHECK_ALWAYS_INLINE bool outer_balls_apart(const CoreA& core_a, const CoreB& core_b,
                                               double radius, double centres_squared) {
  const double reach = core_a.outer_radius() + core_b.outer_radius() + radius;
  return centres_squared > reach * reach;
}

/// Balls inside the shapes (each core's centre lies inside it) that overlap prove the shapes
/// overlap (intersect and distance, which need no depth); the point dividing their centres in
/// the ratio of their radii is inside both: the distance query's common point. Returns true
/// with `answer` set when they prove it.
template <class CoreA, class CoreB>
HULLCHECK_ALWAYS_INLINE bool inner_balls_overlap(const CoreA& core_a, double radius_a,
                                                 const CoreB& core_b, double radius_b,
                                                 const Eigen::Isometry3d& pose_a,
                                                 const Eigen::Vector3d& centres,
                                                 double centres_squared, QueryKind kind,
                                                 Answer& answer) {
  if (!(core_a.inner_radius() >= 0.0 && core_b.inner_radius() >= 0.0)) return false;
  const double inner_a = core_a.inner_radius() + radius_a;
  const double inside = inner_a + core_b.inner_radius() + radius_b;
  if (!(centres_squared < inside * inside)) return false;
  answer.overlapping = true;
  if (kind == QueryKind::kDistance) {
    answer.point_a = answer.point_b = pose_a * (core_a.center() - (inner_a / inside) * centres);
  }
  return true;
}

/// The ball tests each kind of query can use, in order: cutoff (signed distance below a
/// cutoff), outer balls (intersect, penetration), inner balls (intersect, distance). Returns
/// true with `answer` set when one settles the query.
template <class CoreA, class CoreB>
HULLCHECK_ALWAYS_INLINE bool ball_tests(const CoreA& core_a, double radius_a, const CoreB& core_b,
                                        double radius_b, const Eigen::Isometry3d& pose_a,
                                        const Eigen::Vector3d& centres, QueryKind kind,
                                        double cutoff, Answer& answer) {
  const double radius = radius_a + radius_b;
  const double centres_squared = centres.squaredNorm();
  if (cutoff < INFINITY &&
      cutoff_ball_test(core_a, core_b, radius, centres_squared, cutoff, answer)) {
    return true;
  }
  if ((kind == QueryKind::kIntersect || kind == QueryKind::kPenetration) &&
      outer_balls_apart(core_a, core_b, radius, centres_squared)) {
    return true;  // the default Answer: apart
  }
  return (kind == QueryKind::kIntersect || kind == QueryKind::kDistance) &&
         inner_balls_overlap(core_a, radius_a, core_b, radius_b, pose_a, centres, centres_squared,
                             kind, answer);
}

// ---- Stage 2: the warm start ----

/// The warm start's last simplex re-evaluated at the new poses: its vertex pairs (a_i, b_i) are
/// core vertices, so a_i - R b_i - t is a support point of the difference now, and GJK starts
/// from a simplex that is usually already near the answer. A caller's warm start may hold
/// anything: out-of-range indices leave the simplex empty (the direction only). Cores without
/// vertex indices (curved) never have one.
template <class CoreA, class CoreB>
HULLCHECK_ALWAYS_INLINE void reevaluate_warm_simplex(const MinkowskiDifference<CoreA, CoreB>& md,
                                                     const WarmStart& warm, Simplex& simplex) {
  if constexpr (CoreA::kIndexed && CoreB::kIndexed) {
    simplex.size = warm.simplex_size >= 0 && warm.simplex_size <= 4 ? warm.simplex_size : 0;
    for (int i = 0; i < simplex.size; ++i) {
      if (warm.index_a[i] < 0 || warm.index_a[i] >= md.a.vertex_count() || warm.index_b[i] < 0 ||
          warm.index_b[i] >= md.b.vertex_count()) {
        simplex.size = 0;
      }
    }
    for (int i = 0; i < simplex.size; ++i) {
      simplex.index_a[i] = warm.index_a[i];
      simplex.index_b[i] = warm.index_b[i];
      simplex.a[i] = md.a.vertex(warm.index_a[i]);
      simplex.b[i] = md.rotation * md.b.vertex(warm.index_b[i]) + md.translation;
      simplex.w[i] = simplex.a[i] - simplex.b[i];
    }
  }
}

/// GJK's first search point: the ball centres' difference `v0` as given, or the warm start's
/// last direction (and `simplex`, its re-evaluated simplex) when it has a usable one.
template <class CoreA, class CoreB>
HULLCHECK_ALWAYS_INLINE void apply_warm_start(const MinkowskiDifference<CoreA, CoreB>& md,
                                              const WarmStart* warm, Eigen::Vector3d& v0,
                                              Simplex& simplex) {
  if (warm != nullptr && warm->valid && warm->direction.allFinite()) {
    v0 = warm->direction;
    reevaluate_warm_simplex(md, *warm, simplex);
  }
}

/// After the distance GJK: its separating direction (kept from an earlier query when the cores
/// overlap now) and its simplex's vertex indices, for the next query of the pair.
inline void store_warm_start(const GjkOutput& g, WarmStart& warm) {
  if (g.distance > 0.0) warm.direction = g.v;  // else keep the last separating direction
  warm.valid = true;
  warm.simplex_size = g.simplex.size;
  for (int i = 0; i < g.simplex.size; ++i) {
    warm.index_a[i] = g.simplex.index_a[i];
    warm.index_b[i] = g.simplex.index_b[i];
    // A curved core has no vertex indices: only the direction is kept.
    if (g.simplex.index_a[i] < 0 || g.simplex.index_b[i] < 0) warm.simplex_size = 0;
  }
}

// ---- Stage 3: the boolean GJK ----

/// intersect: the boolean GJK (Casalino algorithm 2) proves a separating plane beyond the
/// radii, or a tetrahedron of support points around the origin (eq. 26-28). Returns true with
/// the verdict in `answer` when it decides.
template <class MD>
HULLCHECK_ALWAYS_INLINE bool boolean_intersect_stage(MD& md, const Eigen::Vector3d& v0,
                                                     double radius, const QueryOptions& options,
                                                     Answer& answer) {
  int boolean_iterations = 0;
  boolean_gjk::PointOnly simplex[4];
  const BooleanVerdict verdict =
      gjk_boolean(md, -v0, radius, options.max_gjk_iterations, boolean_iterations, simplex);
  if (verdict == BooleanVerdict::kUndecided) return false;
  answer.overlapping = verdict == BooleanVerdict::kOverlapping;
  answer.iterations = boolean_iterations;
  return true;
}

/// penetration, and a signed distance needed only below a cutoff <= 0 (it matters only when the
/// shapes overlap): the boolean GJK proves the shapes apart (no depth; beyond such a cutoff),
/// or yields a tetrahedron of support points around the origin, from which EPA gives the depth
/// (Casalino algorithm 3). Returns true with `answer` set when it decides.
template <class MD>
HULLCHECK_ALWAYS_INLINE bool boolean_penetration_stage(MD& md, const Eigen::Vector3d& v0,
                                                       double radius_a, double radius_b,
                                                       const Eigen::Isometry3d& pose_a,
                                                       double tolerance,
                                                       const QueryOptions& options, double cutoff,
                                                       Answer& answer) {
  SimplexVertex tetrahedron[4];
  int boolean_iterations = 0;
  const BooleanVerdict verdict = gjk_boolean(
      md, -v0, radius_a + radius_b, options.max_gjk_iterations, boolean_iterations, tetrahedron);
  if (verdict == BooleanVerdict::kApart) {
    answer.iterations = boolean_iterations;
    if (cutoff < INFINITY) {  // proven apart: signed distance > 0 >= cutoff
      answer.status = Status::kAboveCutoff;
      answer.signed_distance = 0.0;
    }
    return true;
  }
  if (verdict == BooleanVerdict::kOverlapping) {
    answer.iterations = boolean_iterations;
    add_penetration(md, enclosing_simplex(tetrahedron), radius_a, radius_b, pose_a, tolerance,
                    options, answer, cutoff);
    return true;
  }
  return false;
}

// ---- Stage 5: the undecided-sign recovery ----

/// GJK may stop short of its tolerance (curved cores converge geometrically near touching
/// contact; rounding ends progress) with a bracket [lower_bound, distance] on the core distance
/// that reaches the radii: the sign is undecided, and |v| may exceed the true value by more
/// than the tolerance. The boolean GJK from GJK's last direction then proves overlap with a
/// tetrahedron of support points around the origin; EPA gives the depth from it, and for a
/// distance query the origin's barycentric weights in the tetrahedron give a point of A that
/// is also a point of B (sum of weights x (a_i - b_i) = 0). Returns true with `answer`
/// replaced when it proves overlap.
template <class MD>
bool recover_undecided_sign(MD& md, const GjkOutput& g, double radius_a, double radius_b,
                            const Eigen::Isometry3d& pose_a, double tolerance, QueryKind kind,
                            const QueryOptions& options, double cutoff, Answer& answer) {
  const double radius = radius_a + radius_b;
  if (kind == QueryKind::kIntersect || g.cores_overlap ||
      !(g.status == Status::kDegenerate || g.status == Status::kIterationCap) ||
      !(g.lower_bound <= radius + tolerance)) {
    return false;  // GJK decided the sign itself
  }
  SimplexVertex tetrahedron[4];
  int boolean_iterations = 0;
  const BooleanVerdict verdict =
      gjk_boolean(md, -g.v, 0.0, options.max_gjk_iterations, boolean_iterations, tetrahedron);
  if (verdict != BooleanVerdict::kOverlapping) return false;
  Simplex simplex = enclosing_simplex(tetrahedron);
  answer = Answer{};
  answer.iterations = g.iterations + boolean_iterations;
  answer.overlapping = true;
  if (kind == QueryKind::kDistance) {
    reduce_simplex(simplex);  // keeps all four (origin inside) or the nearest face
    answer.point_a = answer.point_b = pose_a * simplex.point_a();
    return true;
  }
  add_penetration(md, simplex, radius_a, radius_b, pose_a, tolerance, options, answer, cutoff);
  return true;
}

// ---- Stage 6: result assembly ----

/// Cores apart by |v| (GJK's closest points a, b of the cores, Casalino eq. 29-31): the shapes
/// are apart by |v| - radius along n = -v / |v| (from A to B), with points a + r_A n and
/// b - r_B n; or they overlap by radius - |v|, when a distance query's common point lies on the
/// segment between the core points, inside both shapes.
inline void apart_cores_answer(const GjkOutput& g, double radius_a, double radius_b,
                               const Eigen::Isometry3d& pose_a, QueryKind kind, Answer& answer) {
  const double radius = radius_a + radius_b;
  const Eigen::Vector3d core_a_point = g.simplex.point_a();
  const Eigen::Vector3d core_b_point = g.simplex.point_b();
  const Eigen::Vector3d n = -g.v / g.distance;  // from A to B, A's frame
  answer.signed_distance = g.distance - radius;
  answer.overlapping = answer.signed_distance < 0.0;
  if (kind == QueryKind::kDistance && answer.overlapping) {
    const Eigen::Vector3d p =
        core_a_point + (radius > 0.0 ? g.distance * radius_a / radius : 0.0) * n;
    answer.point_a = answer.point_b = pose_a * p;
    answer.signed_distance = 0.0;
    return;
  }
  answer.point_a = pose_a * (core_a_point + radius_a * n);
  answer.point_b = pose_a * (core_b_point - radius_b * n);
  const Eigen::Matrix3d rotation_a = pose_a.linear();
  answer.normal = rotation_a * n;
}

/// The answer from the distance GJK's output: above the cutoff (its proven lower bound), the
/// intersect verdict (touching within the tolerance counts as overlapping), no penetration when
/// proven apart, the apart cores' answer, or overlapping cores: a distance query's common point
/// is GJK's point of A (its simplex holds the origin), a depth comes from EPA.
template <class MD>
HULLCHECK_ALWAYS_INLINE void assemble_answer(MD& md, const GjkOutput& g, double radius_a,
                                             double radius_b, const Eigen::Isometry3d& pose_a,
                                             double tolerance, QueryKind kind,
                                             const QueryOptions& options, double cutoff,
                                             Answer& answer) {
  const double radius = radius_a + radius_b;
  if (g.status == Status::kAboveCutoff) {  // the shapes are at least `cutoff` apart
    answer.signed_distance = g.lower_bound - radius;
    return;
  }
  if (kind == QueryKind::kIntersect) {
    answer.overlapping = g.cores_overlap || g.distance <= radius ||
                         (g.lower_bound <= radius && g.distance - radius <= tolerance);
    return;
  }
  if (kind == QueryKind::kPenetration && !g.cores_overlap && g.lower_bound > radius) {
    return;  // proven apart: no penetration (points and normal are not needed)
  }
  if (!g.cores_overlap) {
    apart_cores_answer(g, radius_a, radius_b, pose_a, kind, answer);
    return;
  }
  // Cores overlap (or touch within tolerance).
  answer.overlapping = true;
  if (kind == QueryKind::kDistance) {
    answer.signed_distance = 0.0;
    answer.point_a = answer.point_b = pose_a * g.simplex.point_a();
    return;
  }
  add_penetration(md, g.simplex, radius_a, radius_b, pose_a, tolerance, options, answer, cutoff);
}

// ---- Stage 4 and on: the distance GJK, then recovery and assembly ----

/// From the distance GJK (Casalino algorithm 1) on: GJK from `v0` (and `warm_simplex` when
/// not null) with the goal the kind needs, the warm start stored, the undecided-sign recovery,
/// then the answer assembled.
template <class MD>
HULLCHECK_ALWAYS_INLINE Answer distance_gjk_stage(MD& md, const Eigen::Vector3d& v0,
                                                  const Simplex* warm_simplex, double radius_a,
                                                  double radius_b, const Eigen::Isometry3d& pose_a,
                                                  double tolerance, QueryKind kind,
                                                  const QueryOptions& options, WarmStart* warm,
                                                  double cutoff) {
  const double radius = radius_a + radius_b;
  const GjkGoal goal = kind == QueryKind::kIntersect     ? GjkGoal::kBoolean
                       : kind == QueryKind::kPenetration ? GjkGoal::kPenetration
                                                         : GjkGoal::kDistance;
  const GjkOutput g = gjk(md, v0, radius, tolerance, options.max_gjk_iterations, goal, warm_simplex,
                          cutoff + radius);
  Answer answer;
  answer.iterations = g.iterations;
  answer.status = g.status;
  if (warm != nullptr) store_warm_start(g, *warm);
  if (recover_undecided_sign(md, g, radius_a, radius_b, pose_a, tolerance, kind, options, cutoff,
                             answer)) {
    return answer;
  }
  assemble_answer(md, g, radius_a, radius_b, pose_a, tolerance, kind, options, cutoff, answer);
  return answer;
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
  if (kind != QueryKind::kSignedDistance) cutoff = INFINITY;  // only signed distances have one
  // The ball tests need one matrix-vector product pair; the relative rotation is built only
  // when GJK runs.
  const Eigen::Matrix3d rotation_a_t = pose_a.linear().transpose();
  const Eigen::Vector3d offset_world = pose_b.translation() - pose_a.translation();
  const Eigen::Vector3d centres = centres_in_a(core_a, core_b, pose_b, rotation_a_t, offset_world);
  Answer settled;
  if (ball_tests(core_a, radius_a, core_b, radius_b, pose_a, centres, kind, cutoff, settled)) {
    return settled;
  }
  auto md = difference_in_a(core_a, core_b, pose_b, rotation_a_t, offset_world);
  Eigen::Vector3d v0 = centres;
  Simplex warm_simplex;
  apply_warm_start(md, warm, v0, warm_simplex);
  if (kind == QueryKind::kIntersect &&
      boolean_intersect_stage(md, v0, radius_a + radius_b, options, settled)) {
    return settled;
  }
  const double tolerance =
      query_tolerance(core_a, radius_a, core_b, radius_b, md.translation, options);
  if ((kind == QueryKind::kPenetration || cutoff <= 0.0) &&
      boolean_penetration_stage(md, v0, radius_a, radius_b, pose_a, tolerance, options, cutoff,
                                settled)) {
    return settled;
  }
  return distance_gjk_stage(md, v0, warm_simplex.size > 0 ? &warm_simplex : nullptr, radius_a,
                            radius_b, pose_a, tolerance, kind, options, warm, cutoff);
}

/// run_query (no warm start, no cutoff) from the distance GJK on, for an intersect or
/// penetration query whose ball tests and boolean GJK have already run and left it undecided
/// (fast_paths.hpp; their first support direction is run_query's, computed in the world frame).
/// The pair is placed in A's frame exactly as run_query places it, so the distance GJK and all
/// that follows see run_query's inputs.
template <class CoreA, class CoreB>
Answer run_query_after_boolean(const CoreA& core_a, double radius_a,
                               const Eigen::Isometry3d& pose_a, const CoreB& core_b,
                               double radius_b, const Eigen::Isometry3d& pose_b, QueryKind kind,
                               const QueryOptions& options) {
  const Eigen::Matrix3d rotation_a_t = pose_a.linear().transpose();
  const Eigen::Vector3d offset_world = pose_b.translation() - pose_a.translation();
  const Eigen::Vector3d centres = centres_in_a(core_a, core_b, pose_b, rotation_a_t, offset_world);
  auto md = difference_in_a(core_a, core_b, pose_b, rotation_a_t, offset_world);
  const double tolerance =
      query_tolerance(core_a, radius_a, core_b, radius_b, md.translation, options);
  return distance_gjk_stage(md, centres, nullptr, radius_a, radius_b, pose_a, tolerance, kind,
                            options, nullptr, INFINITY);
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
