// CollisionChecker::is_valid: the first overlapping pair, through the broad phase (group and
// link balls against obstacle boxes and each other, bounding hulls) and exact boolean GJK.
#include <cstdint>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/scene/collision_checker.hpp>

#include "collision_checker_internals.hpp"
#include "sphere_box_rows.hpp"

namespace hullcheck {

namespace {

// A ball is clear of an oriented box when its centre is further than its radius from the box.
// Forced inline here and below: the per-block tests run in is_valid's innermost loop (out of
// line, they cost a fifth more instructions per state on the Panda).
[[gnu::always_inline]] inline bool ball_clear_of_box(const Eigen::Matrix3d& box_rotation_t,
                                                     const Eigen::Vector3d& box_center,
                                                     const Eigen::Vector3d& half_extents,
                                                     const Eigen::Vector3d& c, double radius) {
  const Eigen::Vector3d local = box_rotation_t * (c - box_center);
  return (local.cwiseAbs() - half_extents).cwiseMax(0.0).squaredNorm() > radius * radius;
}

// A group ball is culled when clear of a box by more than this (m): far above the SIMD test's
// rounding (a few ulps of the coordinates), so a culled block is clear whatever the rounding.
constexpr double kBallSlack = 1e-9;

}  // namespace

[[gnu::always_inline]] inline bool CollisionChecker::environment_block_overlaps(
    const EnvironmentBlock& block, Scratch& s) const {
  // Balls against the obstacle's oriented box: the shape group's ball first, then its shapes'.
  const ObstacleBox& box = boxes_[static_cast<std::size_t>(block.obstacle)];
  const auto g = static_cast<std::size_t>(block.group);
  if (block.end - block.begin > 1 && ball_clear_of_box(box.rotation_t, box.center, box.half_extents,
                                                       s.group_centers[g], s.group_radii[g])) {
    return false;
  }
  return environment_block_shapes_overlap(block, s);
}

[[gnu::always_inline]] inline bool CollisionChecker::environment_block_shapes_overlap(
    const EnvironmentBlock& block, Scratch& s) const {
  const ObstacleBox& box = boxes_[static_cast<std::size_t>(block.obstacle)];
  const auto clear = [&box](const Eigen::Vector3d& c, double radius) {
    return ball_clear_of_box(box.rotation_t, box.center, box.half_extents, c, radius);
  };
  const auto g = static_cast<std::size_t>(block.group);
  const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(block.obstacle)];
  const int bound = groups_[g].bound;
  if (bound >= 0 && block.end - block.begin > 1) {
    // A decomposed mesh: its hull first (it contains every piece; one query, not one each).
    if (!intersect(bounding_shape(bound), shape_pose(bound, s), o.shape, o.pose)) return false;
  }
  for (int i = block.begin; i < block.end; ++i) {
    const int shape = environment_pairs_[static_cast<std::size_t>(i)].shape;
    if (clear(center(shape, s), shapes_[static_cast<std::size_t>(shape)].radius)) continue;
    if (intersect(shape_of(shape), shape_pose(shape, s), o.shape, o.pose)) return true;
  }
  return false;
}

bool CollisionChecker::piece_meets_hull(int shape, int other_ball, const Shape& other,
                                        const Eigen::Isometry3d& other_pose, std::uint64_t mark,
                                        Scratch& s) const {
  // s.meets_other[shape]: `mark` when it meets, mark | kMisses when it does not, else untested
  // (marks are below 2^63: a stamp shifted by 20 bits).
  constexpr std::uint64_t kMisses = std::uint64_t{1} << 63;
  std::uint64_t& known = s.meets_other[static_cast<std::size_t>(shape)];
  if ((known & ~kMisses) != mark) {
    // The other link's ball contains its hull: a piece whose ball misses it misses the hull.
    const double reach = shapes_[static_cast<std::size_t>(shape)].radius +
                         link_balls_[static_cast<std::size_t>(other_ball)].radius;
    const bool meets =
        (center(shape, s) - s.link_centers[static_cast<std::size_t>(other_ball)]).squaredNorm() <=
            reach * reach &&
        intersect(shape_of(shape), shape_pose(shape, s), other, other_pose);
    known = meets ? mark : mark | kMisses;
  }
  return known == mark;
}

