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

/// Path length (weight `length_weight`) plus ClearanceCostObjective (weight
/// `clearance_weight`, its `scale`), as one OMPL MultiOptimizationObjective. Weights >= 0.
::ompl::base::OptimizationObjectivePtr make_length_clearance_objective(
    const ::ompl::base::SpaceInformationPtr& si, double length_weight, double clearance_weight,
    double scale = 0.05);

}  // namespace hullcheck
