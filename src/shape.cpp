#include <hullcheck/shape.hpp>

#include "detail/checks.hpp"
#include "detail/query_engine.hpp"

namespace hullcheck {

Shape Shape::inflated(double margin) const {
  detail::require_non_negative(margin, "Shape margin");
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
