// GuaranteedMotionValidator: OMPL motion validation that cannot miss a collision between
// checked states (conservative advancement).
#pragma once

#include <ompl/base/MotionValidator.h>

#include <atomic>
#include <hullcheck/ompl/state_validity_checker.hpp>
#include <memory>

namespace hullcheck {

/// Checks the motion between two states of a JointStateSpace as OMPL interpolates it (real
/// joints linearly, continuous joints the short way round) by conservative advancement: at each
/// checked state CollisionChecker::safe_advance finds, pair by pair, how far the motion can go
/// before the pair's shapes could touch (exact distance over a bound on their relative motion
/// from the kinematic chain and the shapes' radii), and the motion advances by the smallest
/// such step until it reaches the end. So an accepted motion is collision-free at every point,
/// not only at sampled ones — thin obstacles included.
///
/// A motion is rejected when a checked state has clearance <= `min_clearance` (m, default
/// 1e-6: states closer than that count as touching), or after `max_steps` (default 100000)
/// states (reported as a failure at the last state checked, never as success). Thread-safe;
/// OMPL's own valid/invalid counters (plain integers, racy under parallel planners) are left at
/// zero, the counts are in valid_motion_count() / invalid_motion_count() (atomic).
class GuaranteedMotionValidator : public ::ompl::base::MotionValidator {
 public:
  GuaranteedMotionValidator(const ::ompl::base::SpaceInformationPtr& si,
                            std::shared_ptr<const StateValidityChecker> validity,
                            double min_clearance = 1e-6, int max_steps = 100000);

  bool checkMotion(const ::ompl::base::State* s1, const ::ompl::base::State* s2) const override;
  /// On failure, `last_valid.first` (when not null) receives the last state known free and
  /// `last_valid.second` its fraction of the motion in [0, 1).
  bool checkMotion(const ::ompl::base::State* s1, const ::ompl::base::State* s2,
                   std::pair<::ompl::base::State*, double>& last_valid) const override;

  unsigned long valid_motion_count() const { return valid_motions_.load(); }
  unsigned long invalid_motion_count() const { return invalid_motions_.load(); }
  /// Conservative-advancement steps taken so far (one safe_advance call each).
  unsigned long step_count() const { return steps_.load(); }

 private:
  /// Advances from s1 towards s2: true when the whole motion is certified free; `last_free`
  /// receives the fraction of the motion in [0, 1] certified free from s1 (1 when free).
  bool advance(const ::ompl::base::State* s1, const ::ompl::base::State* s2,
               double* last_free) const;

  std::shared_ptr<const StateValidityChecker> validity_;
  double min_clearance_;
  int max_steps_;
  mutable std::atomic<unsigned long> valid_motions_{0};
  mutable std::atomic<unsigned long> invalid_motions_{0};
  mutable std::atomic<unsigned long> steps_{0};
};

}  // namespace hullcheck
