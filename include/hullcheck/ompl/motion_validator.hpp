// GuaranteedMotionValidator: OMPL motion validation that cannot miss a collision between
// checked states (CollisionChecker::check_motion's certificate).
#pragma once

#include <ompl/base/MotionValidator.h>

#include <atomic>
#include <hullcheck/ompl/state_validity_checker.hpp>
#include <memory>

namespace hullcheck {

/// Checks the motion between two states of a JointStateSpace as OMPL interpolates it (real
/// joints linearly, continuous joints the short way round) with CollisionChecker::check_motion:
/// interval bisection in which a pair is decided over a whole interval when its signed
/// distance at the interval's middle exceeds how far its shapes can move relative to each other
/// within it (lever arms of the kinematic chain). So an accepted motion is collision-free at
/// every point, not only at sampled ones — thin obstacles included.
///
/// A motion is rejected when some configuration of it has a pair within
/// `options.min_clearance` (m, default 1e-6) of touching; it may be rejected when it passes
/// within min_clearance + `options.resolution` (default 1e-4 m), and is after
/// `options.max_states` configurations without a decision (never reported as success). On
/// rejection the last valid fraction is the end of the proven-free part, before the contact
/// found, with no pair moving more than `resolution` between the two (moved back by up to 16
/// times that where checkMotion(s1, last valid state) would not accept the part kept, inside
/// the band; 0 when even that is not accepted; without a state to fill, one is allocated for
/// that check, on rejections with a last valid fraction above 0 only). Both overloads give the
/// same verdict for the same motion (the yes/no search decides; the overload with a last valid
/// state then locates the contact). Thread-safe; OMPL's own
/// valid/invalid counters (plain integers, racy under parallel planners) are left at zero, the
/// counts are in valid_motion_count() / invalid_motion_count() (atomic).
class GuaranteedMotionValidator : public ::ompl::base::MotionValidator {
 public:
  GuaranteedMotionValidator(const ::ompl::base::SpaceInformationPtr& si,
                            std::shared_ptr<const StateValidityChecker> validity,
                            const MotionCheckOptions& options = {});

  bool checkMotion(const ::ompl::base::State* s1, const ::ompl::base::State* s2) const override;
  /// On failure, `last_valid.first` (when not null) receives the last state known free and
  /// `last_valid.second` its fraction of the motion in [0, 1).
  bool checkMotion(const ::ompl::base::State* s1, const ::ompl::base::State* s2,
                   std::pair<::ompl::base::State*, double>& last_valid) const override;

  unsigned long valid_motion_count() const { return valid_motions_.load(); }
  unsigned long invalid_motion_count() const { return invalid_motions_.load(); }
  /// Configurations evaluated so far by check_motion (one forward kinematics each).
  unsigned long step_count() const { return steps_.load(); }
  const MotionCheckOptions& options() const { return options_; }

 private:
  /// Checks s1 -> s2: true when the whole motion is certified free; `last_free` (when not null:
  /// on rejection the first contact is then located, see MotionCheckOptions::locate_contact)
  /// receives the fraction of the motion in [0, 1] certified free from s1 (1 when free).
  bool advance(const ::ompl::base::State* s1, const ::ompl::base::State* s2,
               double* last_free) const;
  /// The configurations of s1 and s2 (full, the model's values) for the motion between them:
  /// continuous joints' end values unwrapped the short way round, as OMPL interpolates them.
  void motion_configurations(const ::ompl::base::State* s1, const ::ompl::base::State* s2,
                             Eigen::VectorXd& q0, Eigen::VectorXd& q1) const;

  std::shared_ptr<const StateValidityChecker> validity_;
  MotionCheckOptions options_;
  mutable std::atomic<unsigned long> valid_motions_{0};
  mutable std::atomic<unsigned long> invalid_motions_{0};
  mutable std::atomic<unsigned long> steps_{0};
};

}  // namespace hullcheck
