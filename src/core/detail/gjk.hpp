// GJK (Gilbert-Johnson-Keerthi) on the Minkowski difference of two cores: Casalino algorithm 1
// (the closest point, §2.2), with goals that stop it early. Algorithm 2, the boolean test, is
// gjk_boolean.hpp.
#pragma once

#include <hullcheck/core/query_result.hpp>

#include "minkowski.hpp"
#include "simplex.hpp"

namespace hullcheck::detail {

/// What GJK is asked to decide.
enum class GjkGoal {
  kBoolean,      ///< Stop as soon as the distance between cores is known to be <= or > radius.
  kDistance,     ///< Converge on the core distance (needed when it is below radius, too).
  kPenetration,  ///< Stop once the cores are proven farther apart than radius, else converge.
};

struct GjkOutput {
  Simplex simplex;
  Eigen::Vector3d v{0, 0, 0};  ///< Closest point of the core difference to the origin.
  double distance = 0.0;       ///< |v| (an upper bound of the core distance)
  double lower_bound = 0.0;    ///< Proven lower bound of the core distance.
  bool cores_overlap = false;  ///< Origin inside the simplex (or within tolerance of it).
  Status status = Status::kConverged;
  int iterations = 0;
};

/// Reduces simplex `s` (its newest vertex last) to the sub-simplex nearest the origin and sets
/// its weights (Casalino §2 cases a, b, c). Returns false when the origin is inside a tetrahedron.
inline bool reduce_simplex(Simplex& s) {
  SubSimplex sub;
  switch (s.size) {
    case 1:
      sub = SubSimplex{{0, 0, 0, 0}, {1.0, 0, 0, 0}, 1, s.w[0].squaredNorm()};
      break;
    case 2:
      sub = closest_on_segment(s.w, 0, 1);
      break;
    case 3:
      sub = closest_on_triangle(s.w, 0, 1, 2);
      break;
    default:
      sub = closest_on_tetrahedron(s.w);
      break;
  }
  // Keep the vertices of the closest region, in place (indices are ascending).
  for (int i = 0; i < sub.size; ++i) {
    const int from = sub.index[i];
    if (from != i) {
      s.w[i] = s.w[from];
      s.a[i] = s.a[from];
      s.b[i] = s.b[from];
      s.index_a[i] = s.index_a[from];
      s.index_b[i] = s.index_b[from];
    }
    s.lambda[i] = sub.lambda[i];
  }
  s.size = sub.size;
  return s.size < 4;
}

/// Runs GJK. `v` is the initial search point (any vector; the warm start's last separating
/// direction or the vector between the shapes' ball centres). `radius` is the sum of the
/// shapes' radii (boolean goal: shapes overlap when the core distance is <= radius).
/// `tolerance` is the absolute convergence tolerance. Never more than `max_iterations` support
/// calls. `initial` (optional, warm start): a simplex of support points to start from instead
/// of the single point in direction -v. `stop_distance`: once the core distance is proven to be
/// at least this, GJK stops with status kAboveCutoff (lower_bound holds the proof).
template <class MD>
GjkOutput gjk(MD& md, Eigen::Vector3d v, double radius, double tolerance, int max_iterations,
              GjkGoal goal, const Simplex* initial = nullptr, double stop_distance = INFINITY) {
  GjkOutput out;
  Simplex& s = out.simplex;
  if (!(v.squaredNorm() > 0.0)) v = Eigen::Vector3d::UnitX();
  double best_distance_squared = INFINITY;
  double lower = 0.0;
  // Restarts (see the no-progress case below): the answer kept from before them.
  constexpr int kMaxRestarts = 6;
  int restarts = 0;
  Simplex kept;
  double kept_distance_squared = INFINITY;
  if (initial != nullptr && initial->size > 0) {
    s = *initial;
    if (!reduce_simplex(s)) {
      out.cores_overlap = true;
      out.v.setZero();
      return out;
    }
    v = s.closest_point();
    best_distance_squared = v.squaredNorm();
  }
  for (int iteration = 1; iteration <= max_iterations; ++iteration) {
    out.iterations = iteration;
    const int k = s.size;
    md.support(-v, s.w[k], s.a[k], s.b[k]);
    s.index_a[k] = md.index_a;
    s.index_b[k] = md.index_b;
    if (k > 0) {
      // v is a point of the difference: |v| bounds the distance from above, and the support
      // plane through w bounds it from below by v.w / |v|.
      const double vw = v.dot(s.w[k]);
      if (vw > 0.0 && vw * vw > lower * lower * best_distance_squared) {
        lower = vw / std::sqrt(best_distance_squared);
      }
      if (goal != GjkGoal::kDistance && lower > radius) break;  // separating plane found
      // A lower bound proves a signed distance only when it proves the cores apart (lower > 0):
      // overlapping cores have core distance 0 whatever their depth.
      if (lower > 0.0 && lower >= stop_distance) {
        out.status = Status::kAboveCutoff;
        break;
      }
      // Converged when |v| - lower <= tolerance, i.e. |v|^2 <= (lower + tolerance)^2.
      const double reach = lower + tolerance;
      if (best_distance_squared <= reach * reach) break;
    }
    ++s.size;
    reduce_simplex(s);
    if (s.size == 4) {  // origin inside the tetrahedron
      out.cores_overlap = true;
      v.setZero();
      best_distance_squared = 0.0;
      break;
    }
    const Eigen::Vector3d next_v = s.closest_point();
    const double next_distance_squared = next_v.squaredNorm();
    if (!(next_distance_squared < best_distance_squared)) {
      if (std::sqrt(best_distance_squared) - lower > tolerance && restarts < kMaxRestarts &&
          iteration < max_iterations) {
        // No progress with the duality gap still open: the simplex has become a sliver whose
        // closest point no longer improves in double precision (curved cores near contact).
        // Keep this answer and restart from the newest support point alone, which is still in
        // slot k (reduce_simplex only writes slots below the sub-simplex size).
        ++restarts;
        if (next_distance_squared < kept_distance_squared) {
          kept = s;
          kept_distance_squared = next_distance_squared;
        }
        if (k != 0) {
          s.w[0] = s.w[k];
          s.a[0] = s.a[k];
          s.b[0] = s.b[k];
          s.index_a[0] = s.index_a[k];
          s.index_b[0] = s.index_b[k];
        }
        s.lambda[0] = 1.0;
        s.size = 1;
        v = s.w[0];
        best_distance_squared = v.squaredNorm();
        continue;
      }
      // No progress in double precision: the answer is the best bound there is. Keep v, the
      // distance and the simplex consistent (the new estimate differs by rounding only).
      if (std::sqrt(best_distance_squared) - lower > tolerance) out.status = Status::kDegenerate;
      v = next_v;
      best_distance_squared = next_distance_squared;
      break;
    }
    v = next_v;
    best_distance_squared = next_distance_squared;
    if (best_distance_squared <= tolerance * tolerance) {  // touching within tolerance
      out.cores_overlap = true;
      break;
    }
    if (goal == GjkGoal::kBoolean && best_distance_squared <= radius * radius) break;
    if (iteration == max_iterations) out.status = Status::kIterationCap;
  }
  if (restarts > 0 && !out.cores_overlap && out.status != Status::kAboveCutoff) {
    if (kept_distance_squared < best_distance_squared) {  // the restarts did not do better
      s = kept;
      v = s.closest_point();
      best_distance_squared = kept_distance_squared;
    }
    if (std::sqrt(best_distance_squared) - lower <= tolerance) {
      out.status = Status::kConverged;
    } else if (out.status == Status::kConverged) {
      out.status = Status::kDegenerate;
    }
  }
  out.v = v;
  out.distance = std::sqrt(best_distance_squared);
  out.lower_bound = std::min(lower, out.distance);
  if (!out.cores_overlap && !(out.lower_bound > 0.0) && out.distance <= tolerance) {
    // |v| within the tolerance of the origin and no support plane separating the cores: they
    // are not proven apart, whichever test stopped the loop (a warm-started simplex can begin
    // there). The sign is decided by the caller's overlap path (EPA), never by reading |v| as
    // a separation.
    out.cores_overlap = true;
  }
  return out;
}

}  // namespace hullcheck::detail
