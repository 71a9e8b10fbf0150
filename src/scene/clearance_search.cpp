// CollisionChecker::clearance: the nearest checked pair, by a best-first search over lower
// bounds (link and group balls, bounding hulls, slab bounds) with exact signed distances only
// for pairs whose bound could beat the best answer so far.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>
#include <utility>
#include <vector>

#include "collision_checker_internals.hpp"

namespace hullcheck {
namespace {

// Queue codes of nearest_pair's blocks (negative; pairs are 2 * pair + refined, >= 0): block
// `index` (self blocks first, then obstacle blocks), refined once its bounding shapes'
// distance is in.
int block_code(std::size_t index, bool refined) {
  return -1 - (2 * static_cast<int>(index) + (refined ? 1 : 0));
}
std::size_t block_index(int code) { return static_cast<std::size_t>((-1 - code) / 2); }
bool block_refined(int code) { return (-1 - code) % 2 == 1; }

}  // namespace

SignedDistanceResult CollisionChecker::pair_distance_below(std::size_t i, double cutoff,
                                                           Scratch& s) const {
  const std::size_t n_env = environment_pairs_.size();
  if (i < n_env) {
    const EnvironmentPair& p = environment_pairs_[i];
    const RobotShape& rs = shapes_[static_cast<std::size_t>(p.shape)];
    const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(p.obstacle)];
    return signed_distance_below(
        model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].shape,
        shape_pose(p.shape, s), o.shape, o.pose, cutoff);
  }
  const SelfPair& p = self_pairs_[i - n_env];
  const RobotShape& a = shapes_[static_cast<std::size_t>(p.a)];
  const RobotShape& b = shapes_[static_cast<std::size_t>(p.b)];
  const WarmStartGrid* grid = warm_grids_[i - n_env];
  if (grid != nullptr && s.q != nullptr) {
    WarmStart warm = grid->at(s.q);
    return signed_distance_below(
        model_->link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape, shape_pose(p.a, s),
        model_->link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape, shape_pose(p.b, s),
        cutoff, warm);
  }
  return signed_distance_below(model_->link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape,
                               shape_pose(p.a, s),
                               model_->link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape,
                               shape_pose(p.b, s), cutoff);
}

void CollisionChecker::check_below(double below) {
  if (std::isnan(below)) throw InputError("CollisionChecker::clearance: the cap `below` is NaN");
}

ClearanceResult CollisionChecker::clearance(const Eigen::Ref<const Eigen::VectorXd>& q,
                                            ClearanceScope scope, double below) const {
  check_below(below);
  model_->check_configuration(q);
  Scratch& s = scratch();
  model_->compute_link_poses_unchecked(q.data(), s.link_poses.data());
  place(s.link_poses, s);
  s.q = q.data();
  return nearest_pair(s, scope, nullptr, below);
}

ClearanceResult CollisionChecker::clearance_at(const std::vector<Eigen::Isometry3d>& link_poses,
                                               ClearanceScope scope) const {
  Scratch& s = scratch();
  place(link_poses, s);
  return nearest_pair(s, scope);
}

ClearanceResult CollisionChecker::clearance(const Eigen::Ref<const Eigen::VectorXd>& q,
                                            const PairScope& scope, double below) const {
  check_below(below);
  const char* mask = self_mask(scope);
  model_->check_configuration(q);
  Scratch& s = scratch();
  model_->compute_link_poses_unchecked(q.data(), s.link_poses.data());
  place(s.link_poses, s);
  s.q = q.data();
  return nearest_pair(s, scope.obstacles() ? ClearanceScope::kAll : ClearanceScope::kSelf, mask,
                      below);
}

ClearanceResult CollisionChecker::clearance_at(const std::vector<Eigen::Isometry3d>& link_poses,
                                               const PairScope& scope) const {
  const char* mask = self_mask(scope);
  Scratch& s = scratch();
  place(link_poses, s);
  return nearest_pair(s, scope.obstacles() ? ClearanceScope::kAll : ClearanceScope::kSelf, mask);
}

