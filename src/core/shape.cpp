#include <hullcheck/core/shape.hpp>

#include "detail/checks.hpp"
#include "detail/cores.hpp"

namespace hullcheck {

using detail::require_length;

// The primitives' constructors check their arguments, but their fields are public: checked
// again here, where they become a Shape (a few comparisons).
Shape::Shape(const Sphere& s) : geometry_(s) { require_length(s.radius, "Shape: Sphere radius"); }

Shape::Shape(const Capsule& c) : geometry_(c) {
  require_length(c.radius, "Shape: Capsule radius");
  require_length(2.0 * c.half_length, "Shape: Capsule length");
}

Shape::Shape(const Box& b) : geometry_(b) {
  require_length(2.0 * b.half_extents.x(), "Shape: Box size x");
  require_length(2.0 * b.half_extents.y(), "Shape: Box size y");
  require_length(2.0 * b.half_extents.z(), "Shape: Box size z");
}

Shape::Shape(const Cylinder& c) : geometry_(c) {
  require_length(c.radius, "Shape: Cylinder radius");
  require_length(2.0 * c.half_length, "Shape: Cylinder length");
}

// ConvexHull's data is immutable and checked by its constructor.
Shape::Shape(const ConvexHull& h) : geometry_(h) {}

Shape Shape::inflated(double margin) const {
  detail::require_non_negative(margin, "Shape margin");
  require_length(margin_ + margin, "Shape margin (total)");
  Shape copy = *this;
  copy.margin_ += margin;
  return copy;
}

double Shape::bounding_radius() const {
  return detail::with_core(
      *this, [](const auto& core, double radius) { return detail::core_extent(core) + radius; });
}

Eigen::Vector3d Shape::support(const Eigen::Vector3d& direction) const {
  return detail::with_core(*this, [&](const auto& core, double radius) -> Eigen::Vector3d {
    int index = -1;
    const Eigen::Vector3d p = core.support(direction, index);
    const double length = direction.norm();
    if (radius == 0.0 || !(length > 0.0)) return p;
    return p + (radius / length) * direction;
  });
}

}  // namespace hullcheck
