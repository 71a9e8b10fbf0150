// RobotModel::compute_link_poses_block: forward kinematics of kPoseBlockLanes configurations
// at once, vectorised across them with Highway (compiled for every x86 target Highway knows,
// the best the CPU supports chosen at run time: SSE2 to AVX-512; scalar elsewhere). The same
// steps as compute_link_poses_unchecked (forward_kinematics.cpp), lane by lane:
//   pose[link] = pose[anchor] * offset * motion(value),  value = multiplier * q[variable] + offset
// with motion a rotation about the joint axis (Rodrigues; about a frame axis, two columns mixed
// by cos and sin) or a translation along it.
#include <cstddef>
#include <hullcheck/robot/link_pose_block.hpp>

#include "robot/kinematic_block_step.hpp"

// Highway's order: this file is included again once per SIMD target.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "robot/forward_kinematics_block.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>
// clang-format on

HWY_BEFORE_NAMESPACE();
namespace hullcheck {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The angle a minus the multiple k of 2 pi nearest to it, to within 1e-15 rad for |a| below
// 2^19 x 2 pi (3.3e6 rad, beyond RobotModel::kMaxContinuousValue; past it within |a| x 1e-16
// on CPUs without FMA): Highway's Sin and Cos are accurate on [-39000, 39000] only, and a
// continuous joint takes up to 1e6 rad. Cody-Waite: 2 pi split into c1 + c2 + c3, c1 and c2 of
// 34 significant bits, so that k c1 and k c2 are exact for |k| < 2^19 and a - k c1 is exact
// (Sterbenz); only the last two subtractions round.
template <class D, class V>
HWY_INLINE V reduce_angle(D d, V a) {
  const V k = hn::Round(hn::Mul(a, hn::Set(d, 0x1.45f306dc9c883p-3)));  // a / (2 pi)
  V r = hn::NegMulAdd(k, hn::Set(d, 0x1.921fb54480000p+2), a);
  r = hn::NegMulAdd(k, hn::Set(d, -0x1.e973dcb380000p-33), r);
  return hn::NegMulAdd(k, hn::Set(d, -0x1.9cceba3f91f19p-68), r);
}

// steps[0..n) in kinematic order; q: variable-major (kPoseBlockLanes values per variable);
// out: LinkPoseBlock::values.
void LinkPosesBlock(const detail::KinematicBlockStep* steps, std::size_t n, const double* q,
                    double* out) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  constexpr std::size_t kL = kPoseBlockLanes;
  for (std::size_t base = 0; base < kL; base += lanes) {
    for (std::size_t k = 0; k < n; ++k) {
      const detail::KinematicBlockStep& st = steps[k];
      V r[9], t[3];
      if (st.anchor < 0) {
        for (int e = 0; e < 9; ++e) r[e] = hn::Set(d, st.offset_rotation[e]);
        for (int e = 0; e < 3; ++e) t[e] = hn::Set(d, st.offset_translation[e]);
      } else {
        const double* a = out + static_cast<std::size_t>(st.anchor) * 12 * kL + base;
        V ar[9];
        for (int e = 0; e < 9; ++e) ar[e] = hn::LoadU(d, a + e * kL);
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) {
            V sum = hn::Mul(ar[3 * i], hn::Set(d, st.offset_rotation[j]));
            sum = hn::MulAdd(ar[3 * i + 1], hn::Set(d, st.offset_rotation[3 + j]), sum);
            r[3 * i + j] = hn::MulAdd(ar[3 * i + 2], hn::Set(d, st.offset_rotation[6 + j]), sum);
          }
          V sum = hn::LoadU(d, a + (9 + i) * kL);
          for (int j = 0; j < 3; ++j) {
            sum = hn::MulAdd(ar[3 * i + j], hn::Set(d, st.offset_translation[j]), sum);
          }
          t[i] = sum;
        }
      }
      if (st.type != detail::KinematicBlockStep::kFixed) {
        const V value =
            hn::MulAdd(hn::Set(d, st.multiplier),
                       hn::LoadU(d, q + static_cast<std::size_t>(st.variable) * kL + base),
                       hn::Set(d, st.offset));
        if (st.type == detail::KinematicBlockStep::kPrismatic) {
          for (int i = 0; i < 3; ++i) {
            V along = hn::Mul(r[3 * i], hn::Set(d, st.axis[0]));
            along = hn::MulAdd(r[3 * i + 1], hn::Set(d, st.axis[1]), along);
            along = hn::MulAdd(r[3 * i + 2], hn::Set(d, st.axis[2]), along);
            t[i] = hn::MulAdd(value, along, t[i]);
          }
        } else if (st.axis_index >= 0) {
          const V angle = reduce_angle(d, hn::Mul(value, hn::Set(d, st.axis_sign)));
          const V c = hn::Cos(d, angle);
          const V s = hn::Sin(d, angle);
          const int ci = (st.axis_index + 1) % 3;
          const int cj = (st.axis_index + 2) % 3;
          for (int i = 0; i < 3; ++i) {
            const V vi = r[3 * i + ci];
            const V vj = r[3 * i + cj];
            r[3 * i + ci] = hn::MulAdd(c, vi, hn::Mul(s, vj));
            r[3 * i + cj] = hn::NegMulAdd(s, vi, hn::Mul(c, vj));
          }
        } else {
          // Rodrigues: rot = c I + (1 - c) a a^T + s [a]x, then r <- r * rot.
          const V angle = reduce_angle(d, value);
          const V c = hn::Cos(d, angle);
          const V s = hn::Sin(d, angle);
          const V one_c = hn::Sub(hn::Set(d, 1.0), c);
          const double* ax = st.axis;
          V rot[9];
          for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
              rot[3 * i + j] = hn::Mul(one_c, hn::Set(d, ax[i] * ax[j]));
            }
            rot[4 * i] = hn::Add(rot[4 * i], c);
          }
          rot[1] = hn::NegMulAdd(s, hn::Set(d, ax[2]), rot[1]);  // (0,1) -= s z
          rot[2] = hn::MulAdd(s, hn::Set(d, ax[1]), rot[2]);     // (0,2) += s y
          rot[3] = hn::MulAdd(s, hn::Set(d, ax[2]), rot[3]);     // (1,0) += s z
          rot[5] = hn::NegMulAdd(s, hn::Set(d, ax[0]), rot[5]);  // (1,2) -= s x
          rot[6] = hn::NegMulAdd(s, hn::Set(d, ax[1]), rot[6]);  // (2,0) -= s y
          rot[7] = hn::MulAdd(s, hn::Set(d, ax[0]), rot[7]);     // (2,1) += s x
          V before[9];
          for (int e = 0; e < 9; ++e) before[e] = r[e];
          for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
              V sum = hn::Mul(before[3 * i], rot[j]);
              sum = hn::MulAdd(before[3 * i + 1], rot[3 + j], sum);
              r[3 * i + j] = hn::MulAdd(before[3 * i + 2], rot[6 + j], sum);
            }
          }
        }
      }
      double* p = out + static_cast<std::size_t>(st.link) * 12 * kL + base;
      for (int e = 0; e < 9; ++e) hn::StoreU(r[e], d, p + e * kL);
      for (int e = 0; e < 3; ++e) hn::StoreU(t[e], d, p + (9 + e) * kL);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hullcheck
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <algorithm>
#include <hullcheck/robot/robot_model.hpp>
#include <vector>