// The search of nearest_pair: best-first over the pairs by lower bounds on their signed
// distance, refined lazily. Every pair gets its bounding balls' bound (a link pair with many
// shape pairs, or an obstacle with a decomposed mesh's pieces, gets one block entry bounded by
// the links' or group's balls instead, expanded when it comes first, after the distance between
// the bounding shapes when both sides have one); a pair first in the queue with its ball bound
// gets the slab between the shapes' supporting planes (along the balls' direction, or a self
// pair's warm-start direction); a pair first with its slab bound gets its exact signed
// distance. With a cap `below`, the search starts as if a pair at `below` had been found: pairs
// bounded at or above it are never refined nor evaluated. `cut` is an upper bound on the minimum
// (the distance between two points of some pair's shapes, from the slabs): a pair whose bound
// exceeds it cannot be the closest. The search ends when the smallest bound left reaches the best
// exact value. Queue entries are (lower bound, code): pairs 2 * pair + 1 once their slab bound is
// in, blocks negative.
struct CollisionChecker::NearestSearch {
  using Entry = std::pair<double, int>;

  NearestSearch(const CollisionChecker& checker, Scratch& scratch, ClearanceScope scope,
                const char* mask, double below)
      : c(checker),
        s(scratch),
        n_env(checker.environment_pairs_.size()),
        with_self(scope != ClearanceScope::kObstacles),
        with_environment(scope != ClearanceScope::kSelf),
        self_mask(mask),
        cut(below) {
    best.distance = below;  // no pair yet (link_a -1): run() reports +inf if none beats it
  }

  const CollisionChecker& c;
  Scratch& s;
  std::size_t n_env;
  bool with_self, with_environment;  // the scope: which pairs are seeded
  const char* self_mask;             // per self block, 1: seeded (null: all)
  double cut;  // an upper bound on the answer (or the cap): pairs bounded above it are dropped
  ClearanceResult best;

  ClearanceResult run();
  /// The slab bound of pair i whose ball bound is `ball`: the refined lower bound; tightens the
  /// cut.
  double refine(std::size_t i, double ball);
  /// Ball bound of self pair k.
  double pair_ball(std::size_t k) const;
  /// The pairs of a self block with their ball bounds.
  void push_self_pairs(const SelfBlock& block, std::vector<Entry>* to) const;
  /// The pairs of an obstacle block with their ball bounds below the cut.
  void push_environment_pairs(const EnvironmentBlock& block, std::vector<Entry>* to) const;
  /// Entries for the self pairs and blocks into s.nearest; a block nearest of all is expanded.
  void seed_self_entries();
  /// Entries for the obstacle pairs and blocks whose ball bound is below the cut.
  void seed_environment_entries();
  /// Refines the nearest pair entry of s.nearest[from, end): its slab sets a first cut.
  void refine_nearest(std::size_t from);
  /// A block entry first in the queue: queued again with its bounding shapes' distance, or
  /// expanded into its pairs.
  void open_block(double bound, int code);
  /// The exact signed distance of pair i, taken as the best when it is below it.
  void evaluate(std::size_t i);
  void push(const Entry& entry) {
    s.candidates.push_back(entry);
    std::push_heap(s.candidates.begin(), s.candidates.end(), Later{});
  }
  // The heap's order (a function object, so that the heap operations inline it).
  struct Later {
    bool operator()(const Entry& x, const Entry& y) const { return x > y; }
  };
};

namespace {

// box_gap(box, c, radius) in *gap when it is below `cut`; the square root only then. Forced
// inline here and below: these run per pair in the search's inner loops (out of line, they
// cost a tenth more instructions per state on the Panda).
[[gnu::always_inline]] inline bool ball_below_cut(const Eigen::Matrix3d& box_rotation_t,
                                                  const Eigen::Vector3d& box_center,
                                                  const Eigen::Vector3d& half_extents,
                                                  const Eigen::Vector3d& c, double radius,
                                                  double cut, double* gap) {
  const Eigen::Vector3d local = box_rotation_t * (c - box_center);
  const Eigen::Vector3d excess = local.cwiseAbs() - half_extents;
  const double outside_squared = excess.cwiseMax(0.0).squaredNorm();
  if (outside_squared == 0.0) {
    *gap = excess.maxCoeff() - radius;
  } else {
    const double reach = cut + radius;  // gap < cut <=> outside < reach
    if (!(reach > 0.0) || outside_squared >= reach * reach) return false;
    *gap = std::sqrt(outside_squared) - radius;
  }
  return *gap < cut;
}

}  // namespace

