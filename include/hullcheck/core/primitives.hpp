// Exact primitive shapes. Each is centred on its local origin; lengths in metres (any unit works,
// as long as it is used consistently). Axis-symmetric shapes have their axis along local z.
// Every constructor throws InputError unless each length is finite, >= 0 and at most
// kMaxLength (1e6 m, limits.hpp); Shape checks the public fields again when it is built.
#pragma once

#include <Eigen/Core>

namespace hullcheck {

/// Ball of `radius` around the local origin. Radius >= 0 (0 is a point).
struct Sphere {
  explicit Sphere(double radius);
  double radius;
};

/// Segment from (0,0,-half_length) to (0,0,+half_length) grown by `radius` (a "pill").
/// `length` is the length of the straight part, without the caps (URDF/FCL convention).
struct Capsule {
  Capsule(double radius, double length);
  double radius;
  double half_length;
};

/// Axis-aligned box centred on the local origin. Constructed from the full side lengths
/// (URDF `<box size>` convention); stores half extents.
struct Box {
  Box(double size_x, double size_y, double size_z);
  explicit Box(const Eigen::Vector3d& sizes);
  Eigen::Vector3d half_extents;
};

/// Solid circular cylinder of `radius`, axis along local z, total `length` (URDF convention),
/// centred on the local origin. Exact (not tessellated): its support function is analytic.
struct Cylinder {
  Cylinder(double radius, double length);
  double radius;
  double half_length;
};

}  // namespace hullcheck
