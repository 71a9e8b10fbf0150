// CollisionChecker::is_valid_batch: validity of a block of configurations at once. Forward
// kinematics for the block (SIMD); link balls, covering spheres and inner balls against
// obstacle boxes and against each other for all lanes (SIMD kernels, ball_tests_block.cpp); the
// self blocks' distance tables (self_block_tables.cpp); and is_valid's exact tests
// (collision_verdict.cpp) only for what those leave undecided, at poses from the scalar forward
// kinematics: the verdicts are is_valid's.
//
// Why identical. The block poses differ from the scalar ones by rounding (below 1e-14 m on the
// robots tested, test RobotFk.*), far below kSlack. A block is skipped when volumes containing
// its shapes (link balls, shape balls, covering spheres) are clear by more than kSlack, or when its
// table proves the links apart by more than kTableSlack: the shapes are then apart at the scalar
// poses by more than the queries' tolerance, and is_valid's tests find no overlap in the block. A
// lane is invalid without exact tests when a ball inside a shape reaches more than kSlack into a
// box obstacle (the box itself, no margin), or when a self block's table proves its links
// overlapping by more than kTableSlack: the shapes overlap by more than the tolerance, and
// is_valid finds an overlap too. Everything else runs exactly as is_valid runs it.
#include <algorithm>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <string>

#include "ball_tests_block.hpp"
#include "collision_checker_internals.hpp"

