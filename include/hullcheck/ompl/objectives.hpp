// Clearance-based optimization objectives for OMPL planners.
#pragma once

#include <ompl/base/OptimizationObjective.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/StateCostIntegralObjective.h>

namespace hullcheck {

/// OMPL's MaximizeMinClearanceObjective: maximise the smallest clearance along the path. It
/// calls the space information's StateValidityChecker::clearance (ours is exact).
::ompl::base::OptimizationObjectivePtr make_max_min_clearance_objective(
    const ::ompl::base::SpaceInformationPtr& si);

/// Integral along the path of exp(-clearance / scale): a cost that falls off smoothly as the
/// robot moves away from obstacles (and grows steeply in penetration), integrated over motion
/// segments (motion cost interpolation enabled). `scale`, m, > 0: the distance beyond which
/// clearance hardly matters (default 0.05 m).
class ClearanceCostObjective : public ::ompl::base::StateCostIntegralObjective {
 public:
  explicit ClearanceCostObjective(const ::ompl::base::SpaceInformationPtr& si, double scale = 0.05);
  ::ompl::base::Cost stateCost(const ::ompl::base::State* s) const override;
  double scale() const { return scale_; }

 private:
  double scale_;
};

/// The clearance optimizer's objective (optimize_clearance): the integral along the path of
/// length_weight + max(0, margin - clearance) / margin, clearance being the space information's
/// StateValidityChecker::clearance (its scope). So each unit of joint-space length costs
/// length_weight, plus up to 1 more where the robot comes within `margin` (m) of a pair of the
/// scope (1 at contact, more in penetration), integrated over motion segments (motion cost
/// interpolation enabled) as a hinge loss on signed distance, as in TrajOpt. margin finite
/// and > 0, length_weight finite and >= 0.
class ClearanceMarginObjective : public ::ompl::base::StateCostIntegralObjective {
 public:
  ClearanceMarginObjective(const ::ompl::base::SpaceInformationPtr& si, double margin,
                           double length_weight);
  ::ompl::base::Cost stateCost(const ::ompl::base::State* s) const override;
  /// The cost density at signed distance d: length_weight + max(0, margin - d) / margin.
  double density(double d) const;
  double margin() const { return margin_; }
  double length_weight() const { return length_weight_; }

 private:
  double margin_, length_weight_;
};

/// Path length (weight `length_weight`) plus ClearanceCostObjective (weight
/// `clearance_weight`, its `scale`), as one OMPL MultiOptimizationObjective. Weights >= 0.
::ompl::base::OptimizationObjectivePtr make_length_clearance_objective(
    const ::ompl::base::SpaceInformationPtr& si, double length_weight, double clearance_weight,
    double scale = 0.05);

}  // namespace hullcheck
