// Clearance-aware path optimization: objective-driven simplification and pushing waypoints
// away from obstacles along the clearance gradient.
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

/// Settings of push_away_from_obstacles.
struct PushOptions {
  int iterations = 20;            ///< Passes over the path's interior waypoints.
  double step = 0.02;             ///< Largest joint-space step per waypoint and pass (rad or m).
  double target_clearance = 0.1;  ///< Waypoints at least this clear (m) are left alone.
};

/// What push_away_from_obstacles did.
struct PushResult {
  double min_clearance_before = 0.0;  ///< Smallest waypoint clearance before / after, m.
  double min_clearance_after = 0.0;
  int moves = 0;  ///< Accepted waypoint moves.
};

/// Moves each interior waypoint of `path` along the clearance gradient of its closest pair
/// (witness points and normal, clearance_gradient()), restricted to the planning group and
/// clamped to joint limits, when that raises the waypoint's clearance and both adjacent motions
/// stay valid (the space information's motion validator). Start and goal never move. The path
/// stays valid throughout.
PushResult push_away_from_obstacles(const ::ompl::base::SpaceInformationPtr& si,
                                    const StateValidityChecker& validity,
                                    ::ompl::geometric::PathGeometric& path,
                                    const PushOptions& options = {});

}  // namespace hullcheck
