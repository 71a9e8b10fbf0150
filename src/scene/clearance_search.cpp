// CollisionChecker::clearance: the nearest checked pair, by a best-first search over lower
// bounds (link and group balls, bounding hulls, slab bounds) with exact signed distances only
// for pairs whose bound could beat the best answer so far.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/scene/collision_checker.hpp>

#include "collision_checker_internals.hpp"

namespace hullcheck {
namespace {

// Bounds on the signed distance of A and B from their supporting planes normal to the unit
// vector n (from A towards B): every point of A is at most n.a_max along n, every point of
// B at least n.b_min, so distance >= n.(b_min - a_max) (and depth <= -that when overlapping:
// the difference A - B reaches no further than that along -n). The two support points are
// points of the shapes, so their distance bounds the signed distance from above.
void slab_bounds(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                 const Eigen::Isometry3d& pose_b, const Eigen::Vector3d& n, double* lower,
                 double* upper) {
  const Eigen::Vector3d a_max = pose_a * a.support(pose_a.linear().transpose() * n);
  const Eigen::Vector3d b_min = pose_b * b.support(-(pose_b.linear().transpose() * n));
  *lower = n.dot(b_min - a_max);
  *upper = (b_min - a_max).norm();
}

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
  const WarmStartGrid& grid = warm_grids_[i - n_env];
  if (grid.dims >= 0 && s.q != nullptr) {
    WarmStart warm = grid.at(s.q);
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

ClearanceResult CollisionChecker::clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  model_->check_configuration(q);
  Scratch& s = scratch();
  model_->compute_link_poses_unchecked(q.data(), s.link_poses.data());
  place(s.link_poses, s);
  s.q = q.data();
  return nearest_pair(s);
}

ClearanceResult CollisionChecker::clearance_at(
    const std::vector<Eigen::Isometry3d>& link_poses) const {
  Scratch& s = scratch();
  place(link_poses, s);
  return nearest_pair(s);
}

ClearanceResult CollisionChecker::nearest_pair(Scratch& s) const {
  ClearanceResult best;
  const std::size_t n_env = environment_pairs_.size();
  if (n_env + self_pairs_.size() == 0) return best;
  // Best-first search over the pairs by lower bounds on their signed distance, refined lazily:
  // bounding balls (and, for a group of shapes, the group's ball) for every pair, the slab
  // between the shapes' supporting planes (along the balls' direction, or a self pair's
  // warm-start direction) only for a pair that comes first with its ball bound, and the exact
  // signed distance only for a pair that comes first with its slab bound. `cut` is an upper
  // bound on the minimum (the distance between two points of some pair's shapes, from the
  // slabs): a pair whose bound exceeds it cannot be the closest. The search ends when the
  // smallest bound left reaches the best exact value. Queue entries: (lower bound, 2 * pair + 1
  // once the slab bound is in).
  double cut = std::numeric_limits<double>::infinity();
  // Slab bound of pair i whose ball bound is `ball`: the refined lower bound; tightens the cut.
  const auto refine = [&](std::size_t i, double ball) {
    double slab, upper;
    if (i < n_env) {
      const EnvironmentPair& p = environment_pairs_[i];
      const RobotShape& rs = shapes_[static_cast<std::size_t>(p.shape)];
      const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(p.obstacle)];
      Eigen::Vector3d towards_shape;
      box_gap(boxes_[static_cast<std::size_t>(p.obstacle)], center(p.shape, s), rs.radius,
              &towards_shape);
      slab_bounds(model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].shape,
                  shape_pose(p.shape, s), o.shape, o.pose, -towards_shape, &slab, &upper);
    } else {
      const SelfPair& p = self_pairs_[i - n_env];
      const RobotShape& a = shapes_[static_cast<std::size_t>(p.a)];
      const RobotShape& b = shapes_[static_cast<std::size_t>(p.b)];
      const Eigen::Isometry3d& pose_a = shape_pose(p.a, s);
      Eigen::Vector3d n;
      const WarmStartGrid& grid = warm_grids_[i - n_env];
      const Eigen::Vector3d* direction =
          grid.dims >= 0 && s.q != nullptr ? &grid.at(s.q).direction : nullptr;
      if (direction != nullptr && direction->squaredNorm() > 0.0) {
        // The closest pair's direction at the grid cell's centre: a near-optimal slab.
        n = -(pose_a.linear() * *direction).normalized();
      } else {  // the balls' direction
        const Eigen::Vector3d ab = center(p.b, s) - center(p.a, s);
        const double centres = ab.norm();
        if (!(centres > 0.0)) return ball;  // concentric balls: no direction, no slab
        n = ab / centres;
      }
      slab_bounds(model_->link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape, pose_a,
                  model_->link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape,
                  shape_pose(p.b, s), n, &slab, &upper);
    }
    // The pair's bound may exceed its own upper bound by rounding (two spheres: both are their
    // distance): the cut then takes the bound, so that the pair setting it is never dropped.
    const double bound = std::max(ball, slab);
    cut = std::min(cut, std::max(upper, bound));
    return bound;
  };
  // Ball bounds of the self pairs, a link pair with several shape pairs (decomposed meshes) as
  // one entry bounded by the links' balls (a block code, negative), expanded into its pairs
  // when it comes first. A block of an obstacle and a decomposed mesh's pieces likewise. Block
  // entries come first with their ball bound, then (when both sides have one bounding shape)
  // with the distance between the bounding shapes, a lower bound for every pair inside. The nearest
  // pair is refined at once: its slab sets a first cut that culls most obstacle pairs (on arms the
  // closest pair is often a self pair).
  s.nearest.clear();
  const auto pair_ball = [&](std::size_t k) {
    const SelfPair& p = self_pairs_[k];
    return (center(p.b, s) - center(p.a, s)).norm() -
           shapes_[static_cast<std::size_t>(p.a)].radius -
           shapes_[static_cast<std::size_t>(p.b)].radius;
  };
  const auto push_pairs = [&](const SelfBlock& block, std::vector<std::pair<double, int>>* to) {
    for (int k = block.begin; k < block.end; ++k) {
      to->emplace_back(pair_ball(static_cast<std::size_t>(k)), 2 * static_cast<int>(n_env) + 2 * k);
    }
  };
  for (std::size_t b = 0; b < self_blocks_.size(); ++b) {
    const SelfBlock& block = self_blocks_[b];
    if (block.end - block.begin <= kGroupSize) {
      push_pairs(block, &s.nearest);
      continue;
    }
    const LinkBall& la = link_balls_[static_cast<std::size_t>(block.link_a)];
    const LinkBall& lb = link_balls_[static_cast<std::size_t>(block.link_b)];
    s.nearest.emplace_back((s.link_centers[static_cast<std::size_t>(block.link_a)] -
                            s.link_centers[static_cast<std::size_t>(block.link_b)])
                                   .norm() -
                               la.radius - lb.radius,
                           block_code(b, false));
  }
  if (!s.nearest.empty()) {  // the nearest entry a block: its pairs instead
    const auto it = std::min_element(s.nearest.begin(), s.nearest.end());
    if (it->second < 0) {
      const SelfBlock& block = self_blocks_[block_index(it->second)];
      *it = s.nearest.back();
      s.nearest.pop_back();
      push_pairs(block, &s.nearest);
    }
  }
  const auto refine_nearest = [&](std::size_t from) {
    if (s.nearest.size() <= from) return;
    const auto it = std::min_element(
        s.nearest.begin() + static_cast<std::ptrdiff_t>(from), s.nearest.end(),
        [](const auto& x, const auto& y) {  // pairs only (blocks have negative codes)
          return (x.second >= 0) != (y.second >= 0) ? x.second >= 0 : x < y;
        });
    if (it->second < 0) return;
    it->first = refine(static_cast<std::size_t>(it->second / 2), it->first);
    it->second |= 1;
  };
  refine_nearest(0);
  // box_gap(box, c, radius) when it is below the cut; the square root only then.
  const auto ball_below_cut = [](const ObstacleBox& box, const Eigen::Vector3d& c, double radius,
                                 double cut_now, double* gap) {
    const Eigen::Vector3d local = box.rotation_t * (c - box.center);
    const Eigen::Vector3d excess = local.cwiseAbs() - box.half_extents;
    const double outside_squared = excess.cwiseMax(0.0).squaredNorm();
    if (outside_squared == 0.0) {
      *gap = excess.maxCoeff() - radius;
    } else {
      const double reach = cut_now + radius;  // gap < cut <=> outside < reach
      if (!(reach > 0.0) || outside_squared >= reach * reach) return false;
      *gap = std::sqrt(outside_squared) - radius;
    }
    return *gap < cut_now;
  };
  // The pairs of an obstacle block with their ball bounds below the cut.
  const auto push_environment_pairs = [&](const EnvironmentBlock& block,
                                          std::vector<std::pair<double, int>>* to) {
    const ObstacleBox& box = boxes_[static_cast<std::size_t>(block.obstacle)];
    double ball = 0.0;
    for (int i = block.begin; i < block.end; ++i) {
      const int shape = environment_pairs_[static_cast<std::size_t>(i)].shape;
      if (ball_below_cut(box, center(shape, s), shapes_[static_cast<std::size_t>(shape)].radius,
                         cut, &ball)) {
        to->emplace_back(ball, 2 * i);
      }
    }
  };
  const std::size_t environment_begin = s.nearest.size();
  for (const EnvironmentBlock& block : blocks_) {
    const ObstacleBox& box = boxes_[static_cast<std::size_t>(block.obstacle)];
    const auto g = static_cast<std::size_t>(block.group);
    double ball = 0.0;
    if (block.end - block.begin > 1 &&
        !ball_below_cut(box, s.group_centers[g], s.group_radii[g], cut, &ball)) {
      continue;
    }
    if (groups_[g].bound >= 0 && block.end - block.begin > kGroupSize) {
      s.nearest.emplace_back(
          ball, block_code(self_blocks_.size() + static_cast<std::size_t>(&block - blocks_.data()),
                           false));
      continue;
    }
    push_environment_pairs(block, &s.nearest);
  }
  refine_nearest(environment_begin);  // the nearest obstacle pair tightens the cut in turn
  // The queue: a binary heap, smallest bound on top (ties by pair: deterministic).
  auto& queue = s.candidates;
  queue.clear();
  for (const auto& entry : s.nearest) {
    if (entry.first <= cut) queue.push_back(entry);
  }
  const auto later = [](const std::pair<double, int>& x, const std::pair<double, int>& y) {
    return x > y;
  };
  std::make_heap(queue.begin(), queue.end(), later);
  const auto evaluate = [&](std::size_t i) {
    ++best.exact_queries;
    const SignedDistanceResult r = pair_distance_below(i, best.distance, s);
    best.iterations += r.iterations;
    if (r.status == Status::kAboveCutoff || !(r.signed_distance < best.distance)) return;
    best.distance = r.signed_distance;
    best.point_a = r.point_a;
    best.point_b = r.point_b;
    best.normal = r.normal;
    best.status = r.status;
    if (i < n_env) {
      const EnvironmentPair& p = environment_pairs_[i];
      const RobotShape& rs = shapes_[static_cast<std::size_t>(p.shape)];
      best.self = false;
      best.link_a = rs.link;
      best.shape_a = rs.shape;
      best.link_b = best.shape_b = -1;
      best.obstacle = p.obstacle;
      best.name_a = rs.link_name;
      best.name_b = scene_.obstacles[static_cast<std::size_t>(p.obstacle)].name;
    } else {
      const SelfPair& p = self_pairs_[i - n_env];
      const RobotShape& a = shapes_[static_cast<std::size_t>(p.a)];
      const RobotShape& b = shapes_[static_cast<std::size_t>(p.b)];
      best.self = true;
      best.link_a = a.link;
      best.shape_a = a.shape;
      best.link_b = b.link;
      best.shape_b = b.shape;
      best.obstacle = -1;
      best.name_a = a.link_name;
      best.name_b = b.link_name;
    }
  };

