// One sphere against many boxes, vectorised across the boxes with Highway (dispatched at run
// time, like ball_tests_block.cpp's kernels, which are vectorised across configurations).
#include "sphere_box_rows.hpp"

#include <cstddef>
#include <cstdint>

#include "ball_tests_block.hpp"

// Highway's order: this file is included again once per SIMD target.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "scene/sphere_box_rows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
// clang-format on

HWY_BEFORE_NAMESPACE();
namespace hullcheck {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Per box of the columns [j, j + Lanes(d)): the sphere centre's coordinates in the box frame,
// minus the half extents (> 0: beyond that face pair); returns the centre's squared distance
// from the box (0 inside).
template <class D, class V>
HWY_INLINE V excesses(D d, const double* rows, std::size_t padded, std::size_t j, const double* c,
                      V* excess) {
  const auto row = [&](std::size_t r) { return hn::LoadU(d, rows + r * padded + j); };
  const V dx = hn::Sub(hn::Set(d, c[0]), row(9));
  const V dy = hn::Sub(hn::Set(d, c[1]), row(10));
  const V dz = hn::Sub(hn::Set(d, c[2]), row(11));
  for (std::size_t r = 0; r < 3; ++r) {
    V local = hn::Mul(dx, row(3 * r));
    local = hn::MulAdd(dy, row(3 * r + 1), local);
    local = hn::MulAdd(dz, row(3 * r + 2), local);
    excess[r] = hn::Sub(hn::Abs(local), row(12 + r));
  }
  V outside2 = hn::Zero(d);
  for (std::size_t r = 0; r < 3; ++r) {
    const V beyond = hn::Max(excess[r], hn::Zero(d));
    outside2 = hn::MulAdd(beyond, beyond, outside2);
  }
  return outside2;
}

void SphereClearOfBoxRows(const double* rows, std::size_t padded, const double* c, double radius,
                          double slack, std::uint64_t* bits) {
  const hn::CappedTag<double, 8> d;  // at most 8 lanes: a multiple of them pads the rows
  const std::size_t lanes = hn::Lanes(d);
  const auto reach = hn::Set(d, radius + slack);
  const auto reach2 = hn::Mul(reach, reach);
  for (std::size_t w = 0; w < (padded + 63) / 64; ++w) bits[w] = 0;
  for (std::size_t j = 0; j < padded; j += lanes) {
    hn::Vec<decltype(d)> excess[3];
    const auto outside2 = excesses(d, rows, padded, j, c, excess);
    std::uint8_t mask[8] = {};
    hn::StoreMaskBits(d, hn::Gt(outside2, reach2), mask);
    bits[j / 64] |= static_cast<std::uint64_t>(mask[0]) << (j % 64);
  }
}

void SphereBoxRowGaps(const double* rows, std::size_t padded, const double* c, double radius,
                      double* gaps) {
  const hn::CappedTag<double, 8> d;  // at most 8 lanes: a multiple of them pads the rows
  const std::size_t lanes = hn::Lanes(d);
  const auto r = hn::Set(d, radius);
  for (std::size_t j = 0; j < padded; j += lanes) {
    hn::Vec<decltype(d)> excess[3];
    const auto outside = hn::Sqrt(excesses(d, rows, padded, j, c, excess));
    const auto deepest = hn::Max(hn::Max(excess[0], excess[1]), excess[2]);
    const auto gap = hn::IfThenElse(hn::Gt(outside, hn::Zero(d)), outside, deepest);
    hn::StoreU(hn::Sub(gap, r), d, gaps + j);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hullcheck
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hullcheck::detail {

HWY_EXPORT(SphereClearOfBoxRows);
HWY_EXPORT(SphereBoxRowGaps);

std::size_t box_rows_padded(std::size_t count) { return (count + 7) / 8 * 8; }

std::vector<double> pack_box_rows(const double* boxes, std::size_t count) {
  const std::size_t padded = box_rows_padded(count);
  std::vector<double> rows(kBoxValues * padded, 0.0);
  for (std::size_t j = 0; j < count; ++j) {
    for (std::size_t v = 0; v < kBoxValues; ++v) rows[v * padded + j] = boxes[j * kBoxValues + v];
  }
  return rows;
}

void sphere_clear_of_box_rows(const double* rows, std::size_t padded, const double* c,
                              double radius, double slack, std::uint64_t* bits) {
  HWY_DYNAMIC_DISPATCH(SphereClearOfBoxRows)(rows, padded, c, radius, slack, bits);
}

void sphere_box_row_gaps(const double* rows, std::size_t padded, const double* c, double radius,
                         double* gaps) {
  HWY_DYNAMIC_DISPATCH(SphereBoxRowGaps)(rows, padded, c, radius, gaps);
}

}  // namespace hullcheck::detail
#endif  // HWY_ONCE
