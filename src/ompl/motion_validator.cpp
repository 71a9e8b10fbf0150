#include <atomic>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/motion_validator.hpp>

namespace hullcheck {

namespace ob = ::ompl::base;

GuaranteedMotionValidator::GuaranteedMotionValidator(
    const ob::SpaceInformationPtr& si, std::shared_ptr<const StateValidityChecker> validity,
    double min_clearance, int max_steps)
    : ob::MotionValidator(si),
      validity_(std::move(validity)),
      min_clearance_(min_clearance),
      max_steps_(max_steps) {
  if (!validity_) throw InputError("GuaranteedMotionValidator: validity checker is null");
  if (!(min_clearance >= 0.0) || !std::isfinite(min_clearance) || max_steps < 1) {
    throw InputError(
        "GuaranteedMotionValidator: min_clearance must be finite and >= 0, "
        "max_steps >= 1");
  }
}

bool GuaranteedMotionValidator::advance(const ob::State* s1, const ob::State* s2,
                                        double* last_free) const {
  const JointStateSpace& joints = validity_->joint_space();
  const CollisionChecker& checker = validity_->collision_checker();
  // Per-thread scratch: sized once, reused (no allocation per motion).
  thread_local Eigen::VectorXd q0, q1, dq, at;
  const auto n = joints.fixed_configuration().size();
  q0.resize(n);
  q1.resize(n);
  dq.resize(n);
  at.resize(n);
  joints.to_configuration(s1, q0);
  joints.to_configuration(s2, q1);
  // Continuous joints: the end value reached the short way round, as SO2 interpolation does.
  for (int v : joints.variables()) {
    if (joints.model().joint(joints.model().variable_joint(v)).type == JointType::kContinuous) {
      q1[v] = q0[v] + std::remainder(q1[v] - q0[v], 2.0 * M_PI);
    }
  }
  dq = q1 - q0;  // the motion per unit of t
  double t = 0.0;
  *last_free = 0.0;
  for (int step = 0; step < max_steps_; ++step) {
    at = q0 + t * dq;
    const double advance = checker.safe_advance(at, dq, min_clearance_);
    steps_.fetch_add(1, std::memory_order_relaxed);
    if (advance < 0.0) return false;  // this state is (nearly) in contact
    *last_free = t;
    if (t + advance >= 1.0) {
      *last_free = 1.0;
      return true;
    }
    t += advance;
  }
  return false;
}

bool GuaranteedMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  double last_free = 0.0;
  const bool ok = advance(s1, s2, &last_free);
  (ok ? valid_motions_ : invalid_motions_).fetch_add(1, std::memory_order_relaxed);
  return ok;
}

bool GuaranteedMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                            std::pair<ob::State*, double>& last_valid) const {
  double last_free = 0.0;
  const bool ok = advance(s1, s2, &last_free);
  (ok ? valid_motions_ : invalid_motions_).fetch_add(1, std::memory_order_relaxed);
  if (ok) return true;
  last_valid.second = last_free;
  if (last_valid.first != nullptr) {
    si_->getStateSpace()->interpolate(s1, s2, last_free, last_valid.first);
  }
  return false;
}

}  // namespace hullcheck
