// JointStateSpace: an OMPL state space for a planning group of a robot, and conversions between
// OMPL states and full configuration vectors.
#pragma once

#include <ompl/base/StateSpace.h>

#include <Eigen/Core>
#include <hullcheck/robot/robot_model.hpp>
#include <memory>
#include <vector>

namespace hullcheck {

/// The configuration space of some of a robot's joints (a planning group), the others held at
/// fixed values. Revolute and prismatic joints are bounded real dimensions (their URDF limits);
/// continuous joints are OMPL SO2 dimensions (wrapping at +-pi). Mimic and fixed joints are not
/// dimensions (they follow). When every group joint is bounded the space is one
/// RealVectorStateSpace; otherwise a CompoundStateSpace of a RealVectorStateSpace (bounded
/// joints, in group order) followed by one SO2StateSpace per continuous joint.
///
/// A default projection (for KPIECE and similar planners) on the group's first three joints in
/// configuration order is registered. The object must outlive its space (the projection refers
/// to it): keep it in a shared_ptr next to the space, as PlanningSetup does. Not copyable.
/// Units: rad and m. Conversions are allocation-free and thread-safe (const).
class JointStateSpace {
 public:
  /// `variables`: configuration indices of the group (group_variables()); `fixed`: the full
  /// configuration the other joints keep (checked). Throws InputError on an empty group, a
  /// repeated or out-of-range index.
  JointStateSpace(std::shared_ptr<const RobotModel> model, std::vector<int> variables,
                  const Eigen::VectorXd& fixed);

  JointStateSpace(const JointStateSpace&) = delete;
  JointStateSpace& operator=(const JointStateSpace&) = delete;

  const ::ompl::base::StateSpacePtr& space() const { return space_; }
  const RobotModel& model() const { return *model_; }
  /// Configuration indices of the group, in dimension order of the state (bounded first).
  const std::vector<int>& variables() const { return variables_; }
  /// The full configuration with the held joints' values.
  const Eigen::VectorXd& fixed_configuration() const { return fixed_; }
  int dimension() const { return static_cast<int>(variables_.size()); }

  /// Full configuration (RobotModel order) of `state`: the held values with the group's written
  /// in. `q` must have model().variable_count() entries.
  void to_configuration(const ::ompl::base::State* state, Eigen::Ref<Eigen::VectorXd> q) const;
  /// Writes the group's values of the full configuration `q` into `state` (continuous joints
  /// wrapped into [-pi, pi)). Throws InputError when q has the wrong size or a NaN, or when a
  /// group value is outside its joint's range (RobotModel::check_joint_range, default
  /// tolerance).
  void from_configuration(const Eigen::Ref<const Eigen::VectorXd>& q,
                          ::ompl::base::State* state) const;
  /// The group's values of `state` in dimension order.
  void to_group_values(const ::ompl::base::State* state, Eigen::Ref<Eigen::VectorXd> values) const;

 private:
  std::shared_ptr<const RobotModel> model_;
  std::vector<int> variables_;  // bounded ones first, then continuous ones
  int bounded_count_ = 0;
  Eigen::VectorXd fixed_;
  ::ompl::base::StateSpacePtr space_;
};

}  // namespace hullcheck
