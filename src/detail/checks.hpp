// Input validation helpers shared by the sources (not installed).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <hullcheck/errors.hpp>
#include <hullcheck/limits.hpp>
#include <string>

namespace hullcheck::detail {

/// Throws InputError "<what> must be finite and >= 0 (got <value>)" unless value is.
inline void require_non_negative(double value, const char* what) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw InputError(std::string(what) + " must be finite and >= 0 (got " + std::to_string(value) +
                     ")");
  }
}

/// Throws InputError "<what> must be finite, >= 0 and at most 1e6 m (got <value>)" unless the
/// value is a length in [0, kMaxLength] (NaN fails every comparison).
inline void require_length(double value, const char* what) {
  if (!(value >= 0.0 && value <= kMaxLength)) {
    throw InputError(std::string(what) + " must be finite, >= 0 and at most 1e6 m (got " +
                     std::to_string(value) + ")");
  }
}

/// True when `pose` is usable by a query: every translation component within kMaxLength (which
/// rejects NaN and infinity), and the linear part a rotation to kRotationTolerance (columns c0,
/// c1 orthonormal and c2 = c0 x c1, which also excludes reflections). About 30 flops.
inline bool pose_is_rigid(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix4d& m = pose.matrix();
  const double tx = m(0, 3), ty = m(1, 3), tz = m(2, 3);
  const double x0 = m(0, 0), y0 = m(1, 0), z0 = m(2, 0);
  const double x1 = m(0, 1), y1 = m(1, 1), z1 = m(2, 1);
  const double e00 = x0 * x0 + y0 * y0 + z0 * z0 - 1.0;
  const double e11 = x1 * x1 + y1 * y1 + z1 * z1 - 1.0;
  const double e01 = x0 * x1 + y0 * y1 + z0 * z1;
  const double cx = y0 * z1 - z0 * y1 - m(0, 2);
  const double cy = z0 * x1 - x0 * z1 - m(1, 2);
  const double cz = x0 * y1 - y0 * x1 - m(2, 2);
  constexpr double t = kRotationTolerance;
  // Comparisons that NaN fails, combined with & (not &&): no branch per entry.
  const bool translation_ok =
      (std::abs(tx) <= kMaxLength) & (std::abs(ty) <= kMaxLength) & (std::abs(tz) <= kMaxLength);
  const bool rotation_ok = (std::abs(e00) <= t) & (std::abs(e11) <= t) & (std::abs(e01) <= t) &
                           (std::abs(cx) <= t) & (std::abs(cy) <= t) & (std::abs(cz) <= t);
  return translation_ok & rotation_ok;
}

}  // namespace hullcheck::detail
