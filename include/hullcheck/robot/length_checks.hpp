// Range checks of lengths and joint values read from files (URDF, SRDF, scenes), shared by the
// loaders so that their errors name the file element.
#pragma once

#include <Eigen/Core>
#include <hullcheck/core/limits.hpp>
#include <string>

namespace hullcheck {

/// Largest magnitude, m, of a length the loaders accept: shape dimensions, mesh vertex
/// coordinates, origin translations. The core's limit (Shape, ConvexHull and every query reject
/// larger values), checked here first so that the message names the file element.
inline constexpr double kMaxLoadedLength = kMaxLength;

/// Throws InputError "`what`: must be finite and at most 1e+06 m in magnitude (got v)" when
/// `value` (m) is NaN, infinite or larger in magnitude than kMaxLoadedLength.
void check_length(double value, const std::string& what);

/// Largest magnitude of a joint limit (rad or m) or a mimic coefficient the URDF loader
/// accepts: beyond it, sampling and motion checks within the limits would be meaningless.
inline constexpr double kMaxJointValue = 1e6;

/// Throws InputError "`what`: must be finite and at most 1e+06 `unit` in magnitude (got v)"
/// when `value` is NaN, infinite or larger in magnitude than kMaxJointValue.
void check_joint_value(double value, const std::string& what, const char* unit);

/// check_length for each component of `v` (m); the message names the component (x, y, z).
void check_lengths(const Eigen::Vector3d& v, const std::string& what);

}  // namespace hullcheck
