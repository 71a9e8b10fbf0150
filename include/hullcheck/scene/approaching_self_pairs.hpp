// Which of the robot's own link pairs a planning group's motion moves and can take clear of a
// clearance margin: the self pairs worth optimising clearance over.
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
/// the configuration values `variables` move relative to each other and can take clear of
/// `margin` (m): the pair's signed distance varies, and exceeds the margin somewhere, over
/// `fixed` and options.samples configurations with those values drawn uniformly between their
/// limits (a continuous joint over one turn), the others as in `fixed`. Left out are pairs that
/// never get clear of the margin: links held close by the robot's design (a wrist over its
/// forearm, two links turning about a common axis), whose hinge would only tax path length
/// without ever being satisfied; and pairs that no listed value moves (a constant distance,
/// which no path can change). Pairs that rarely come near are kept: a hinge at the margin
/// costs nothing while they stay clear of it. The decision is sampled (a pair clear of the
/// margin only in configurations the samples miss is left out): it chooses which clearance to
/// optimise and report, never what is valid (validity always checks every pair).
/// Deterministic for a seed; cost: at most samples x checked pairs clearance queries, a pair
/// no longer queried once seen clear of the margin at two distances (later samples cannot
/// change its verdict): the pairs held close or never moved take the whole sample. Throws
/// InputError on a bad variable index, configuration, margin (finite, > 0) or option.
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
