// Per SIMD target (Highway's -inl.h convention: a per-target include guard, included after
// <hwy/highway.h> in each foreach_target pass): the squared distance from points to an oriented
// box, shared by the kernels vectorised across configurations (ball_tests_block.cpp,
// ball_gaps_block.cpp: one box, its values broadcast) and across boxes (sphere_box_rows.cpp: one
// point, the boxes' values loaded from rows).

// Per-target include guard.
#if defined(HULLCHECK_SCENE_BOX_DISTANCE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HULLCHECK_SCENE_BOX_DISTANCE_INL_H_
#undef HULLCHECK_SCENE_BOX_DISTANCE_INL_H_
#else
#define HULLCHECK_SCENE_BOX_DISTANCE_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>

HWY_BEFORE_NAMESPACE();
namespace hullcheck {
namespace HWY_NAMESPACE {

/// The squared distance (m^2) from the points (x, y, z lanes, model frame) to the box whose
/// kBoxValues values (ball_tests_block.hpp: the world-to-box rotation row by row, the centre,
/// the half extents) `value(i)` gives as vectors; 0 inside. *deepest, when given: the largest
/// of the points' box-frame coordinates' excesses over the half extents (negative inside: minus
/// the depth below the nearest face).
template <class D, class V, class BoxValue>
HWY_INLINE V box_distance2(D d, V x, V y, V z, const BoxValue& value, V* deepest = nullptr) {
  namespace hn = hwy::HWY_NAMESPACE;
  const V dx = hn::Sub(x, value(9));
  const V dy = hn::Sub(y, value(10));
  const V dz = hn::Sub(z, value(11));
  V distance2 = hn::Zero(d);
  for (std::size_t r = 0; r < 3; ++r) {
    V local = hn::Mul(dx, value(3 * r));
    local = hn::MulAdd(dy, value(3 * r + 1), local);
    local = hn::MulAdd(dz, value(3 * r + 2), local);
    const V excess = hn::Sub(hn::Abs(local), value(12 + r));
    if (deepest != nullptr) *deepest = r == 0 ? excess : hn::Max(*deepest, excess);
    const V beyond = hn::Max(excess, hn::Zero(d));
    distance2 = hn::MulAdd(beyond, beyond, distance2);
  }
  return distance2;
}

/// box_distance2 for one box given as kBoxValues doubles, broadcast to every lane.
template <class D, class V>
HWY_INLINE V box_distance2(D d, V x, V y, V z, const double* box) {
  return box_distance2(d, x, y, z,
                       [&](std::size_t i) { return hwy::HWY_NAMESPACE::Set(d, box[i]); });
}

}  // namespace HWY_NAMESPACE
}  // namespace hullcheck
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
