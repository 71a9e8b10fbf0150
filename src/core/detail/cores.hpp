// Shape -> core dispatch: a shape is a core (point, segment, box, cylinder, hull) grown by a
// radius; the engine is templated on the core types so that their support functions inline.
#pragma once

#include <cmath>
#include <hullcheck/core/shape.hpp>
#include <variant>

#include "support.hpp"

namespace hullcheck::detail {

/// Largest distance of a point of the core from its local origin.
template <class Core>
double core_extent(const Core& core);
inline double core_extent(const PointCore&) { return 0.0; }
inline double core_extent(const SegmentCore& c) { return c.half_length; }
inline double core_extent(const BoxCore& c) { return c.half.norm(); }
inline double core_extent(const CylinderCore& c) {
  return std::sqrt(c.radius * c.radius + c.half_length * c.half_length);
}
inline double core_extent(const HullCore& c) { return c.data->extent; }

/// Calls f(core, radius) with the shape's core and its total radius (own + margin).
template <class F>
decltype(auto) with_core(const Shape& shape, F&& f) {
  const double margin = shape.margin();
  switch (shape.kind()) {
    case ShapeKind::kSphere:
      return f(PointCore{}, std::get<Sphere>(shape.geometry()).radius + margin);
    case ShapeKind::kCapsule: {
      const Capsule& c = std::get<Capsule>(shape.geometry());
      return f(SegmentCore{c.half_length}, c.radius + margin);
    }
    case ShapeKind::kBox:
      return f(BoxCore{std::get<Box>(shape.geometry()).half_extents}, margin);
    case ShapeKind::kCylinder: {
      const Cylinder& c = std::get<Cylinder>(shape.geometry());
      return f(CylinderCore{c.radius, c.half_length}, margin);
    }
    case ShapeKind::kConvexHull:
    default:
      return f(HullCore{&std::get<ConvexHull>(shape.geometry()).data()}, margin);
  }
}

/// Calls f(core_a, radius_a, core_b, radius_b) with both shapes' cores and radii.
template <class F>
decltype(auto) with_cores(const Shape& a, const Shape& b, F&& f) {
  return with_core(a, [&](const auto& core_a, double radius_a) {
    return with_core(b, [&](const auto& core_b, double radius_b) {
      return f(core_a, radius_a, core_b, radius_b);
    });
  });
}

}  // namespace hullcheck::detail
