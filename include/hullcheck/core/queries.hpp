// Proximity queries between two convex shapes: stateless free functions.
//
// Frames: each shape is given in its local frame and placed by its pose (local -> world);
// every returned point and vector is in the world frame. Units: those of the shapes (metres).
// Tolerances: see QueryOptions. Thread-safety: all functions are reentrant and allocate nothing.
// Errors: every query checks both poses with validate_pose()'s test (finite, translation within
// kMaxLength = 1e6 m, linear part a rotation to 1e-6) and throws InputError naming the pose
// otherwise; shapes are validated when constructed (limits.hpp). For valid input no query
// returns NaN, and a status kConverged is a proof to the stated tolerance.
#pragma once

#include <Eigen/Geometry>
#include <hullcheck/core/query_options.hpp>
#include <hullcheck/core/query_result.hpp>
#include <hullcheck/core/shape.hpp>
#include <hullcheck/core/warm_start.hpp>

namespace hullcheck {

/// True when A and B overlap or touch (GJK, Casalino algorithm 2, exiting early on a separating
/// direction). Verdicts are exact outside the tolerance band of QueryOptions.
bool intersect(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
               const Eigen::Isometry3d& pose_b, const QueryOptions& options = {});

/// True when A and B are at most `distance` (m) apart, overlapping included: intersect() with A
/// grown by `distance` (the boolean GJK, which stops at a separating plane; no distance is
/// converged). Verdicts are exact outside the tolerance band of QueryOptions. Throws InputError
/// unless distance is finite, >= 0 and, with A's margin, at most kMaxLength. Reentrant.
bool within_distance(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                     const Eigen::Isometry3d& pose_b, double distance,
                     const QueryOptions& options = {});

/// Separation distance and closest points (GJK, Casalino eq. 29-31). Distance 0 when overlapping.
DistanceResult distance(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                        const Eigen::Isometry3d& pose_b, const QueryOptions& options = {});

/// Penetration depth, direction and witness points (GJK then EPA, Casalino eq. 32-35).
/// Depth 0 and zero normal when the shapes are apart.
PenetrationResult penetration(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                              const Eigen::Isometry3d& pose_b, const QueryOptions& options = {});

/// Distance when apart, minus depth when overlapping, from one GJK run (EPA only if overlapping).
SignedDistanceResult signed_distance(const Shape& a, const Eigen::Isometry3d& pose_a,
                                     const Shape& b, const Eigen::Isometry3d& pose_b,
                                     const QueryOptions& options = {});

/// signed_distance() for callers that need the answer only when it is below `cutoff` (m), such
/// as a running minimum over many pairs: pass the smallest value so far. Once the signed
/// distance is proven to be at least `cutoff` (bounding balls, a GJK support plane, or, for
/// overlapping shapes, an EPA support plane), the query stops with status kAboveCutoff and
/// signed_distance set to that proven lower bound (>= cutoff; points and normal zero).
/// Otherwise the result is signed_distance()'s, to the same tolerance. A cutoff <= 0 makes the
/// query as cheap as intersect() on separated shapes. Throws InputError for a NaN cutoff.
SignedDistanceResult signed_distance_below(const Shape& a, const Eigen::Isometry3d& pose_a,
                                           const Shape& b, const Eigen::Isometry3d& pose_b,
                                           double cutoff, const QueryOptions& options = {});

/// signed_distance_below() of the same pair at nearby poses, started from `warm` and leaving
/// the new warm start in it (WarmStart: the same answer to the tolerance, usually in fewer GJK
/// iterations). `warm` belongs to this ordered pair (A, B); pass WarmStart{} for the first query.
/// A cutoff of +infinity gives signed_distance(). Same checks, frames and tolerances as above;
/// reentrant for distinct `warm` objects.
SignedDistanceResult signed_distance_below(const Shape& a, const Eigen::Isometry3d& pose_a,
                                           const Shape& b, const Eigen::Isometry3d& pose_b,
                                           double cutoff, WarmStart& warm,
                                           const QueryOptions& options = {});

}  // namespace hullcheck