namespace hullcheck {

HWY_EXPORT(LinkPosesBlock);

void RobotModel::compute_link_poses_block(const double* q, std::ptrdiff_t stride, int count,
                                          LinkPoseBlock& out) const {
  constexpr std::size_t kL = kPoseBlockLanes;
  // This thread's scratch: the steps in plain form, converted again whenever they are not this
  // model's (another model's id; or a moved-from model, whose steps_ is empty), and the
  // configurations variable-major.
  thread_local std::vector<detail::KinematicBlockStep> steps;
  thread_local std::uint64_t steps_of = 0;  // the kinematics_id_ they were converted from
  thread_local std::vector<double> values;
  if (steps_of != kinematics_id_ || steps.size() != steps_.size()) {
    steps.resize(steps_.size());
    for (std::size_t k = 0; k < steps_.size(); ++k) {
      const KinematicStep& from = steps_[k];
      detail::KinematicBlockStep& to = steps[k];
      to.link = from.link;
      to.anchor = from.anchor;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) to.offset_rotation[3 * i + j] = from.offset_rotation(i, j);
        to.offset_translation[i] = from.offset_translation[i];
        to.axis[i] = from.axis[i];
      }
      to.type = from.type == JointType::kFixed       ? detail::KinematicBlockStep::kFixed
                : from.type == JointType::kPrismatic ? detail::KinematicBlockStep::kPrismatic
                                                     : detail::KinematicBlockStep::kRevolute;
      to.axis_index = from.axis_index;
      to.axis_sign = from.axis_sign;
      to.variable = from.variable;
      to.multiplier = from.multiplier;
      to.offset = from.offset;
    }
    steps_of = kinematics_id_;
  }
  const auto variables = static_cast<std::size_t>(variable_count());
  values.resize(variables * kL);
  for (std::size_t lane = 0; lane < kL; ++lane) {
    const double* config = q + static_cast<std::ptrdiff_t>(std::min<std::size_t>(
                                   lane, static_cast<std::size_t>(count - 1))) *
                                   stride;
    for (std::size_t v = 0; v < variables; ++v) values[v * kL + lane] = config[v];
  }
  out.values.resize(links_.size() * 12 * kL);
  HWY_DYNAMIC_DISPATCH(LinkPosesBlock)
  (steps.data(), steps.size(), values.data(), out.values.data());
}

}  // namespace hullcheck
#endif  // HWY_ONCE
