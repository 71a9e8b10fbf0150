// simplify_with_objective: OMPL's path simplifier under an optimization objective, never
// raising its cost.
#include <ompl/geometric/PathSimplifier.h>

#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/path_simplification.hpp>

#include "detail/shortcut_path.hpp"

namespace hullcheck {

namespace ob = ::ompl::base;
namespace og = ::ompl::geometric;

bool simplify_with_objective(const ob::SpaceInformationPtr& si, og::PathGeometric& path,
                             const ob::OptimizationObjectivePtr& objective, double max_time,
                             const ob::GoalPtr& goal) {
  if (!objective) throw InputError("simplify_with_objective: objective is null");
  og::PathSimplifier simplifier(si, goal, objective);
  const std::size_t before = path.getStateCount();
  const ob::Cost cost_before = path.cost(objective);
  const og::PathGeometric original(path);
  const ob::PlannerTerminationCondition ptc = ob::timedPlannerTerminationCondition(max_time);
  // OMPL 1.5.2's simplify() also runs steps that ignore the objective (reduceVertices,
  // collapseCloseVertices, B-spline smoothing, checkAndRepair): they shorten the path but may
  // take it closer to obstacles. Keep its result only when the objective's cost did not grow;
  // otherwise use only the objective-aware steps (shortcuts, findBetterGoal).
  simplifier.simplify(path, ptc);
  if (objective->isCostBetterThan(cost_before, path.cost(objective))) {
    path = original;
    for (bool more = true; more;) {
      more = detail::shortcut_path(simplifier, path);
      if (goal) more = simplifier.findBetterGoal(path, ptc) || more;
      if (ptc) break;
    }
    // Shortcuts compare costs piecewise; a final guard keeps the contract exactly.
    if (objective->isCostBetterThan(cost_before, path.cost(objective))) path = original;
  }
  return path.getStateCount() != before ||
         objective->isCostBetterThan(path.cost(objective), cost_before);
}

}  // namespace hullcheck
