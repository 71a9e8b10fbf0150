#include <algorithm>
#include <atomic>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/motion_validator.hpp>

namespace hullcheck {

namespace ob = ::ompl::base;

GuaranteedMotionValidator::GuaranteedMotionValidator(
    const ob::SpaceInformationPtr& si, std::shared_ptr<const StateValidityChecker> validity,
    const MotionCheckOptions& options)
    : ob::MotionValidator(si), validity_(std::move(validity)), options_(options) {
  if (!validity_) throw InputError("GuaranteedMotionValidator: validity checker is null");
  validate(options, "GuaranteedMotionValidator");
}

void GuaranteedMotionValidator::motion_configurations(const ob::State* s1, const ob::State* s2,
                                                      Eigen::VectorXd& q0,
                                                      Eigen::VectorXd& q1) const {
  const JointStateSpace& joints = validity_->joint_space();
  const auto n = joints.fixed_configuration().size();
  q0.resize(n);  // no allocation once sized
  q1.resize(n);
  joints.to_configuration(s1, q0);
  joints.to_configuration(s2, q1);
  // Continuous joints: the end value reached the short way round, as SO2 interpolation does.
  for (int v : joints.variables()) {
    if (joints.model().joint(joints.model().variable_joint(v)).type == JointType::kContinuous) {
      q1[v] = q0[v] + std::remainder(q1[v] - q0[v], 2.0 * M_PI);
    }
  }
}

bool GuaranteedMotionValidator::advance(const ob::State* s1, const ob::State* s2,
                                        double* last_free) const {
  MotionCheckOptions options = options_;
  const CollisionChecker& checker = validity_->collision_checker();
  // Per-thread scratch: sized once, reused (no allocation per motion).
  thread_local Eigen::VectorXd q0, q1;
  motion_configurations(s1, s2, q0, q1);
  // The verdict comes from the yes/no search (level order, the first contact found settles it)
  // whichever overload asks: the two searches examine different intervals, and within
  // `resolution` of contact one may prove a motion free that the other calls near contact, so
  // a path accepted through checkMotion(s1, s2) would be rejected when re-checked with a last
  // valid state.
  options.locate_contact = false;
  // A motion from the state just validated (to an existing one, usually): its end is not
  // tested first.
  options.end_first = !validity_->last_valid_is(q0);
  const MotionCheckResult r = checker.check_motion(q0, q1, options);
  steps_.fetch_add(static_cast<unsigned long>(r.states), std::memory_order_relaxed);
  if (r.free() || last_free == nullptr) {
    if (last_free != nullptr) *last_free = r.last_free;
    return r.free();
  }
  // Rejected: the depth-first search places the last valid state (before the first contact;
  // 0 when it proves the motion free after all, inside that band).
  options.locate_contact = true;
  const MotionCheckResult located = checker.check_motion(q0, q1, options);
  steps_.fetch_add(static_cast<unsigned long>(located.states), std::memory_order_relaxed);
  *last_free = located.free() ? 0.0 : located.last_free;
  return false;
}

bool GuaranteedMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  const bool ok = advance(s1, s2, nullptr);
  (ok ? valid_motions_ : invalid_motions_).fetch_add(1, std::memory_order_relaxed);
  return ok;
}

bool GuaranteedMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                            std::pair<ob::State*, double>& last_valid) const {
  double last_free = 0.0;
  const bool ok = advance(s1, s2, &last_free);
  (ok ? valid_motions_ : invalid_motions_).fetch_add(1, std::memory_order_relaxed);
  if (ok) return true;
  // A planner keeps s1 -> the last valid state as a motion of its own (KPIECE does), and its
  // path is re-checked motion by motion: checkMotion(s1, that state) must accept it. Its end
  // lies within `resolution` of the contact, possibly inside the band where the yes/no search
  // calls it near contact: then it moves back by 1, 4 and 16 times the fraction over which no
  // point moves more than `resolution` (motion_bound), and to 0 when none is accepted. Checked
  // on the state itself (as interpolated and stored), so that the re-check is the same query.
  const ob::StateSpacePtr& space = si_->getStateSpace();
  if (last_free > 0.0) {
    ob::State* end = last_valid.first != nullptr ? last_valid.first : si_->allocState();
    thread_local Eigen::VectorXd q0, q1;
    motion_configurations(s1, s2, q0, q1);
    const double unit =
        options_.resolution / std::max(validity_->collision_checker().motion_bound(q0, q1), 1e-300);
    double t = last_free;
    for (int attempt = 0; t > 0.0; ++attempt) {
      space->interpolate(s1, s2, t, end);
      if (advance(s1, end, nullptr)) break;
      t = attempt == 3 ? 0.0
                       : std::max(0.0, last_free - unit * static_cast<double>(1 << (2 * attempt)));
    }
    last_free = t;
    if (end != last_valid.first) si_->freeState(end);
  }
  last_valid.second = last_free;
  if (last_valid.first != nullptr) space->interpolate(s1, s2, last_free, last_valid.first);
  return false;
}

}  // namespace hullcheck
