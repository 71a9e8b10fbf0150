// The range of sizes hullcheck answers for, in one place.
#pragma once

namespace hullcheck {

/// Largest magnitude, in metres, of every length hullcheck accepts: primitive dimensions,
/// margins, hull vertex coordinates and pose translations (1e6 m = 1000 km). Larger values are
/// rejected with InputError, so that no intermediate product in GJK/EPA can overflow (the
/// largest squared quantity stays below 1e14 m^2, far from double's 1e308).
inline constexpr double kMaxLength = 1e6;

/// Smallest length scale, in metres, at which tolerances stay relative: a query's scale is
/// taken as at least this, so answers are exact to QueryOptions::relative_tolerance x 1e-6 m
/// (1e-16 m by default) for shapes smaller than a micrometre. Smaller shapes (and size 0: a
/// point, a flat box) are accepted.
inline constexpr double kMinScale = 1e-6;

/// Largest deviation of a pose's linear part from a rotation: the sum of |c0.c0 - 1|,
/// |c1.c1 - 1|, |c0.c1| and the absolute components of c0 x c1 - c2 (columns c0, c1, c2) must
/// not exceed it. Rotations built in double precision deviate by ~1e-15.
inline constexpr double kRotationTolerance = 1e-6;

}  // namespace hullcheck
