// Tolerances and iteration caps of the proximity queries, all in one place.
#pragma once

namespace hullcheck {

/// Tolerance model. Every tolerance is relative: it is multiplied by the query's scale,
///   scale = max(extent(A), extent(B), kMinScale = 1e-6 m),
/// where extent is the largest distance of a point of the shape (margin included) from its local
/// origin. Answers are exact up to `relative_tolerance * scale`:
///  - distance and depth are within that of the true value (for polytopes and exact primitives);
///  - intersect's verdict is right whenever the true distance or depth exceeds it; inside that
///    band (touching contact) either verdict may be returned.
///  - normals and witness points are exact to the same order on flat features (polytopes, box
///    faces); where the nearest feature is curved (cylinder rim, sphere, margin) a distance
///    exact to eps fixes the direction only to about sqrt(2 eps / curvature radius).
/// Curved cores (cylinders) converge geometrically. Near touching contact GJK's simplex can
/// become a sliver that stops improving in double precision; GJK then restarts from its newest
/// support point (at most 6 times), which brings the distance back within the tolerance, but the
/// proven lower bound may still lag: such answers carry status kDegenerate (or kIterationCap).
/// When that bracket reaches contact, a boolean GJK settles the sign (and EPA the depth).
/// Measured on shapes resting on a face within 1e-7 x size (test NearTouchingOnAFace): every
/// answer within the tolerance, whatever its status.
struct QueryOptions {
  /// Convergence tolerance relative to scale (see above). 1e-10 leaves a margin of 10x to
  /// the 1e-9 accuracy the tests check, and is ~1e6 x double precision.
  double relative_tolerance = 1e-10;
  /// GJK iteration cap (each iteration adds one support point). Polytopes need < 30 in practice.
  int max_gjk_iterations = 128;
  /// EPA iteration cap (each iteration adds one polytope vertex). Bounded by storage too.
  int max_epa_iterations = 250;
};

}  // namespace hullcheck
