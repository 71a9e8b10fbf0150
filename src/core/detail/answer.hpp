// What a query is asked for and everything it can answer, in the world frame: the engine's
// output, converted to the public result types by result_conversion.hpp.
#pragma once

#include <Eigen/Core>
#include <hullcheck/core/query_result.hpp>

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

}  // namespace hullcheck::detail
