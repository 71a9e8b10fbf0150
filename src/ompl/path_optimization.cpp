#include <ompl/config.h>
#include <ompl/geometric/PathSimplifier.h>

#include <algorithm>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/path_optimization.hpp>
#include <hullcheck/scene/clearance_gradient.hpp>
#include <limits>

namespace hullcheck {

namespace ob = ::ompl::base;
namespace og = ::ompl::geometric;

namespace {

// One pass of random shortcuts that keep the objective's cost from growing. OMPL 1.7 renamed
// PathSimplifier::shortcutPath to partialShortcutPath (same arguments and meaning).
bool shortcut_once(og::PathSimplifier& simplifier, og::PathGeometric& path) {
#if OMPL_VERSION_VALUE >= 1007000
  return simplifier.partialShortcutPath(path);
#else
  return simplifier.shortcutPath(path);
#endif
}

}  // namespace

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
      more = shortcut_once(simplifier, path);
      if (goal) more = simplifier.findBetterGoal(path, ptc) || more;
      if (ptc) break;
    }
    // Shortcuts compare costs piecewise; a final guard keeps the contract exactly.
    if (objective->isCostBetterThan(cost_before, path.cost(objective))) path = original;
  }
  return path.getStateCount() != before ||
         objective->isCostBetterThan(path.cost(objective), cost_before);
}

PushResult push_away_from_obstacles(const ob::SpaceInformationPtr& si,
                                    const StateValidityChecker& validity, og::PathGeometric& path,
                                    const PushOptions& options) {
  if (!(options.step > 0.0) || options.iterations < 0) {
    throw InputError("push_away_from_obstacles: step must be > 0, iterations >= 0");
  }
  const JointStateSpace& joints = validity.joint_space();
  const CollisionChecker& checker = validity.collision_checker();
  const RobotModel& model = joints.model();
  PushResult result;
  const auto min_clearance = [&] {
    double m = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < path.getStateCount(); ++i) {
      m = std::min(m, validity.clearance(path.getState(i)));
    }
    return m;
  };
  result.min_clearance_before = min_clearance();
  Eigen::VectorXd q(model.variable_count()), trial(model.variable_count());
  std::vector<Eigen::Isometry3d> poses;
  ob::State* candidate = si->allocState();
  const Eigen::VectorXd lower = model.lower_limits(), upper = model.upper_limits();
  for (int pass = 0; pass < options.iterations; ++pass) {
    int moved = 0;
    for (std::size_t i = 1; i + 1 < path.getStateCount(); ++i) {
      joints.to_configuration(path.getState(i), q);
      model.compute_link_poses(q, poses);
      const ClearanceResult closest = checker.clearance_at(poses);
      if (!(closest.distance < options.target_clearance) || closest.link_a < 0) continue;
      const Eigen::VectorXd full = clearance_gradient(model, poses, closest);
      Eigen::VectorXd g = Eigen::VectorXd::Zero(model.variable_count());
      for (int v : joints.variables()) g[v] = full[v];
      const double norm = g.cwiseAbs().maxCoeff();
      if (!(norm > 0.0)) continue;
      // Halve the step until the waypoint's clearance grows and its motions stay valid.
      for (double step = options.step; step > options.step / 64; step /= 2) {
        trial = q + (step / norm) * g;
        trial = trial.cwiseMax(lower).cwiseMin(upper);
        joints.from_configuration(trial, candidate);
        const double d = validity.clearance(candidate);
        if (d > closest.distance && si->checkMotion(path.getState(i - 1), candidate) &&
            si->checkMotion(candidate, path.getState(i + 1))) {
          si->copyState(path.getState(i), candidate);
          ++moved;
          break;
        }
      }
    }
    result.moves += moved;
    if (moved == 0) break;
  }
  si->freeState(candidate);
  result.min_clearance_after = min_clearance();
  return result;
}

}  // namespace hullcheck