ClearanceResult CollisionChecker::nearest_pair(Scratch& s, ClearanceScope scope,
                                               const char* self_mask, double below) const {
  NearestSearch search(*this, s, scope, self_mask, below);
  ClearanceResult best = search.run();
  // Nothing closer than the cap (or nothing checked): no pair, +inf.
  if (best.link_a < 0) best.distance = std::numeric_limits<double>::infinity();
  return best;
}

ClearanceResult CollisionChecker::NearestSearch::run() {
  // The nearest self entry and the nearest obstacle entry are refined at once: their slabs set
  // a first cut that culls most pairs (on arms the closest pair is often a self pair). Pairs
  // outside the scope are never seeded, so never queued: every later step sees only the scope.
  s.nearest.clear();
  if (with_self) {
    seed_self_entries();
    refine_nearest(0);
  }
  const std::size_t environment_begin = s.nearest.size();
  if (with_environment) {
    seed_environment_entries();
    refine_nearest(environment_begin);
  }
  if (s.nearest.empty()) return best;
  // The queue: a binary heap, smallest bound on top (ties by pair: deterministic).
  auto& queue = s.candidates;
  queue.clear();
  for (const Entry& entry : s.nearest) {
    if (entry.first <= cut) queue.push_back(entry);
  }
  std::make_heap(queue.begin(), queue.end(), Later{});
  // Each exact query stops as soon as it proves its pair no closer than the best so far (on a
  // colliding state, a separated pair costs a boolean test and a shallow one a few EPA steps).
  while (!queue.empty()) {
    std::pop_heap(queue.begin(), queue.end(), Later{});
    const auto [bound, code] = queue.back();
    queue.pop_back();
    // Strictly above the cut: the pair that set the cut has a bound at most the cut and is
    // still queued or evaluated.
    if (bound >= best.distance || bound > cut) break;
    if (code < 0) {
      open_block(bound, code);
      continue;
    }
    const auto i = static_cast<std::size_t>(code / 2);
    if (code % 2 == 1) {
      evaluate(i);
      continue;
    }
    const double refined = refine(i, bound);
    if (refined >= best.distance || refined > cut) continue;
    push({refined, code | 1});
  }
  return best;
}

double CollisionChecker::NearestSearch::refine(std::size_t i, double ball) {
  double slab, upper;
  if (i < n_env) {
    const EnvironmentPair& p = c.environment_pairs_[i];
    const RobotShape& rs = c.shapes_[static_cast<std::size_t>(p.shape)];
    const Obstacle& o = c.scene_.obstacles[static_cast<std::size_t>(p.obstacle)];
    Eigen::Vector3d towards_shape;
    c.box_gap(c.boxes_[static_cast<std::size_t>(p.obstacle)], c.center(p.shape, s), rs.radius,
              &towards_shape);
    slab_bounds(c.shape_of(p.shape), c.shape_pose(p.shape, s), o.shape, o.pose, -towards_shape,
                &slab, &upper);
  } else {
    const SelfPair& p = c.self_pairs_[i - n_env];
    const Eigen::Isometry3d& pose_a = c.shape_pose(p.a, s);
    Eigen::Vector3d n;
    const WarmStartGrid* grid = c.warm_grids_[i - n_env];
    const Eigen::Vector3d* direction =
        grid != nullptr && s.q != nullptr ? &grid->at(s.q).direction : nullptr;
    if (direction != nullptr && direction->squaredNorm() > 0.0) {
      // The closest pair's direction at the grid cell's centre: a near-optimal slab.
      n = -(pose_a.linear() * *direction).normalized();
    } else {  // the balls' direction
      const Eigen::Vector3d ab = c.center(p.b, s) - c.center(p.a, s);
      const double centres = ab.norm();
      if (!(centres > 0.0)) return ball;  // concentric balls: no direction, no slab
      n = ab / centres;
    }
    slab_bounds(c.shape_of(p.a), pose_a, c.shape_of(p.b), c.shape_pose(p.b, s), n, &slab, &upper);
  }
  // The pair's bound may exceed its own upper bound by rounding (two spheres: both are their
  // distance): the cut then takes the bound, so that the pair setting it is never dropped.
  const double bound = std::max(ball, slab);
  cut = std::min(cut, std::max(upper, bound));
  return bound;
}

