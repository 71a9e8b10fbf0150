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

#include "box_distance_inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace hullcheck {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The sphere centre's squared distance from the boxes of the columns [j, j + Lanes(d)), and
// *deepest as box_distance2's.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V column_distance2(D d, const double* rows, std::size_t padded, std::size_t j,
                              const double* c, V* deepest = nullptr) {
  return box_distance2(
      d, hn::Set(d, c[0]), hn::Set(d, c[1]), hn::Set(d, c[2]),
      [&](std::size_t r) { return hn::LoadU(d, rows + r * padded + j); }, deepest);
}

void SphereClearOfBoxRows(const double* rows, std::size_t padded, const double* c, double radius,
                          double slack, std::uint64_t* bits) {
  const hn::CappedTag<double, 8> d;  // at most 8 lanes: a multiple of them pads the rows
  const std::size_t lanes = hn::Lanes(d);
  const auto reach = hn::Set(d, radius + slack);
  const auto reach2 = hn::Mul(reach, reach);
  for (std::size_t w = 0; w < (padded + 63) / 64; ++w) bits[w] = 0;
  for (std::size_t j = 0; j < padded; j += lanes) {
    const auto outside2 = column_distance2(d, rows, padded, j, c);
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
    auto deepest = hn::Zero(d);
    const auto outside = hn::Sqrt(column_distance2(d, rows, padded, j, c, &deepest));
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
