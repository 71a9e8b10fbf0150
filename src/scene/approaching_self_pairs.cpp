// approaching_self_pairs: the self link pairs a planning group's motion moves and can take
// clear of a margin, measured over sampled configurations.
#include <algorithm>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/approaching_self_pairs.hpp>
#include <limits>
#include <random>
#include <string>

namespace hullcheck {

std::vector<std::pair<int, int>> approaching_self_pairs(const CollisionChecker& checker,
                                                        const std::vector<int>& variables,
                                                        const Eigen::VectorXd& fixed, double margin,
                                                        const SelfPairSampling& options) {
  const RobotModel& model = checker.model();
  if (options.samples < 1 || !(margin > 0.0) || !std::isfinite(margin)) {
    throw InputError("approaching_self_pairs: samples must be >= 1 and margin finite and > 0");
  }
  model.check_configuration(fixed);
  const Eigen::VectorXd lower = model.lower_limits(), upper = model.upper_limits();
  for (int v : variables) {
    if (v < 0 || v >= model.variable_count()) {
      throw InputError("approaching_self_pairs: variable index " + std::to_string(v) +
                       " is out of range (the model has " + std::to_string(model.variable_count()) +
                       " values)");
    }
  }
  const std::vector<std::pair<int, int>> checked = checker.checked_link_pairs();
  std::vector<PairScope> scopes;
  scopes.reserve(checked.size());
  for (const auto& pair : checked) scopes.push_back(checker.pair_scope(false, {pair}));
  std::vector<double> low(checked.size(), std::numeric_limits<double>::infinity());
  std::vector<double> high(checked.size(), -std::numeric_limits<double>::infinity());
  // A pair is decided once it has been seen clear of the margin and at two distances: later
  // samples can only widen [low, high], so they cannot change its verdict.
  const auto moving_clear = [&](std::size_t k) {
    return high[k] > margin && high[k] - low[k] > 1e-9 * std::max(1.0, std::abs(high[k]));
  };
  std::vector<char> decided(checked.size(), 0);
  std::size_t undecided = checked.size();

  std::mt19937_64 random(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::VectorXd q = fixed;
  std::vector<Eigen::Isometry3d> poses;
  for (int sample = 0; sample <= options.samples && undecided > 0; ++sample) {
    if (sample > 0) {  // sample 0 is `fixed` itself
      for (int v : variables) {
        double lo = lower[v], hi = upper[v];
        if (!std::isfinite(lo) || !std::isfinite(hi)) lo = -M_PI, hi = M_PI;  // one turn
        q[v] = lo + (hi - lo) * unit(random);
      }
    }
    model.compute_link_poses(q, poses);
    for (std::size_t k = 0; k < checked.size(); ++k) {
      if (decided[k]) continue;
      const double d = checker.clearance_at(poses, scopes[k]).distance;
      low[k] = std::min(low[k], d);
      high[k] = std::max(high[k], d);
      if (moving_clear(k)) decided[k] = 1, --undecided;
    }
  }
  // A pair none of the values moves keeps one distance (to the rounding of forward
  // kinematics); one never clear of the margin is held close by the robot's design.
  std::vector<std::pair<int, int>> moving;
  for (std::size_t k = 0; k < checked.size(); ++k) {
    if (moving_clear(k)) moving.push_back(checked[k]);
  }
  return moving;
}

PairScope optimization_scope(const CollisionChecker& checker, const std::vector<int>& variables,
                             const Eigen::VectorXd& fixed, double margin,
                             const SelfPairSampling& options) {
  return checker.pair_scope(true,
                            approaching_self_pairs(checker, variables, fixed, margin, options));
}

}  // namespace hullcheck