[[gnu::always_inline]] inline double CollisionChecker::NearestSearch::pair_ball(
    std::size_t k) const {
  const SelfPair& p = c.self_pairs_[k];
  return (c.center(p.b, s) - c.center(p.a, s)).norm() -
         c.shapes_[static_cast<std::size_t>(p.a)].radius -
         c.shapes_[static_cast<std::size_t>(p.b)].radius;
}

[[gnu::always_inline]] inline void CollisionChecker::NearestSearch::push_self_pairs(
    const SelfBlock& block, std::vector<Entry>* to) const {
  for (int k = block.begin; k < block.end; ++k) {
    to->emplace_back(pair_ball(static_cast<std::size_t>(k)), 2 * static_cast<int>(n_env) + 2 * k);
  }
}

[[gnu::always_inline]] inline void CollisionChecker::NearestSearch::push_environment_pairs(
    const EnvironmentBlock& block, std::vector<Entry>* to) const {
  const ObstacleBox& box = c.boxes_[static_cast<std::size_t>(block.obstacle)];
  double ball = 0.0;
  for (int i = block.begin; i < block.end; ++i) {
    const int shape = c.environment_pairs_[static_cast<std::size_t>(i)].shape;
    if (ball_below_cut(box.rotation_t, box.center, box.half_extents, c.center(shape, s),
                       c.shapes_[static_cast<std::size_t>(shape)].radius, cut, &ball)) {
      to->emplace_back(ball, 2 * i);
    }
  }
}

[[gnu::flatten]] void CollisionChecker::NearestSearch::seed_self_entries() {
  for (std::size_t b = 0; b < c.self_blocks_.size(); ++b) {
    if (self_mask != nullptr && self_mask[b] == 0) continue;
    const SelfBlock& block = c.self_blocks_[b];
    if (block.end - block.begin <= kGroupSize) {
      push_self_pairs(block, &s.nearest);
      continue;
    }
    const LinkBall& la = c.link_balls_[static_cast<std::size_t>(block.link_a)];
    const LinkBall& lb = c.link_balls_[static_cast<std::size_t>(block.link_b)];
    s.nearest.emplace_back((s.link_centers[static_cast<std::size_t>(block.link_a)] -
                            s.link_centers[static_cast<std::size_t>(block.link_b)])
                                   .norm() -
                               la.radius - lb.radius,
                           block_code(b, false));
  }
  if (s.nearest.empty()) return;
  const auto it = std::min_element(s.nearest.begin(), s.nearest.end());
  if (it->second < 0) {  // the nearest entry a block: its pairs instead
    const SelfBlock& block = c.self_blocks_[block_index(it->second)];
    *it = s.nearest.back();
    s.nearest.pop_back();
    push_self_pairs(block, &s.nearest);
  }
}

[[gnu::flatten]] void CollisionChecker::NearestSearch::seed_environment_entries() {
  for (const EnvironmentBlock& block : c.blocks_) {
    const ObstacleBox& box = c.boxes_[static_cast<std::size_t>(block.obstacle)];
    const auto g = static_cast<std::size_t>(block.group);
    double ball = 0.0;
    if (block.end - block.begin > 1 &&
        !ball_below_cut(box.rotation_t, box.center, box.half_extents, s.group_centers[g],
                        s.group_radii[g], cut, &ball)) {
      continue;
    }
    if (c.groups_[g].bound >= 0 && block.end - block.begin > kGroupSize) {
      s.nearest.emplace_back(
          ball,
          block_code(c.self_blocks_.size() + static_cast<std::size_t>(&block - c.blocks_.data()),
                     false));
      continue;
    }
    push_environment_pairs(block, &s.nearest);
  }
}

