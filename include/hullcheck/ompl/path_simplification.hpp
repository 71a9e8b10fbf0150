// Objective-driven path simplification: OMPL's shortcuts accepted only when they do not raise
// an optimization objective's cost.
#pragma once

#include <ompl/base/Goal.h>
#include <ompl/base/OptimizationObjective.h>
#include <ompl/geometric/PathGeometric.h>

#include <hullcheck/ompl/state_validity_checker.hpp>

namespace hullcheck {

/// OMPL's PathSimplifier built with `objective` (so shortcuts are accepted only when they do not
/// increase the objective's cost; OMPL 1.5.2's SimpleSetup builds its simplifier without the
/// objective, which optimises length only), run for up to `max_time` seconds. `goal` lets the
/// simplifier move the last state within the goal region (may be null). Every motion it
/// accepts is checked with the space information's motion validator. Returns true when the
/// path changed.
bool simplify_with_objective(const ::ompl::base::SpaceInformationPtr& si,
                             ::ompl::geometric::PathGeometric& path,
                             const ::ompl::base::OptimizationObjectivePtr& objective,
                             double max_time, const ::ompl::base::GoalPtr& goal = nullptr);

}  // namespace hullcheck
