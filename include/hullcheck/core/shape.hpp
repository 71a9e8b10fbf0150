// Shape: any convex shape hullcheck can query, optionally inflated by a margin.
#pragma once

#include <hullcheck/core/convex_hull.hpp>
#include <hullcheck/core/limits.hpp>
#include <hullcheck/core/primitives.hpp>
#include <variant>

namespace hullcheck {

/// What a Shape is made of, without its margin.
enum class ShapeKind { kSphere, kCapsule, kBox, kCylinder, kConvexHull };

/// A convex shape in its local frame: one primitive or hull, grown by `margin` (>= 0) in every
/// direction (the Minkowski sum with a ball of that radius, e.g. link padding). Implicitly
/// constructible from each primitive and from ConvexHull, so queries accept them directly.
/// Cheap to copy (hull data is shared). Thread-safe for concurrent reads.
///
/// The primitives' fields are public, so each constructor checks them again: every dimension
/// finite, >= 0 and at most kMaxLength (1e6 m); otherwise InputError naming the field. A Shape
/// therefore always holds valid geometry, and its geometry cannot be changed afterwards.
class Shape {
 public:
  using Geometry = std::variant<Sphere, Capsule, Box, Cylinder, ConvexHull>;

  Shape(const Sphere& s);      // NOLINT(google-explicit-constructor)
  Shape(const Capsule& c);     // NOLINT(google-explicit-constructor)
  Shape(const Box& b);         // NOLINT(google-explicit-constructor)
  Shape(const Cylinder& c);    // NOLINT(google-explicit-constructor)
  Shape(const ConvexHull& h);  // NOLINT(google-explicit-constructor)

  /// The same geometry grown by `margin` metres (finite, >= 0, and the total margin at most
  /// kMaxLength; throws InputError otherwise). Margins add: inflated(a).inflated(b) has margin
  /// a + b.
  Shape inflated(double margin) const;

  ShapeKind kind() const { return static_cast<ShapeKind>(geometry_.index()); }
  const Geometry& geometry() const { return geometry_; }
  double margin() const { return margin_; }
  /// Radius of a ball about the local origin that contains the shape (margin included).
  double bounding_radius() const;
  /// Support point of the inflated shape in local frame: argmax over the shape of dot(p, d).
  Eigen::Vector3d support(const Eigen::Vector3d& direction) const;

 private:
  Geometry geometry_;
  double margin_ = 0.0;
};

}  // namespace hullcheck
