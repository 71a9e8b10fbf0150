// Proximity queries between two convex shapes: stateless free functions.
//
// Frames: each shape is given in its local frame and placed by its pose (local -> world);
// every returned point and vector is in the world frame. Units: those of the shapes (metres).
// Tolerances: see QueryOptions. Thread-safety: all functions are reentrant and allocate nothing.
// Poses must be rigid (rotation + translation; validate_pose() checks that, and ProximityPair
// does on every set). Errors: a pose with NaN/inf throws InputError.
#pragma once

#include <Eigen/Geometry>
#include <hullcheck/query_options.hpp>
#include <hullcheck/query_result.hpp>
#include <hullcheck/shape.hpp>

namespace hullcheck {

/// True when A and B overlap or touch (GJK, seed algorithm 2, exiting early on a separating
/// direction). Verdicts are exact outside the tolerance band of QueryOptions.
bool intersect(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
               const Eigen::Isometry3d& pose_b, const QueryOptions& options = {});

/// Separation distance and closest points (GJK, seed eq. 29-31). Distance 0 when overlapping.
DistanceResult distance(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                        const Eigen::Isometry3d& pose_b, const QueryOptions& options = {});

/// Penetration depth, direction and witness points (GJK then EPA, seed eq. 32-35).
/// Depth 0 and zero normal when the shapes are apart.
PenetrationResult penetration(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                              const Eigen::Isometry3d& pose_b, const QueryOptions& options = {});

/// Distance when apart, minus depth when overlapping, from one GJK run (EPA only if overlapping).
SignedDistanceResult signed_distance(const Shape& a, const Eigen::Isometry3d& pose_a,
                                     const Shape& b, const Eigen::Isometry3d& pose_b,
                                     const QueryOptions& options = {});

}  // namespace hullcheck
