// The engine's Answer as the public result of each query.
#pragma once

#include <hullcheck/core/query_result.hpp>

#include "answer.hpp"

namespace hullcheck::detail {

/// distance(): 0 and no normal when overlapping (the points are then a common point).
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

/// penetration(): depth, normal and points only when overlapping.
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

/// signed_distance(): the answer as it is.
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
