#include <hullcheck/core/primitives.hpp>

#include "detail/checks.hpp"

namespace hullcheck {

using detail::require_length;

Sphere::Sphere(double r) : radius(r) { require_length(r, "Sphere radius"); }

Capsule::Capsule(double r, double length) : radius(r), half_length(0.5 * length) {
  require_length(r, "Capsule radius");
  require_length(length, "Capsule length");
}

Box::Box(double size_x, double size_y, double size_z)
    : Box(Eigen::Vector3d(size_x, size_y, size_z)) {}

Box::Box(const Eigen::Vector3d& sizes) : half_extents(0.5 * sizes) {
  require_length(sizes.x(), "Box size x");
  require_length(sizes.y(), "Box size y");
  require_length(sizes.z(), "Box size z");
}

Cylinder::Cylinder(double r, double length) : radius(r), half_length(0.5 * length) {
  require_length(r, "Cylinder radius");
  require_length(length, "Cylinder length");
}

}  // namespace hullcheck
