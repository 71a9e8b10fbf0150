// clearance_lower_bound_batch's gap kernels for a block of kPoseBlockLanes configurations,
// vectorised across the lanes with Highway (dispatched at run time, like the block forward
// kinematics and is_valid_batch's ball tests, ball_tests_block.cpp).
#include "ball_gaps_block.hpp"

#include <cstddef>
#include <hullcheck/robot/link_pose_block.hpp>

// Highway's order: this file is included again once per SIMD target.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "scene/ball_gaps_block.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
// clang-format on

#include "box_distance_inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace hullcheck {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

constexpr std::size_t kL = kPoseBlockLanes;

void LowerSphereBoxGap(const double* spheres, std::size_t n, const double* b, double* gap) {
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  for (std::size_t base = 0; base < kL; base += lanes) {
    auto lowest = hn::LoadU(d, gap + base);
    for (std::size_t i = 0; i < n; ++i) {
      const double* s = spheres + i * 4 * kL + base;
      const auto outside2 =
          box_distance2(d, hn::LoadU(d, s), hn::LoadU(d, s + kL), hn::LoadU(d, s + 2 * kL), b);
      lowest = hn::Min(lowest, hn::Sub(hn::Sqrt(outside2), hn::LoadU(d, s + 3 * kL)));
    }
    hn::StoreU(lowest, d, gap + base);
  }
}

void LowerSpherePairGap(const double* a, std::size_t na, const double* b, std::size_t nb,
                        double* gap) {
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  for (std::size_t base = 0; base < kL; base += lanes) {
    auto lowest = hn::LoadU(d, gap + base);
    for (std::size_t i = 0; i < na; ++i) {
      const double* p = a + i * 4 * kL + base;
      const auto px = hn::LoadU(d, p), py = hn::LoadU(d, p + kL), pz = hn::LoadU(d, p + 2 * kL);
      const auto pr = hn::LoadU(d, p + 3 * kL);
      for (std::size_t j = 0; j < nb; ++j) {
        const double* q = b + j * 4 * kL + base;
        const auto dx = hn::Sub(px, hn::LoadU(d, q));
        const auto dy = hn::Sub(py, hn::LoadU(d, q + kL));
        const auto dz = hn::Sub(pz, hn::LoadU(d, q + 2 * kL));
        const auto dist = hn::Sqrt(hn::MulAdd(dz, dz, hn::MulAdd(dy, dy, hn::Mul(dx, dx))));
        lowest = hn::Min(lowest, hn::Sub(dist, hn::Add(pr, hn::LoadU(d, q + 3 * kL))));
      }
    }
    hn::StoreU(lowest, d, gap + base);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hullcheck
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hullcheck::detail {

HWY_EXPORT(LowerSphereBoxGap);
HWY_EXPORT(LowerSpherePairGap);

void lower_sphere_box_gap(const double* spheres, std::size_t n, const double* box, double* gap) {
  HWY_DYNAMIC_DISPATCH(LowerSphereBoxGap)(spheres, n, box, gap);
}

void lower_sphere_pair_gap(const double* a, std::size_t na, const double* b, std::size_t nb,
                           double* gap) {
  HWY_DYNAMIC_DISPATCH(LowerSpherePairGap)(a, na, b, nb, gap);
}

}  // namespace hullcheck::detail
#endif  // HWY_ONCE
