// CollisionChecker::clearance_lower_bound_batch: lower bounds on the clearance of many
// configurations, a block of kPoseBlockLanes at a time.
//
// Every block of pairs (a shape group against an obstacle, or two links) gets a lower bound on
// its pairs' signed distance per lane from its links' (or groups') balls, all lanes at once.
// Blocks are then refined in increasing order of that bound: their covering spheres (each
// shape's spheres contain it, ball_gaps_block.cpp; an obstacle's box contains it) and a self
// block's measured table give a tighter bound, its term, less kRounding, when it is positive and
// at least e = max(exact_below, 0). Refining stops for a lane once the blocks left have ball
// bounds at or above its smallest term (they cannot go under it): that smallest term, the cap,
// is at most the clearance and at least e. A lane where some refined block has no term answers
// min(cap, clearance), from clearance()'s search capped there (exact below the cap,
// CollisionChecker::clearance's `below`): at most the clearance, and when below e the clearance
// itself.
#include <algorithm>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>

#include "ball_gaps_block.hpp"
#include "ball_tests_block.hpp"
#include "collision_checker_internals.hpp"

namespace hullcheck {

namespace {

constexpr int kLanes = kPoseBlockLanes;
// Metres taken off every bound: far above the block poses' rounding (below 1e-14 m on the
// robots tested) so that a bound never exceeds the clearance at the scalar poses.
constexpr double kRounding = 1e-9;

// True when `gap` (a lower bound on a block's distance at a lane) less kRounding is a term: a
// bound that is positive and at least e.
bool is_term(double gap, double e) {
  const double term = gap - kRounding;
  return term > 0.0 && term >= e;
}

}  // namespace

void CollisionChecker::clearance_lower_bound_batch(
    const Eigen::Ref<const Eigen::MatrixXd>& configurations, double exact_below,
    double* lower) const {
  if (std::isnan(exact_below)) {
    throw InputError("CollisionChecker::clearance_lower_bound_batch: exact_below is NaN");
  }
  check_columns(configurations, "clearance_lower_bound_batch");
  const double e = std::max(exact_below, 0.0);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const std::size_t n_env = blocks_.size(), n_blocks = n_env + self_blocks_.size();
  Scratch& s = scratch();
  s.block_gaps.resize(n_blocks * kLanes);
  for (Eigen::Index first = 0; first < configurations.cols(); first += kLanes) {
    const int count =
        static_cast<int>(std::min<Eigen::Index>(kLanes, configurations.cols() - first));
    place_block(configurations, first, count, s);
    // The balls' bound of every block, and the order to refine them in.
    s.block_order.clear();
    for (std::size_t b = 0; b < n_blocks; ++b) {
      double* gap = s.block_gaps.data() + b * kLanes;
      std::fill(gap, gap + kLanes, kInf);
      if (b < n_env) {
        const EnvironmentBlock& block = blocks_[b];
        const auto g = static_cast<std::size_t>(block.group);
        for (int k = group_ball_begin_[g]; k < group_ball_begin_[g + 1]; ++k) {
          const auto i = static_cast<std::size_t>(group_balls_[static_cast<std::size_t>(k)]);
          detail::lower_sphere_box_gap(
              s.ball_centers.data() + i * 4 * kLanes, 1,
              box_values_.data() + static_cast<std::size_t>(block.obstacle) * detail::kBoxValues,
              gap);
        }
      } else {
        const SelfBlock& block = self_blocks_[b - n_env];
        detail::lower_sphere_pair_gap(
            s.ball_centers.data() + static_cast<std::size_t>(block.link_a) * 4 * kLanes, 1,
            s.ball_centers.data() + static_cast<std::size_t>(block.link_b) * 4 * kLanes, 1, gap);
      }
      s.block_order.emplace_back(*std::min_element(gap, gap + count), static_cast<int>(b));
    }
    std::sort(s.block_order.begin(), s.block_order.end());
    double cap[kLanes];
    bool exact[kLanes] = {};
    std::fill(cap, cap + kLanes, kInf);
    for (const auto& [smallest, b] : s.block_order) {
      if (smallest >= *std::max_element(cap, cap + count)) break;  // nothing left lowers a cap
      double* gap = s.block_gaps.data() + static_cast<std::size_t>(b) * kLanes;
      bool lowers = false;
      for (int k = 0; k < count; ++k) lowers = lowers || gap[k] < cap[k];
      if (!lowers) continue;
      refine_block_gap(configurations, first, count, static_cast<std::size_t>(b), e, gap, s);
      for (int k = 0; k < count; ++k) {
        if (is_term(gap[k], e)) {
          cap[k] = std::min(cap[k], gap[k] - kRounding);
        } else {
          exact[k] = true;
        }
      }
    }
    // The lanes some block left: the exact search, capped at the lane's cap.
    for (int k = 0; k < count; ++k) {
      lower[first + k] =
          exact[k]
              ? std::min(
                    cap[k],
                    clearance(configurations.col(first + k), ClearanceScope::kAll, cap[k]).distance)
              : cap[k];
    }
  }
}

void CollisionChecker::refine_block_gap(const Eigen::Ref<const Eigen::MatrixXd>& configurations,
                                        Eigen::Index first, int count, std::size_t b, double e,
                                        double* gap, Scratch& s) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double spheres[kLanes];
  std::fill(spheres, spheres + kLanes, kInf);
  const std::size_t n_env = blocks_.size();
  if (b < n_env) {  // the pairs' shapes' covering spheres against the obstacle's box
    const EnvironmentBlock& block = blocks_[b];
    const double* box =
        box_values_.data() + static_cast<std::size_t>(block.obstacle) * detail::kBoxValues;
    for (int p = block.begin; p < block.end; ++p) {
      const int shape = environment_pairs_[static_cast<std::size_t>(p)].shape;
      detail::lower_sphere_box_gap(place_cover(shape, shape + 1, s),
                                   cover_spheres(shape, shape + 1), box, spheres);
    }
    for (int k = 0; k < count; ++k) gap[k] = std::max(gap[k], spheres[k]);
    return;
  }
  // Two links: their covering spheres when few enough, then the block's table where the
  // spheres leave no term.
  const SelfBlock& block = self_blocks_[b - n_env];
  const LinkCover cover_a = link_cover(block.link_a), cover_b = link_cover(block.link_b);
  if (cover_a.spheres * cover_b.spheres <= detail::kMaxSpherePairs) {
    detail::lower_sphere_pair_gap(
        place_cover(cover_a.first_shape, cover_a.end_shape, s), cover_a.spheres,
        place_cover(cover_b.first_shape, cover_b.end_shape, s), cover_b.spheres, spheres);
    for (int k = 0; k < count; ++k) gap[k] = std::max(gap[k], spheres[k]);
  }
  for (int k = 0; k < count; ++k) {
    double table_lower = 0.0, table_upper = 0.0;
    if (!is_term(gap[k], e) &&
        self_block_bounds(static_cast<int>(b - n_env), configurations.col(first + k).data(),
                          &table_lower, &table_upper)) {
      gap[k] = std::max(gap[k], table_lower);
    }
  }
}

}  // namespace hullcheck
