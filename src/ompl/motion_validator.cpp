#include <atomic>
#include <cmath>
#include <hullcheck/errors.hpp>
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
  thread_local Eigen::VectorXd q0, q1, q;
  const auto n = joints.fixed_configuration().size();
  q0.resize(n);
  q1.resize(n);
  q.resize(n);
  joints.to_configuration(s1, q0);
  joints.to_configuration(s2, q1);
  // Continuous joints: the end value reached the short way round, as SO2 interpolation does.
  for (int v : joints.variables()) {
    if (joints.model().joint(joints.model().variable_joint(v)).type == JointType::kContinuous) {
      q1[v] = q0[v] + std::remainder(q1[v] - q0[v], 2.0 * M_PI);
    }
  }
  const double full_bound = checker.motion_bound(q0, q1);
  double t = 0.0;
  *last_free = 0.0;
  for (int step = 0; step < max_steps_; ++step) {
    q = q0 + t * (q1 - q0);
    const double d = checker.clearance(q).distance;
    if (!(d > min_clearance_)) return false;
    *last_free = t;
    const double rest = (1.0 - t) * full_bound;  // the bound is linear in the joint motion
    if (rest < d) {
      // The end state itself is within the bound's reach: free as well.
      *last_free = 1.0;
      return true;
    }
    t += (1.0 - t) * (d / rest);
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
