// Which of the robot's own link pairs a planning group's motion can take both within a
// clearance margin and clear of it: the self pairs worth optimising clearance over.
#pragma once

#include <Eigen/Core>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/pair_scope.hpp>
#include <utility>
#include <vector>

namespace hullcheck {

/// Settings of approaching_self_pairs.
struct SelfPairSampling {
  int samples = 128;  ///< Configurations sampled besides `fixed`, >= 1.
  unsigned seed = 1;  ///< Seed of the (deterministic) sampling.
};

/// The checked self link pairs (model link indices, a < b, in checked_link_pairs() order) that
/// the configuration values `variables` can bring within `margin` (m) of each other and also
/// take clear of it: the pair's signed distance is below the margin in some and above it in
/// other configurations among `fixed` and options.samples configurations with those values
/// drawn uniformly between their limits (a continuous joint over one turn), the others as in
/// `fixed`. Left out are pairs that never come within the margin (a hinge at the margin never
/// acts on them) and pairs that never get clear of it: links held close by the robot's design
/// (a wrist over its forearm, two links turning about a common axis), whose hinge would only
/// tax path length, and pairs that no listed value moves relative to each other. The decision
/// is sampled: it chooses which clearance to optimise and report, never what is valid
/// (validity always checks every pair). Deterministic for a seed; cost: samples x checked
/// pairs clearance queries (milliseconds for a 7-joint arm). Throws InputError on a bad
/// variable index, configuration, margin (finite, > 0) or option.
std::vector<std::pair<int, int>> approaching_self_pairs(const CollisionChecker& checker,
                                                        const std::vector<int>& variables,
                                                        const Eigen::VectorXd& fixed, double margin,
                                                        const SelfPairSampling& options = {});

/// The default scope of clearance optimization with a hinge at `margin`: every robot-obstacle
/// pair, and the self pairs approaching_self_pairs finds for `variables`.
PairScope optimization_scope(const CollisionChecker& checker, const std::vector<int>& variables,
                             const Eigen::VectorXd& fixed, double margin,
                             const SelfPairSampling& options = {});

}  // namespace hullcheck