  // Each exact query stops as soon as it proves its pair no closer than the best so far (on a
  // colliding state, a separated pair costs a boolean test and a shallow one a few EPA steps).
  while (!queue.empty()) {
    std::pop_heap(queue.begin(), queue.end(), later);
    const auto [bound, code] = queue.back();
    queue.pop_back();
    // Strictly above the cut: the pair that set the cut has a bound at most the cut and is
    // still queued or evaluated.
    if (bound >= best.distance || bound > cut) break;
    if (code < 0) {
      const std::size_t index = block_index(code);
      const bool self_block = index < self_blocks_.size();
      if (!block_refined(code)) {
        // The bounding shapes' distance: a lower bound for every pair of the block (each
        // side's shapes lie in its bounding shape). Overlapping bounds bound nothing: expand.
        int bound_a = -1, bound_b = -1;
        const Shape* shape_b = nullptr;
        const Eigen::Isometry3d* pose_b = nullptr;
        if (self_block) {
          const SelfBlock& block = self_blocks_[index];
          bound_a = link_balls_[static_cast<std::size_t>(block.link_a)].bound;
          bound_b = link_balls_[static_cast<std::size_t>(block.link_b)].bound;
          if (bound_b >= 0) {
            shape_b = &bounding_shape(bound_b);
            pose_b = &shape_pose(bound_b, s);
          }
        } else {
          const EnvironmentBlock& block = blocks_[index - self_blocks_.size()];
          bound_a = groups_[static_cast<std::size_t>(block.group)].bound;
          const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(block.obstacle)];
          shape_b = &o.shape;
          pose_b = &o.pose;
        }
        if (bound_a >= 0 && shape_b != nullptr) {
          ++best.exact_queries;
          const DistanceResult d =
              distance(bounding_shape(bound_a), shape_pose(bound_a, s), *shape_b, *pose_b);
          best.iterations += d.iterations;
          if (d.distance > 0.0) {
            const double refined = std::max(bound, d.distance);
            if (refined >= best.distance || refined > cut) continue;
            queue.emplace_back(refined, block_code(index, true));
            std::push_heap(queue.begin(), queue.end(), later);
            continue;
          }
        }
      }
      // The block's pairs with their own ball bounds.
      std::vector<std::pair<double, int>>& expanded = s.expanded;
      expanded.clear();
      if (self_block) {
        push_pairs(self_blocks_[index], &expanded);
      } else {
        push_environment_pairs(blocks_[index - self_blocks_.size()], &expanded);
      }
      for (const auto& entry : expanded) {
        if (entry.first >= best.distance || entry.first > cut) continue;
        queue.push_back(entry);
        std::push_heap(queue.begin(), queue.end(), later);
      }
      continue;
    }
    const auto i = static_cast<std::size_t>(code / 2);
    if (code % 2 == 1) {
      evaluate(i);
      continue;
    }
    const double refined = refine(i, bound);
    if (refined >= best.distance || refined > cut) continue;
    queue.emplace_back(refined, code | 1);
    std::push_heap(queue.begin(), queue.end(), later);
  }
  return best;
}

}  // namespace hullcheck