[[gnu::always_inline]] inline bool CollisionChecker::self_block_overlaps(const SelfBlock& block,
                                                                         Scratch& s) const {
  const bool single = block.end - block.begin == 1;
  const SelfPair& first = self_pairs_[static_cast<std::size_t>(block.begin)];
  // Balls: the two links' (one pair: its shapes', which contain them more tightly).
  const double reach = single ? shapes_[static_cast<std::size_t>(first.a)].radius +
                                    shapes_[static_cast<std::size_t>(first.b)].radius
                              : link_balls_[static_cast<std::size_t>(block.link_a)].radius +
                                    link_balls_[static_cast<std::size_t>(block.link_b)].radius;
  const Eigen::Vector3d& center_a =
      single ? center(first.a, s) : s.link_centers[static_cast<std::size_t>(block.link_a)];
  const Eigen::Vector3d& center_b =
      single ? center(first.b, s) : s.link_centers[static_cast<std::size_t>(block.link_b)];
  if ((center_a - center_b).squaredNorm() > reach * reach) return false;
  // The block's distance table, when the query has a configuration: bounds proving the links
  // apart or overlapping by more than kTableSlack decide (the exact tests below would agree).
  // Else the cell's near shapes: only pairs of those can overlap.
  std::uint64_t near = kAllShapesNear;
  if (s.q != nullptr) {
    double lower = 0.0, upper = 0.0;
    if (self_block_bounds(static_cast<int>(&block - self_blocks_.data()), s.q, &lower, &upper,
                          &near)) {
      if (lower > kTableSlack) return false;
      if (upper < -kTableSlack) return true;
    }
  }
  // A block joining two rigid bodies with many blocks between them: their hulls, once for all
  // of them (the UR5's forearm against the gripper's twelve links: one query, not twelve).
  const int cluster = cluster_of_block_[static_cast<std::size_t>(&block - self_blocks_.data())];
  if (cluster >= 0 && many_blocks(cluster) && bodies_apart(cluster, s)) return false;
  const NearShapeBits bits = near_shape_bits(block);
  // Non-zero when a pair's pieces are tested against the other link's hull first (below).
  std::uint64_t mark = 0;
  struct {
    const Shape* hull_a;
    const Eigen::Isometry3d* pose_a;
    const Shape* hull_b;
    const Eigen::Isometry3d* pose_b;
  } hulls_of{};
  if (!single && near == kAllShapesNear) {
    // Links that are one shape or one decomposed mesh: their hulls first.
    const int bound_a = link_balls_[static_cast<std::size_t>(block.link_a)].bound;
    const int bound_b = link_balls_[static_cast<std::size_t>(block.link_b)].bound;
    if (bound_a >= 0 && bound_b >= 0) {
      const Shape& hull_a = bounding_shape(bound_a);
      const Shape& hull_b = bounding_shape(bound_b);
      const Eigen::Isometry3d& pose_a = shape_pose(bound_a, s);
      const Eigen::Isometry3d& pose_b = shape_pose(bound_b, s);
      if (!intersect(hull_a, pose_a, hull_b, pose_b)) return false;
      if (block.end - block.begin > kGroupSize) {
        // Many piece pairs: a pair is tested only when each of its pieces meets the other
        // link's hull (a piece clear of it is clear of that link's pieces), each piece tested
        // once, when a pair first needs it. A mark is this query and block's stamp. Measured
        // (bench_vamp, UR5, colliding blocks of decomposed links): testing every piece first
        // took 25-50 piece tests before the one or two pair tests that found the contact.
        mark = (s.stamp << 20) + static_cast<std::uint64_t>(&block - self_blocks_.data()) + 1;
        hulls_of = {&hull_a, &pose_a, &hull_b, &pose_b};
      }
    }
  }
  for (int k = block.begin; k < block.end; ++k) {
    const SelfPair& p = self_pairs_[static_cast<std::size_t>(k)];
    if (near != kAllShapesNear && !bits.both(near, p)) continue;  // apart by the table
    if (!single) {
      const double pair_reach = shapes_[static_cast<std::size_t>(p.a)].radius +
                                shapes_[static_cast<std::size_t>(p.b)].radius;
      if ((center(p.a, s) - center(p.b, s)).squaredNorm() > pair_reach * pair_reach) continue;
    }
    if (mark != 0 &&
        (!piece_meets_hull(p.a, block.link_b, *hulls_of.hull_b, *hulls_of.pose_b, mark, s) ||
         !piece_meets_hull(p.b, block.link_a, *hulls_of.hull_a, *hulls_of.pose_a, mark, s))) {
      continue;  // one of the two pieces is clear of the other link's hull
    }
    if (intersect(shape_of(p.a), shape_pose(p.a, s), shape_of(p.b), shape_pose(p.b, s))) {
      return true;
    }
  }
  return false;
}

