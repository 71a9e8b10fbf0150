// PlanningSetup: an OMPL SimpleSetup wired to hullcheck (state space, validity, motions).
#pragma once

#include <ompl/geometric/SimpleSetup.h>

#include <hullcheck/ompl/joint_state_space.hpp>
#include <hullcheck/ompl/motion_validator.hpp>
#include <hullcheck/ompl/state_validity_checker.hpp>
#include <memory>
#include <vector>

namespace hullcheck {

/// How motions between states are validated.
enum class MotionChecking {
  kGuaranteed,  ///< GuaranteedMotionValidator: no collision between states can be missed.
  kDiscrete,    ///< OMPL's DiscreteMotionValidator at the space's longest-valid-segment fraction.
};

/// Everything a planning program needs, built once: the joint space, the validity checker and
/// motion validator on a SimpleSetup (planner and objective left to the caller).
struct PlanningSetup {
  std::shared_ptr<const JointStateSpace> joints;
  std::shared_ptr<StateValidityChecker> validity;
  std::shared_ptr<::ompl::geometric::SimpleSetup> setup;

  /// An OMPL state (allocated by the setup's space) holding the group values of the full
  /// configuration q. Throws InputError on a wrong size or NaN.
  ::ompl::base::ScopedState<> state(const Eigen::VectorXd& q) const;
  /// The full configuration of an OMPL state.
  Eigen::VectorXd configuration(const ::ompl::base::State* state) const;
};

/// Builds a PlanningSetup for the configuration indices `variables` of `checker`'s robot, the
/// other joints held at `fixed` (a full configuration). `discrete_resolution` is the longest
/// valid segment fraction used in kDiscrete mode (OMPL's default 0.01). Throws InputError on
/// bad input.
PlanningSetup make_planning_setup(std::shared_ptr<const CollisionChecker> checker,
                                  const std::vector<int>& variables, const Eigen::VectorXd& fixed,
                                  MotionChecking motions = MotionChecking::kGuaranteed,
                                  double discrete_resolution = 0.01);

}  // namespace hullcheck
