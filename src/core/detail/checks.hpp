// Input validation helpers shared by the sources (not installed).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/limits.hpp>
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

/// True when both poses are usable by a query: every translation component within kMaxLength
/// (which rejects NaN and infinity), and each linear part a rotation to kRotationTolerance: the
/// sum of |c0.c0 - 1|, |c1.c1 - 1|, |c0.c1| and the absolute components of c0 x c1 - c2
/// (columns c0, c1, c2) at most the tolerance, which also excludes reflections. The two poses
/// are checked side by side in the two lanes of one SSE2 register (about 40 packed operations).
inline bool poses_are_rigid(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  using Lanes = Eigen::Array2d;
  const Eigen::Matrix4d& ma = a.matrix();
  const Eigen::Matrix4d& mb = b.matrix();
  const auto lanes = [&](int i, int j) { return Lanes(ma(i, j), mb(i, j)); };
  const Lanes x0 = lanes(0, 0), y0 = lanes(1, 0), z0 = lanes(2, 0);
  const Lanes x1 = lanes(0, 1), y1 = lanes(1, 1), z1 = lanes(2, 1);
  const Lanes tx = lanes(0, 3), ty = lanes(1, 3), tz = lanes(2, 3);
  const Lanes e00 = x0 * x0 + y0 * y0 + z0 * z0 - 1.0;
  const Lanes e11 = x1 * x1 + y1 * y1 + z1 * z1 - 1.0;
  const Lanes e01 = x0 * x1 + y0 * y1 + z0 * z1;
  const Lanes cx = y0 * z1 - z0 * y1 - lanes(0, 2);
  const Lanes cy = z0 * x1 - x0 * z1 - lanes(1, 2);
  const Lanes cz = x0 * y1 - y0 * x1 - lanes(2, 2);
  // Sums propagate NaN (a maximum would drop it); the translation's NaN or infinity turns its
  // zero multiple into NaN.
  const Lanes rotation_error = e00.abs() + e11.abs() + e01.abs() + cx.abs() + cy.abs() + cz.abs();
  const Lanes translation = tx.abs().max(ty.abs()).max(tz.abs()) + 0.0 * (tx + ty + tz);
  return ((rotation_error <= kRotationTolerance) && (translation <= kMaxLength)).all();
}

/// poses_are_rigid for one pose.
inline bool pose_is_rigid(const Eigen::Isometry3d& pose) { return poses_are_rigid(pose, pose); }

}  // namespace hullcheck::detail