namespace hullcheck {

namespace {

constexpr int kLanes = kPoseBlockLanes;
// Metres of slack on every ball test: far above the block poses' rounding, far below any gap
// the balls are meant to find.
constexpr double kSlack = 1e-9;

// A sphere (x, y, z in `link`'s frame, radius) at the block's poses: rows x, y, z, radius of
// kLanes values into `out`.
void place_sphere(const LinkPoseBlock& poses, int link, const Eigen::Vector4d& sphere,
                  double* out) {
  detail::place_spheres(poses.entry(link, 0), sphere.data(), 1, out);
}

}  // namespace

const double* CollisionChecker::place_cover(int begin, int end, Scratch& s) const {
  for (int shape = begin; shape < end; ++shape) {
    if (s.cover_placed[static_cast<std::size_t>(shape)] == s.block_stamp) continue;
    s.cover_placed[static_cast<std::size_t>(shape)] = s.block_stamp;
    const int link = shapes_[static_cast<std::size_t>(shape)].link;
    const auto c = static_cast<std::size_t>(cover_begin_[static_cast<std::size_t>(shape)]);
    detail::place_spheres(s.pose_block.entry(link, 0), cover_[c].data(),
                          cover_spheres(shape, shape + 1), s.cover_world.data() + c * 4 * kLanes);
  }
  return s.cover_world.data() +
         static_cast<std::size_t>(cover_begin_[static_cast<std::size_t>(begin)]) * 4 * kLanes;
}

std::uint8_t CollisionChecker::shape_clear_of_box(int shape, std::size_t obstacle, double slack,
                                                  std::uint8_t needed, Scratch& s) const {
  const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
  double ball[4 * kLanes];
  place_sphere(s.pose_block, rs.link,
               Eigen::Vector4d(rs.center.x(), rs.center.y(), rs.center.z(), rs.radius), ball);
  std::uint8_t clear = 0;
  detail::spheres_clear_of_boxes(ball, 1, box_values_.data() + obstacle * detail::kBoxValues, 1,
                                 slack, &clear);
  if ((needed & ~clear) == 0) return clear;
  return clear | cover_clear_of_box(shape, obstacle, slack, s);
}

std::uint8_t CollisionChecker::cover_clear_of_box(int shape, std::size_t obstacle, double slack,
                                                  Scratch& s) const {
  const double* spheres = place_cover(shape, shape + 1, s);
  const std::size_t n = cover_spheres(shape, shape + 1);
  s.sphere_box_clear.resize(n);
  detail::spheres_clear_of_boxes(spheres, n, box_values_.data() + obstacle * detail::kBoxValues, 1,
                                 slack, s.sphere_box_clear.data());
  std::uint8_t covered = 0xff;
  for (std::size_t i = 0; i < n; ++i) covered &= s.sphere_box_clear[i];
  return covered;
}

CollisionChecker::LinkCover CollisionChecker::link_cover(int link_ball) const {
  const int link = link_balls_[static_cast<std::size_t>(link_ball)].link;
  LinkCover c;
  c.first_shape = shape_begin_[static_cast<std::size_t>(link)];
  c.end_shape = shape_begin_[static_cast<std::size_t>(link) + 1];
  c.spheres = cover_spheres(c.first_shape, c.end_shape);
  return c;
}

std::size_t CollisionChecker::cover_spheres(int first_shape, int end_shape) const {
  return static_cast<std::size_t>(cover_begin_[static_cast<std::size_t>(end_shape)] -
                                  cover_begin_[static_cast<std::size_t>(first_shape)]);
}

void CollisionChecker::check_columns(const Eigen::Ref<const Eigen::MatrixXd>& configurations,
                                     const char* who) const {
  if (configurations.rows() != model_->variable_count()) {
    throw InputError(std::string("CollisionChecker::") + who + ": configurations have " +
                     std::to_string(configurations.rows()) + " rows, robot '" + model_->name() +
                     "' has " + std::to_string(model_->variable_count()) + " values");
  }
  for (Eigen::Index k = 0; k < configurations.cols(); ++k) {
    try {
      model_->check_configuration(configurations.col(k));
    } catch (const InputError& e) {
      throw InputError(std::string("CollisionChecker::") + who + ": column " + std::to_string(k) +
                       ": " + e.what());
    }
  }
  require_current_padding();
}

void CollisionChecker::place_block(const Eigen::Ref<const Eigen::MatrixXd>& configurations,
                                   Eigen::Index first, int count, Scratch& s) const {
  model_->compute_link_poses_block(configurations.col(first).data(), configurations.outerStride(),
                                   count, s.pose_block);
  ++s.block_stamp;  // covering spheres are placed for this block when first needed
  if (s.cover_placed.size() < shapes_.size()) s.cover_placed.resize(shapes_.size(), 0);
  if (s.cover_world.size() < cover_.size() * 4 * kLanes) {
    s.cover_world.resize(cover_.size() * 4 * kLanes);
  }
  const std::size_t balls = link_balls_.size();
  s.ball_centers.resize(balls * 4 * kLanes);
  for (std::size_t i = 0; i < balls; ++i) {
    const LinkBall& ball = link_balls_[i];
    place_sphere(s.pose_block, ball.link,
                 Eigen::Vector4d(ball.center[0], ball.center[1], ball.center[2], ball.radius),
                 s.ball_centers.data() + i * 4 * kLanes);
  }
}

void CollisionChecker::is_valid_batch(const Eigen::Ref<const Eigen::MatrixXd>& configurations,
                                      bool* valid) const {
  check_columns(configurations, "is_valid_batch");
  Scratch& s = scratch();
  for (Eigen::Index first = 0; first < configurations.cols(); first += kLanes) {
    const int count =
        static_cast<int>(std::min<Eigen::Index>(kLanes, configurations.cols() - first));
    is_valid_block(configurations, first, count, valid + first, s);
  }
}

void CollisionChecker::is_valid_block(const Eigen::Ref<const Eigen::MatrixXd>& configurations,
                                      Eigen::Index first, int count, bool* valid,
                                      Scratch& s) const {
  place_block(configurations, first, count, s);
  // Link balls against every obstacle box.
  const std::size_t balls = link_balls_.size();
  const std::size_t obstacles = boxes_.size();
  s.ball_box_clear.resize(balls * obstacles);
  detail::spheres_clear_of_boxes(s.ball_centers.data(), balls, box_values_.data(), obstacles,
                                 kSlack, s.ball_box_clear.data());
  const auto lanes_in_use = static_cast<std::uint8_t>((1u << count) - 1u);
  for (int k = 0; k < kLanes; ++k) s.undecided[k].clear();
  std::uint8_t colliding = 0;  // lanes proven in collision by an inner ball
  // Environment blocks: every link of the block's group clear of the obstacle's box, else each
  // of its shapes by its ball or all its covering spheres.
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const EnvironmentBlock& block = blocks_[b];
    const auto o = static_cast<std::size_t>(block.obstacle);
    const auto g = static_cast<std::size_t>(block.group);
    std::uint8_t clear = 0xff;
    for (int i = group_ball_begin_[g]; i < group_ball_begin_[g + 1]; ++i) {
      const auto ball = static_cast<std::size_t>(group_balls_[static_cast<std::size_t>(i)]);
      clear &= s.ball_box_clear[ball * obstacles + o];
    }
    if ((clear & lanes_in_use) == lanes_in_use) continue;
    std::uint8_t spheres_clear = 0xff;
    for (int p = block.begin; p < block.end && (spheres_clear & ~clear & lanes_in_use); ++p) {
      const int shape = environment_pairs_[static_cast<std::size_t>(p)].shape;
      spheres_clear &= shape_clear_of_box(
          shape, o, kSlack, static_cast<std::uint8_t>(spheres_clear & ~clear & lanes_in_use), s);
    }
    const std::uint8_t open = static_cast<std::uint8_t>(~(clear | spheres_clear) & lanes_in_use);
    if (open != 0 && exact_box_[o]) {
      // A box obstacle: a shape's inner ball reaching into it proves the lane colliding.
      for (int p = block.begin; p < block.end; ++p) {
        const int shape = environment_pairs_[static_cast<std::size_t>(p)].shape;
        double inner[4 * kLanes];
        place_sphere(s.pose_block, shapes_[static_cast<std::size_t>(shape)].link,
                     inner_[static_cast<std::size_t>(shape)], inner);
        colliding |=
            detail::spheres_in_box(inner, 1, box_values_.data() + o * detail::kBoxValues, kSlack) &
            open;
      }
    }
    for (int k = 0; k < count; ++k) {
      if (open & ~colliding & (1u << k)) s.undecided[k].push_back(static_cast<int>(b));
    }
  }
  // Self blocks: the two link balls apart, their covering spheres apart, or the block's table
  // proving the links apart (or overlapping) at the column's values (self_block_tables.cpp).
  s.self_balls_apart.resize(self_blocks_.size());
  detail::sphere_pairs_apart(s.ball_centers.data(), self_block_balls_.data(), self_blocks_.size(),
                             kSlack, s.self_balls_apart.data());
  // The table cells of a block's lanes whose balls meet are fetched one block ahead of their
  // lookups (random cells of tables of up to 64 MB: each lookup would miss the cache).
  const std::vector<SelfTable*>* tables = self_block_tables();
  const auto prefetch_cells = [&](std::size_t b) {
    const SelfTable* table = tables == nullptr || b >= self_blocks_.size() ? nullptr : (*tables)[b];
    if (table == nullptr) return;
    const std::uint8_t near = static_cast<std::uint8_t>(~s.self_balls_apart[b] & lanes_in_use);
    for (int k = 0; k < count; ++k) {
      if (near & (1u << k)) table->prefetch(configurations.col(first + k).data());
    }
  };
  prefetch_cells(0);
  for (std::size_t b = 0; b < self_blocks_.size(); ++b) {
    prefetch_cells(b + 1);
    const SelfBlock& block = self_blocks_[b];
    const auto ia = static_cast<std::size_t>(block.link_a);
    const auto ib = static_cast<std::size_t>(block.link_b);
    const std::uint8_t near = static_cast<std::uint8_t>(~s.self_balls_apart[b] & lanes_in_use);
    if (near == 0) continue;
    // The two links' covering spheres, pair by pair, when they are few.
    const LinkCover cover_a = link_cover(static_cast<int>(ia));
    const LinkCover cover_b = link_cover(static_cast<int>(ib));
    std::uint8_t apart = 0;
    if (cover_a.spheres * cover_b.spheres <= detail::kMaxSpherePairs) {
      apart = detail::spheres_apart(
          place_cover(cover_a.first_shape, cover_a.end_shape, s), cover_a.spheres,
          place_cover(cover_b.first_shape, cover_b.end_shape, s), cover_b.spheres, kSlack);
    }
    for (int k = 0; k < count; ++k) {
      if (!(near & ~apart & ~colliding & (1u << k))) continue;
      double lower = 0.0, upper = 0.0;
      if (self_block_bounds(static_cast<int>(b), configurations.col(first + k).data(), &lower,
                            &upper)) {
        if (lower > kTableSlack) continue;
        if (upper < -kTableSlack) {
          colliding |= static_cast<std::uint8_t>(1u << k);
          continue;
        }
      }
      s.undecided[k].push_back(-1 - static_cast<int>(b));
    }
  }
  // The exact tests, lane by lane, for what the balls left.
  for (int k = 0; k < count; ++k) {
    valid[k] = (colliding & (1u << k)) == 0;
    if (!valid[k] || s.undecided[k].empty()) continue;
    model_->compute_link_poses_unchecked(configurations.col(first + k).data(), s.link_poses.data());
    place(s.link_poses, s);
    s.q = configurations.col(first + k).data();  // the self tables' near shapes
    for (const int b : s.undecided[k]) {
      const bool overlaps =
          b >= 0 ? environment_block_collides(b, s) : self_block_collides(-1 - b, s);
      if (overlaps) {
        valid[k] = false;
        break;
      }
    }
  }
}

}  // namespace hullcheck