bool CollisionChecker::bodies_apart(int cluster, Scratch& s) const {
  const auto k = static_cast<std::size_t>(cluster);
  // Per-thread scratch: allocates on first use only.
  if (s.bodies_tested.size() < self_clusters_.size()) {
    s.bodies_tested.resize(self_clusters_.size(), 0);
    s.bodies_were_apart.resize(self_clusters_.size(), 0);
  }
  if (s.bodies_tested[k] != s.stamp) {
    s.bodies_tested[k] = s.stamp;
    const SelfCluster& c = self_clusters_[k];
    const RigidBodyHull& a = bodies_[static_cast<std::size_t>(c.body_a)];
    const RigidBodyHull& b = bodies_[static_cast<std::size_t>(c.body_b)];
    const Eigen::Isometry3d& pose_a = (*s.link_poses_in)[static_cast<std::size_t>(a.root)];
    const Eigen::Isometry3d& pose_b = (*s.link_poses_in)[static_cast<std::size_t>(b.root)];
    const double reach = a.radius + b.radius;
    s.bodies_were_apart[k] =
        (pose_a * a.center - pose_b * b.center).squaredNorm() > reach * reach ||
        !intersect(*a.hull, pose_a, *b.hull, pose_b);
  }
  return s.bodies_were_apart[k] != 0;
}

bool CollisionChecker::environment_block_collides(int block, Scratch& s) const {
  return environment_block_overlaps(blocks_[static_cast<std::size_t>(block)], s);
}

bool CollisionChecker::self_block_collides(int block, Scratch& s) const {
  return self_block_overlaps(self_blocks_[static_cast<std::size_t>(block)], s);
}

bool CollisionChecker::is_valid(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  model_->check_configuration(q);
  Scratch& s = scratch();
  model_->compute_link_poses_unchecked(q.data(), s.link_poses.data());
  place(s.link_poses, s);
  s.q = q.data();  // self blocks' distance tables
  return placed_is_valid(s);
}

bool CollisionChecker::is_valid_at(const std::vector<Eigen::Isometry3d>& link_poses) const {
  Scratch& s = scratch();
  place(link_poses, s);
  return placed_is_valid(s);
}

bool CollisionChecker::placed_is_valid(Scratch& s) const {
  // The table cells of the self blocks whose links' balls meet, fetched while the environment
  // blocks are tested. Measured (bench_vamp, UR5: 4M cells, 64 MB): a lookup cost ~220 cycles.
  const std::vector<SelfTable*>* tables = s.q == nullptr ? nullptr : self_block_tables();
  for (std::size_t b = 0; tables != nullptr && b < self_blocks_.size(); ++b) {
    const SelfTable* table = (*tables)[b];
    if (table == nullptr) continue;
    const SelfBlock& block = self_blocks_[b];
    const double reach = link_balls_[static_cast<std::size_t>(block.link_a)].radius +
                         link_balls_[static_cast<std::size_t>(block.link_b)].radius;
    if ((s.link_centers[static_cast<std::size_t>(block.link_a)] -
         s.link_centers[static_cast<std::size_t>(block.link_b)])
            .squaredNorm() <= reach * reach) {
      table->prefetch(s.q);
    }
  }
  // Per shape group, its ball against every obstacle's box at once (SIMD across the boxes),
  // then the blocks of the boxes it reaches (one scalar test per block before). Measured
  // (three alternations, bench_python_reference --tables, states along lines, bookshelf_small
  // 1): is_valid 940-1011 -> 847-869 ns (Panda), 2.91-3.27 -> 2.73-2.83 us (UR5: 146 blocks).
  const std::size_t columns = detail::box_rows_padded(boxes_.size());
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    const int first = group_block_begin_[g], last = group_block_begin_[g + 1];
    if (first == last) continue;
    detail::sphere_clear_of_box_rows(box_rows_.data(), columns, s.group_centers[g].data(),
                                     s.group_radii[g], kBallSlack, s.boxes_clear.data());
    for (int b = first; b < last; ++b) {
      const EnvironmentBlock& block = blocks_[static_cast<std::size_t>(b)];
      const auto o = static_cast<std::size_t>(block.obstacle);
      if ((s.boxes_clear[o / 64] >> (o % 64)) & 1u) continue;
      if (environment_block_shapes_overlap(block, s)) return false;
    }
  }
  for (const SelfBlock& block : self_blocks_) {
    if (self_block_overlaps(block, s)) return false;
  }
  return true;
}

void CollisionChecker::colliding_link_pairs_at(const std::vector<Eigen::Isometry3d>& link_poses,
                                               std::vector<std::pair<int, int>>& out) const {
  Scratch& s = scratch();
  place(link_poses, s);
  for (const SelfBlock& block : self_blocks_) {
    if (self_block_overlaps(block, s)) {
      out.emplace_back(link_balls_[static_cast<std::size_t>(block.link_a)].link,
                       link_balls_[static_cast<std::size_t>(block.link_b)].link);
    }
  }
}

std::vector<std::pair<int, int>> CollisionChecker::checked_link_pairs() const {
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(self_blocks_.size());
  for (const SelfBlock& block : self_blocks_) {
    pairs.emplace_back(link_balls_[static_cast<std::size_t>(block.link_a)].link,
                       link_balls_[static_cast<std::size_t>(block.link_b)].link);
  }
  return pairs;
}

}  // namespace hullcheck
