// optimize_clearance: moves a path's waypoints away from obstacles (and the robot's own moving
// links) with exact signed-distance gradients, interleaved with shortcuts, every change
// certified.
#pragma once

#include <ompl/geometric/PathGeometric.h>

#include <hullcheck/ompl/state_validity_checker.hpp>

namespace hullcheck {

/// Settings of optimize_clearance.
struct ClearanceOptimizationOptions {
  /// m, > 0: clearance up to which more clearance is worth path length (the hinge's margin).
  double margin = 0.05;
  /// >= 0: cost of one unit of joint-space path length, against 1 for a unit of length spent at
  /// contact (ClearanceMarginObjective). Smaller buys more clearance with more length.
  double length_weight = 0.1;
  /// s, > 0: time budget; the optimizer also stops earlier once a round changes nothing.
  double time = 0.1;
  /// Joint-space distance between waypoints while optimising (the path is interpolated to it,
  /// up to max_waypoints states), > 0.
  double waypoint_spacing = 0.1;
  /// >= 3: most waypoints of the interpolation; refinement may add as many again.
  int max_waypoints = 48;
  /// rad (or m), > 0: the largest change of any one value of a waypoint in one step.
  double max_step = 0.1;
};

/// What optimize_clearance did. Costs are ClearanceMarginObjective's (margin and length weight
/// of the options, clearance of the validity checker's scope); clearances, m, are the scope's
/// minimum over the path's waypoints as given (before) and as returned (after).
struct ClearanceOptimizationResult {
  double cost_before = 0.0, cost_after = 0.0;
  double length_before = 0.0, length_after = 0.0;  ///< Joint-space path length.
  double min_clearance_before = 0.0, min_clearance_after = 0.0;
  int rounds = 0;        ///< Gradient rounds run (one pass over the waypoints each).
  int moves = 0;         ///< Waypoint moves the rounds accepted.
  int refined = 0;       ///< Waypoints added where motions dipped below the margin.
  int shortcuts = 0;     ///< Shortcut passes that changed the path.
  bool changed = false;  ///< The path was replaced (false: returned as given).
  double seconds = 0.0;  ///< Time spent.
};

/// Optimises `path` (a valid path of `validity`'s joint space, first and last state fixed) for
/// ClearanceMarginObjective(margin, length_weight) over the pairs of validity's clearance scope
/// (set it with StateValidityChecker::set_clearance_scope; optimization_scope() gives the
/// default worth optimising: obstacles and the self pairs the group can move).
///
/// The path is interpolated to waypoint_spacing; rounds move each interior waypoint in turn
/// along minus the gradient of the objective's waypoint discretisation (segment lengths
/// weighted by the cost density at their ends; the clearance's gradient from the closest
/// pair's witnesses, normal and link Jacobians, clearance_gradient), by at most max_step per
/// value and within joint limits, a move kept only when it lowers that discretisation (its step
/// halved otherwise, doubled after a success); after each round the space information's motion
/// validator (a GuaranteedMotionValidator certifies every configuration between waypoints)
/// checks every changed motion, and waypoints of a failing motion go back to their last
/// certified values. When a round saves less than 0.1% of the cost, motions whose middle is
/// closer than the margin and than both their ends are split there (the discretisation missed
/// that dip; at most doubling the waypoints) and the rounds go on; with nothing to split they
/// stop. Then one pass of OMPL's shortcuts (kept only when they do not raise the objective);
/// when it changed the path, interpolation and rounds run once more on the result, so that no
/// shortcut's motion is left dipping below the margin unexamined. The result replaces `path`
/// only when every motion of it passed and its objective cost (path.cost of the objective) is
/// no higher than the input's: the path returned is never worse on the objective, and never
/// uncertified when it changed. The time budget is checked between waypoints; the final
/// certification of the result may overrun it by a few motion checks.
/// Allocates; thread-safe as the space information's checkers are. Throws InputError on bad
/// options or a path of another space.
ClearanceOptimizationResult optimize_clearance(const ::ompl::base::SpaceInformationPtr& si,
                                               const StateValidityChecker& validity,
                                               ::ompl::geometric::PathGeometric& path,
                                               const ClearanceOptimizationOptions& options = {});

}  // namespace hullcheck
