// is_valid_batch's ball tests for a block of kPoseBlockLanes configurations, vectorised across
// the lanes with Highway (dispatched at run time, like the block forward kinematics). Spheres
// come as rows of kPoseBlockLanes values: x, y, z, radius per sphere. A lane's bit in a mask is
// set when the test proves its sphere(s) clear, by more than `slack`.
#include "ball_tests_block.hpp"

#include <cstddef>
#include <cstdint>
#include <hullcheck/robot/link_pose_block.hpp>

// Highway's order: this file is included again once per SIMD target.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "scene/ball_tests_block.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
// clang-format on

#include "box_distance_inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace hullcheck {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

constexpr std::size_t kL = kPoseBlockLanes;

// Lane bits of `mask` for lanes [base, base + Lanes(d)).
template <class D, class M>
HWY_INLINE std::uint32_t lane_bits(D d, M mask, std::size_t base) {
  std::uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, mask, bytes);
  return static_cast<std::uint32_t>(bytes[0]) << base;
}

void PlaceSpheres(const double* pose, const double* spheres, std::size_t n, double* out) {
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  for (std::size_t base = 0; base < kL; base += lanes) {
    hn::Vec<decltype(d)> p[12];  // the pose's rows, loaded once for all the spheres
    for (std::size_t e = 0; e < 12; ++e) p[e] = hn::LoadU(d, pose + e * kL + base);
    for (std::size_t i = 0; i < n; ++i) {
      const double* c = spheres + 4 * i;
      double* o = out + i * 4 * kL + base;
      const auto cx = hn::Set(d, c[0]), cy = hn::Set(d, c[1]), cz = hn::Set(d, c[2]);
      for (std::size_t r = 0; r < 3; ++r) {
        auto v = hn::MulAdd(p[3 * r], cx, p[9 + r]);
        v = hn::MulAdd(p[3 * r + 1], cy, v);
        v = hn::MulAdd(p[3 * r + 2], cz, v);
        hn::StoreU(v, d, o + r * kL);
      }
      hn::StoreU(hn::Set(d, c[3]), d, o + 3 * kL);
    }
  }
}

void SpheresClearOfBoxes(const double* spheres, std::size_t n, const double* boxes, std::size_t m,
                         double slack, std::uint8_t* out) {
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  for (std::size_t i = 0; i < n; ++i) {
    const double* s = spheres + i * 4 * kL;
    for (std::size_t j = 0; j < m; ++j) {
      const double* b = boxes + j * detail::kBoxValues;
      std::uint32_t bits = 0;
      for (std::size_t base = 0; base < kL; base += lanes) {
        const auto gap2 = box_distance2(d, hn::LoadU(d, s + base), hn::LoadU(d, s + kL + base),
                                        hn::LoadU(d, s + 2 * kL + base), b);
        const auto reach = hn::Add(hn::LoadU(d, s + 3 * kL + base), hn::Set(d, slack));
        bits |= lane_bits(d, hn::Gt(gap2, hn::Mul(reach, reach)), base);
      }
      out[i * m + j] = static_cast<std::uint8_t>(bits);
    }
  }
}

std::uint8_t SpheresInBox(const double* spheres, std::size_t n, const double* box, double slack) {
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  std::uint32_t bits = 0;
  for (std::size_t base = 0; base < kL; base += lanes) {
    auto meets = hn::Not(hn::FirstN(d, lanes));  // no lane, so far
    for (std::size_t i = 0; i < n; ++i) {
      const double* s = spheres + i * 4 * kL + base;
      const auto gap2 =
          box_distance2(d, hn::LoadU(d, s), hn::LoadU(d, s + kL), hn::LoadU(d, s + 2 * kL), box);
      // The ball reaches into the box by more than the slack: its centre is closer to the box
      // than radius - slack (and that is positive).
      const auto depth = hn::Sub(hn::LoadU(d, s + 3 * kL), hn::Set(d, slack));
      meets =
          hn::Or(meets, hn::And(hn::Gt(depth, hn::Zero(d)), hn::Lt(gap2, hn::Mul(depth, depth))));
    }
    bits |= lane_bits(d, meets, base);
  }
  return static_cast<std::uint8_t>(bits);
}

std::uint8_t SpheresApart(const double* a, std::size_t na, const double* b, std::size_t nb,
                          double slack) {
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  std::uint32_t all = 0;
  for (std::size_t base = 0; base < kL; base += lanes) {
    auto apart = hn::FirstN(d, lanes);  // every lane, so far
    for (std::size_t i = 0; i < na; ++i) {
      const double* p = a + i * 4 * kL + base;
      const auto px = hn::LoadU(d, p), py = hn::LoadU(d, p + kL), pz = hn::LoadU(d, p + 2 * kL);
      const auto pr = hn::Add(hn::LoadU(d, p + 3 * kL), hn::Set(d, slack));
      for (std::size_t j = 0; j < nb; ++j) {
        const double* q = b + j * 4 * kL + base;
        const auto dx = hn::Sub(px, hn::LoadU(d, q));
        const auto dy = hn::Sub(py, hn::LoadU(d, q + kL));
        const auto dz = hn::Sub(pz, hn::LoadU(d, q + 2 * kL));
        const auto r = hn::Add(pr, hn::LoadU(d, q + 3 * kL));
        const auto dist2 = hn::MulAdd(dz, dz, hn::MulAdd(dy, dy, hn::Mul(dx, dx)));
        apart = hn::And(apart, hn::Gt(dist2, hn::Mul(r, r)));
      }
    }
    all |= lane_bits(d, apart, base);
  }
  return static_cast<std::uint8_t>(all);
}

void SpherePairsApart(const double* spheres, const int* pairs, std::size_t count, double slack,
                      std::uint8_t* out) {
  for (std::size_t k = 0; k < count; ++k) {
    out[k] = SpheresApart(spheres + static_cast<std::size_t>(pairs[2 * k]) * 4 * kL, 1,
                          spheres + static_cast<std::size_t>(pairs[2 * k + 1]) * 4 * kL, 1, slack);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hullcheck
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hullcheck::detail {

HWY_EXPORT(PlaceSpheres);
HWY_EXPORT(SpheresClearOfBoxes);
HWY_EXPORT(SpheresApart);
HWY_EXPORT(SpherePairsApart);
HWY_EXPORT(SpheresInBox);

void place_spheres(const double* pose, const double* spheres, std::size_t n, double* out) {
  HWY_DYNAMIC_DISPATCH(PlaceSpheres)(pose, spheres, n, out);
}

std::uint8_t spheres_in_box(const double* spheres, std::size_t n, const double* box, double slack) {
  return HWY_DYNAMIC_DISPATCH(SpheresInBox)(spheres, n, box, slack);
}

void spheres_clear_of_boxes(const double* spheres, std::size_t n, const double* boxes,
                            std::size_t m, double slack, std::uint8_t* out) {
  HWY_DYNAMIC_DISPATCH(SpheresClearOfBoxes)(spheres, n, boxes, m, slack, out);
}

void sphere_pairs_apart(const double* spheres, const int* pairs, std::size_t count, double slack,
                        std::uint8_t* out) {
  HWY_DYNAMIC_DISPATCH(SpherePairsApart)(spheres, pairs, count, slack, out);
}

std::uint8_t spheres_apart(const double* a, std::size_t na, const double* b, std::size_t nb,
                           double slack) {
  return HWY_DYNAMIC_DISPATCH(SpheresApart)(a, na, b, nb, slack);
}

}  // namespace hullcheck::detail
#endif  // HWY_ONCE
