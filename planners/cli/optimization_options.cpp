#include "optimization_options.hpp"

#include <algorithm>
#include <limits>

#include "number_options.hpp"

namespace hullcheck::cli {

void OptimizationOptions::add_to(CLI::App& command) {
  command
      .add_option("--clearance-scope", scope,
                  "Pairs clearance objectives, the optimizer and reports use: auto (obstacles "
                  "and the self pairs the group moves and can take --margin apart; "
                  "default), all, obstacles, self")
      ->check(CLI::IsMember({"auto", "all", "obstacles", "self"}));
  command
      .add_option("--optimize", optimize,
                  "Optimize the solution path: 'clearance' (gradient rounds on a hinge at "
                  "--margin plus length, interleaved with shortcuts, every motion certified)")
      ->check(CLI::IsMember({"clearance"}));
  command
      .add_option("--margin", settings.margin,
                  "Clearance, m, up to which the optimizer trades length for clearance "
                  "(default 0.05)")
      ->check(finite_in(0.0, 1e3, true));
  command
      .add_option("--length-weight", settings.length_weight,
                  "Cost of a unit of path length against a unit spent at contact (default 0.1)")
      ->check(finite_in(0.0, 1e6));
  command.add_option("--optimize-time", settings.time, "Optimizer time budget, s (default 0.1)")
      ->check(finite_in(0.0, 1e6, true));
}

std::shared_ptr<const PairScope> OptimizationOptions::make_scope(
    const CollisionChecker& checker, const std::vector<int>& variables,
    const Eigen::VectorXd& fixed) const {
  if (scope == "all") return nullptr;
  if (scope == "obstacles") {
    return std::make_shared<const PairScope>(checker.pair_scope(ClearanceScope::kObstacles));
  }
  if (scope == "self") {
    return std::make_shared<const PairScope>(checker.pair_scope(ClearanceScope::kSelf));
  }
  return std::make_shared<const PairScope>(
      optimization_scope(checker, variables, fixed, settings.margin));
}

std::vector<ClearanceSample> clearance_profile(const PlanningSetup& planning,
                                               const ::ompl::geometric::PathGeometric& path,
                                               const PairScope* scope, int per_motion) {
  const auto si = planning.setup->getSpaceInformation();
  const CollisionChecker& checker = planning.validity->collision_checker();
  const auto clearance = [&](const ::ompl::base::State* s) {
    const Eigen::VectorXd q = planning.configuration(s);
    return scope ? checker.clearance(q, *scope).distance : checker.clearance(q).distance;
  };
  std::vector<ClearanceSample> profile;
  ::ompl::base::ScopedState<> mid(si);
  double position = 0.0;
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    profile.push_back({position, clearance(path.getState(i)), true});
    if (i + 1 == path.getStateCount()) break;
    const double segment = si->distance(path.getState(i), path.getState(i + 1));
    for (int k = 1; k < per_motion; ++k) {
      const double t = static_cast<double>(k) / per_motion;
      si->getStateSpace()->interpolate(path.getState(i), path.getState(i + 1), t, mid.get());
      profile.push_back({position + t * segment, clearance(mid.get()), false});
    }
    position += segment;
  }
  return profile;
}

double profile_minimum(const std::vector<ClearanceSample>& profile) {
  double m = std::numeric_limits<double>::infinity();
  for (const ClearanceSample& s : profile) m = std::min(m, s.clearance);
  return m;
}

}  // namespace hullcheck::cli