void CollisionChecker::NearestSearch::refine_nearest(std::size_t from) {
  if (s.nearest.size() <= from) return;
  const auto it = std::min_element(
      s.nearest.begin() + static_cast<std::ptrdiff_t>(from), s.nearest.end(),
      [](const Entry& x, const Entry& y) {  // pairs only (blocks have negative codes)
        return (x.second >= 0) != (y.second >= 0) ? x.second >= 0 : x < y;
      });
  if (it->second < 0) return;
  it->first = refine(static_cast<std::size_t>(it->second / 2), it->first);
  it->second |= 1;
}

[[gnu::flatten]] void CollisionChecker::NearestSearch::open_block(double bound, int code) {
  const std::size_t index = block_index(code);
  const bool self_block = index < c.self_blocks_.size();
  if (!block_refined(code)) {
    // The bounding shapes' distance: a lower bound for every pair of the block (each side's
    // shapes lie in its bounding shape). Overlapping bounds bound nothing: expand.
    int bound_a = -1;
    const Shape* shape_b = nullptr;
    const Eigen::Isometry3d* pose_b = nullptr;
    if (self_block) {
      const SelfBlock& block = c.self_blocks_[index];
      bound_a = c.link_balls_[static_cast<std::size_t>(block.link_a)].bound;
      const int bound_b = c.link_balls_[static_cast<std::size_t>(block.link_b)].bound;
      if (bound_b >= 0) {
        shape_b = &c.bounding_shape(bound_b);
        pose_b = &c.shape_pose(bound_b, s);
      }
    } else {
      const EnvironmentBlock& block = c.blocks_[index - c.self_blocks_.size()];
      bound_a = c.groups_[static_cast<std::size_t>(block.group)].bound;
      const Obstacle& o = c.scene_.obstacles[static_cast<std::size_t>(block.obstacle)];
      shape_b = &o.shape;
      pose_b = &o.pose;
    }
    if (bound_a >= 0 && shape_b != nullptr) {
      ++best.exact_queries;
      const DistanceResult d =
          distance(c.bounding_shape(bound_a), c.shape_pose(bound_a, s), *shape_b, *pose_b);
      best.iterations += d.iterations;
      if (d.distance > 0.0) {
        const double refined = std::max(bound, d.distance);
        if (refined < best.distance && refined <= cut) push({refined, block_code(index, true)});
        return;
      }
    }
  }
  // The block's pairs with their own ball bounds.
  std::vector<Entry>& expanded = s.expanded;
  expanded.clear();
  if (self_block) {
    push_self_pairs(c.self_blocks_[index], &expanded);
  } else {
    push_environment_pairs(c.blocks_[index - c.self_blocks_.size()], &expanded);
  }
  for (const Entry& entry : expanded) {
    if (entry.first >= best.distance || entry.first > cut) continue;
    push(entry);
  }
}

void CollisionChecker::NearestSearch::evaluate(std::size_t i) {
  ++best.exact_queries;
  const SignedDistanceResult r = c.pair_distance_below(i, best.distance, s);
  best.iterations += r.iterations;
  if (r.status == Status::kAboveCutoff || !(r.signed_distance < best.distance)) return;
  best.distance = r.signed_distance;
  best.point_a = r.point_a;
  best.point_b = r.point_b;
  best.normal = r.normal;
  best.status = r.status;
  if (i < n_env) {
    const EnvironmentPair& p = c.environment_pairs_[i];
    const RobotShape& rs = c.shapes_[static_cast<std::size_t>(p.shape)];
    best.self = false;
    best.link_a = rs.link;
    best.shape_a = rs.shape;
    best.link_b = best.shape_b = -1;
    best.obstacle = p.obstacle;
    best.name_a = rs.link_name;
    best.name_b = c.scene_.obstacles[static_cast<std::size_t>(p.obstacle)].name;
  } else {
    const SelfPair& p = c.self_pairs_[i - n_env];
    const RobotShape& a = c.shapes_[static_cast<std::size_t>(p.a)];
    const RobotShape& b = c.shapes_[static_cast<std::size_t>(p.b)];
    best.self = true;
    best.link_a = a.link;
    best.shape_a = a.shape;
    best.link_b = b.link;
    best.shape_b = b.shape;
    best.obstacle = -1;
    best.name_a = a.link_name;
    best.name_b = b.link_name;
  }
}

}  // namespace hullcheck
