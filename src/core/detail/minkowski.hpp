// Support of the Minkowski difference A - B of two cores, in A's local frame.
#pragma once

#include <Eigen/Geometry>

#include "simplex.hpp"
#include "support.hpp"

namespace hullcheck::detail {

/// A - B with B placed relative to A: x_A = rotation * x_B + translation. After each support
/// call, index_a and index_b hold the hull vertices it returned (-1 for other cores).
template <class CoreA, class CoreB>
struct MinkowskiDifference {
  const CoreA& a;
  const CoreB& b;
  Eigen::Matrix3d rotation;     // B's frame to A's frame
  Eigen::Vector3d translation;  // B's origin in A's frame
  int index_a = -1;
  int index_b = -1;

  MinkowskiDifference(const CoreA& core_a, const CoreB& core_b, const Eigen::Matrix3d& b_to_a,
                      const Eigen::Vector3d& b_origin_in_a)
      : a(core_a), b(core_b), rotation(b_to_a), translation(b_origin_in_a) {}

  /// Support point w = pa - pb of A - B in direction d (A's frame), with its parts.
  /// `hint_a`, `hint_b`: vertex indices of support points in a nearby direction, or -1
  /// (see support_near).
  void support(const Eigen::Vector3d& d, Eigen::Vector3d& w, Eigen::Vector3d& pa,
               Eigen::Vector3d& pb, int hint_a = -1, int hint_b = -1) {
    // Written out by columns: Eigen's products with a transpose or a negated operand are
    // out-of-line calls in GCC.
    pa = support_near(a, d, hint_a, index_a);
    const Eigen::Vector3d d_b(-rotation.col(0).dot(d), -rotation.col(1).dot(d),
                              -rotation.col(2).dot(d));
    pb = place_b(support_near(b, d_b, hint_b, index_b));
    w = pa - pb;
  }
  /// A point of B's frame in A's frame.
  Eigen::Vector3d place_b(const Eigen::Vector3d& x) const {
    return rotation.col(0) * x.x() + rotation.col(1) * x.y() + rotation.col(2) * x.z() +
           translation;
  }
  void support(const Eigen::Vector3d& d, SimplexVertex& out) { support(d, out.w, out.a, out.b); }
};

}  // namespace hullcheck::detail
