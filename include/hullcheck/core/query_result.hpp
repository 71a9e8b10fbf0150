// Result structs of the proximity queries.
#pragma once

#include <Eigen/Core>

namespace hullcheck {

/// How a query reached its answer.
enum class Status {
  kConverged,     ///< Tolerance met: the answer is exact up to the documented tolerance.
  kIterationCap,  ///< Stopped at the iteration cap (or EPA storage); best answer so far.
  kDegenerate,    ///< Numerical limit reached (no further progress possible in double
                  ///< precision); the answer is the best bound found, see each result.
  kAboveCutoff,   ///< signed_distance_below() only: the signed distance is proven to be at
                  ///< least the caller's cutoff; the value is that proven lower bound.
};

const char* to_string(Status status);

/// Result of distance(). All points in the world frame, metres.
struct DistanceResult {
  double distance = 0.0;             ///< >= 0; 0 when the shapes overlap or touch.
  Eigen::Vector3d point_a{0, 0, 0};  ///< Closest point on A (a point of A when overlapping).
  Eigen::Vector3d point_b{0, 0, 0};  ///< Closest point on B; |point_b - point_a| == distance.
  /// Unit direction from A to B (point_b - point_a normalised) when apart; zero when overlapping.
  Eigen::Vector3d normal{0, 0, 0};
  Status status = Status::kConverged;
  int iterations = 0;  ///< GJK iterations.
};

/// Result of penetration(). All points in the world frame, metres.
struct PenetrationResult {
  double depth = 0.0;  ///< >= 0: length of the shortest translation of B that separates them.
  /// Unit direction to translate B by `depth` to separate the shapes (from A towards B);
  /// zero when the shapes are apart.
  Eigen::Vector3d normal{0, 0, 0};
  Eigen::Vector3d point_a{0, 0, 0};  ///< Witness on A's boundary (deepest point of A inside B).
  Eigen::Vector3d point_b{0, 0, 0};  ///< Witness on B's boundary; point_a - point_b = depth*normal.
  Status status = Status::kConverged;
  int iterations = 0;      ///< GJK + EPA iterations.
  int epa_iterations = 0;  ///< EPA share of `iterations`.
};

/// Result of signed_distance(): distance when apart, minus the penetration depth when
/// overlapping. point_b - point_a == signed_distance * normal in both cases; normal is the unit
/// direction from A to B (translate B along it to increase the signed distance).
struct SignedDistanceResult {
  double signed_distance = 0.0;
  Eigen::Vector3d point_a{0, 0, 0};
  Eigen::Vector3d point_b{0, 0, 0};
  Eigen::Vector3d normal{0, 0, 0};
  Status status = Status::kConverged;
  int iterations = 0;
  int epa_iterations = 0;
};

}  // namespace hullcheck
