// StateValidityChecker: OMPL's validity checker backed by hullcheck's exact queries.
#pragma once

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include <atomic>
#include <hullcheck/ompl/joint_state_space.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>
#include <memory>

namespace hullcheck {

/// Validity of OMPL states of a JointStateSpace: robot against its enabled self pairs and the
/// scene's obstacles (CollisionChecker), with the robot's padding.
///
/// - isValid(state): boolean collision test with early exit (cheapest); every checked pair.
/// - clearance(state): exact minimum signed distance over the clearance scope's pairs, m
///   (negative: the penetration depth of the deepest pair, by EPA); every checked pair unless
///   set_clearance_scope chose some. +inf when the scope holds nothing. OMPL's clearance
///   objectives read it, so the scope is what they optimise.
/// - isValid(state, dist): both (validity over every pair, dist over the scope).
/// - closest(state): the pair behind clearance(), with link/obstacle names and witnesses.
/// Specs: clearanceComputationType EXACT, hasValidDirectionComputation false. Thread-safe:
/// every method is const and uses per-thread scratch (no lock), as OMPL's parallel planners
/// need.
class StateValidityChecker : public ::ompl::base::StateValidityChecker {
 public:
  StateValidityChecker(const ::ompl::base::SpaceInformationPtr& si,
                       std::shared_ptr<const JointStateSpace> space,
                       std::shared_ptr<const CollisionChecker> checker);

  bool isValid(const ::ompl::base::State* state) const override;
  bool isValid(const ::ompl::base::State* state, double& dist) const override;
  double clearance(const ::ompl::base::State* state) const override;
  ClearanceResult closest(const ::ompl::base::State* state) const;
  /// clearance(state) for a caller that needs it only below `below`, m (a margin; not NaN):
  /// the same value where it is below, +inf where the scope's pairs are all at or above it
  /// (skipped on their bounds: cheaper far from contact). See CollisionChecker::clearance.
  double clearance_below(const ::ompl::base::State* state, double below) const;
  /// closest() at a full configuration q (the model's values) rather than a state, capped at
  /// `below` as CollisionChecker::clearance is; not counted in check_count().
  ClearanceResult scoped_clearance(const Eigen::VectorXd& q,
                                   double below = std::numeric_limits<double>::infinity()) const;

  /// Restricts clearance(), closest() and isValid(state, dist)'s dist to the pairs of `scope`
  /// (a PairScope of collision_checker(), e.g. from optimization_scope()); null: every checked
  /// pair (the default). Validity is never restricted. Set it before planning: it is not
  /// synchronised with queries running on other threads.
  void set_clearance_scope(std::shared_ptr<const PairScope> scope);
  /// The scope set, or null for every checked pair.
  const std::shared_ptr<const PairScope>& clearance_scope() const { return scope_; }

  /// Validity and clearance computations so far (all threads; relaxed atomic counter).
  unsigned long check_count() const { return checks_.load(std::memory_order_relaxed); }
  void reset_check_count() { checks_.store(0); }

  /// True when this thread's last isValid(state) call on this checker found `q` (a full
  /// configuration, as joint_space().to_configuration gives it) valid, bit for bit. A planner
  /// that validates a new state and then checks a motion from it to an existing one (OMPL's
  /// RRTConnect growing its goal tree, PRM connecting a sample) lets the motion validator skip
  /// testing the end state first (MotionCheckOptions::end_first).
  bool last_valid_is(const Eigen::VectorXd& q) const;

  const JointStateSpace& joint_space() const { return *space_; }
  const CollisionChecker& collision_checker() const { return *checker_; }

 private:
  Eigen::VectorXd& configuration(const ::ompl::base::State* state) const;

  std::shared_ptr<const JointStateSpace> space_;
  std::shared_ptr<const CollisionChecker> checker_;
  std::shared_ptr<const PairScope> scope_;
  mutable std::atomic<unsigned long> checks_{0};
};

}  // namespace hullcheck
