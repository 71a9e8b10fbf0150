// CollisionChecker::is_valid_batch: validity of a block of configurations at once. Forward
// kinematics for the block (SIMD), link balls against obstacle boxes and against each other for
// all lanes, and is_valid's exact tests (collision_verdict.cpp) only for what the balls leave
// undecided, at poses from the scalar forward kinematics: the verdicts are is_valid's.
//
// Why identical: a block is skipped only when every link ball it involves is clear by more than
// kSlack of the obstacle's box or of the other link's ball; the block poses differ from the
// scalar ones by rounding (below 1e-14 m on the robots tested, test RobotFk.*), so at the scalar
// poses every shape ball inside those link balls is clear too, and is_valid's per-shape ball
// tests decide "no overlap" for the block without any other test. Everything else runs exactly
// as is_valid runs it.
#include <algorithm>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <string>

#include "collision_checker_internals.hpp"

namespace hullcheck {

namespace {

constexpr int kLanes = kPoseBlockLanes;
// Metres of slack on every ball test: far above the block poses' rounding, far below any gap
// the balls are meant to find.
constexpr double kSlack = 1e-9;
// Covering-sphere pairs of a self block tested for the whole block at most (beyond, the lanes
// the link balls leave go to the exact tests).
constexpr int kMaxSpherePairs = 256;

}  // namespace

// A ball (centre x, y, z, model frame) clear of an obstacle's box: its centre in the box's frame
// further than the radius from the box.
inline bool CollisionChecker::clear_of_box(const ObstacleBox& box, double x, double y, double z,
                                           double radius) {
  const double dx = x - box.center[0], dy = y - box.center[1], dz = z - box.center[2];
  double gap2 = 0.0;
  for (int r = 0; r < 3; ++r) {
    const double local =
        box.rotation_t(r, 0) * dx + box.rotation_t(r, 1) * dy + box.rotation_t(r, 2) * dz;
    const double excess = std::max(std::abs(local) - box.half_extents[r], 0.0);
    gap2 += excess * excess;
  }
  return gap2 > radius * radius;
}

const double* CollisionChecker::place_cover(int begin, int end, Scratch& s) const {
  for (int shape = begin; shape < end; ++shape) {
    if (s.cover_placed[static_cast<std::size_t>(shape)] == s.block_stamp) continue;
    s.cover_placed[static_cast<std::size_t>(shape)] = s.block_stamp;
    const int link = shapes_[static_cast<std::size_t>(shape)].link;
    for (int c = cover_begin_[static_cast<std::size_t>(shape)];
         c < cover_begin_[static_cast<std::size_t>(shape) + 1]; ++c) {
      const Eigen::Vector4d& ball = cover_[static_cast<std::size_t>(c)];
      double* o = s.cover_world.data() + static_cast<std::size_t>(c) * 4 * kLanes;
      for (int r = 0; r < 3; ++r) {
        const double* r0 = s.pose_block.entry(link, 3 * r);
        const double* r1 = s.pose_block.entry(link, 3 * r + 1);
        const double* r2 = s.pose_block.entry(link, 3 * r + 2);
        const double* t = s.pose_block.entry(link, 9 + r);
        for (int k = 0; k < kLanes; ++k) {
          o[r * kLanes + k] = r0[k] * ball[0] + r1[k] * ball[1] + r2[k] * ball[2] + t[k];
        }
      }
      for (int k = 0; k < kLanes; ++k) o[3 * kLanes + k] = ball[3];
    }
  }
  return s.cover_world.data() +
         static_cast<std::size_t>(cover_begin_[static_cast<std::size_t>(begin)]) * 4 * kLanes;
}

void CollisionChecker::is_valid_batch(const Eigen::Ref<const Eigen::MatrixXd>& configurations,
                                      bool* valid) const {
  if (configurations.rows() != model_->variable_count()) {
    throw InputError("CollisionChecker::is_valid_batch: configurations have " +
                     std::to_string(configurations.rows()) + " rows, robot '" + model_->name() +
                     "' has " + std::to_string(model_->variable_count()) + " values");
  }
  for (Eigen::Index k = 0; k < configurations.cols(); ++k) {
    try {
      model_->check_configuration(configurations.col(k));
    } catch (const InputError& e) {
      throw InputError("CollisionChecker::is_valid_batch: column " + std::to_string(k) + ": " +
                       e.what());
    }
  }
  require_current_padding();
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
  model_->compute_link_poses_block(configurations.col(first).data(), configurations.outerStride(),
                                   count, s.pose_block);
  ++s.block_stamp;  // covering spheres are placed for this block when first needed
  if (s.cover_placed.size() < shapes_.size()) s.cover_placed.resize(shapes_.size(), 0);
  if (s.cover_world.size() < cover_.size() * 4 * kLanes) {
    s.cover_world.resize(cover_.size() * 4 * kLanes);
  }
  // Link ball centres, lane by lane (the loops over lanes vectorise).
  const std::size_t balls = link_balls_.size();
  s.ball_centers.resize(balls * 3 * kLanes);
  for (std::size_t i = 0; i < balls; ++i) {
    const LinkBall& ball = link_balls_[i];
    for (int r = 0; r < 3; ++r) {
      const double* r0 = s.pose_block.entry(ball.link, 3 * r);
      const double* r1 = s.pose_block.entry(ball.link, 3 * r + 1);
      const double* r2 = s.pose_block.entry(ball.link, 3 * r + 2);
      const double* t = s.pose_block.entry(ball.link, 9 + r);
      double* c = s.ball_centers.data() + (i * 3 + static_cast<std::size_t>(r)) * kLanes;
      for (int k = 0; k < kLanes; ++k) {
        c[k] = r0[k] * ball.center[0] + r1[k] * ball.center[1] + r2[k] * ball.center[2] + t[k];
      }
    }
  }
  for (int k = 0; k < kLanes; ++k) s.undecided[k].clear();
  // Environment blocks: every link of the block's group clear of the obstacle's box.
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const EnvironmentBlock& block = blocks_[b];
    const ObstacleBox& box = boxes_[static_cast<std::size_t>(block.obstacle)];
    const ShapeGroup& group = groups_[static_cast<std::size_t>(block.group)];
    bool clear[kLanes];
    for (int k = 0; k < kLanes; ++k) clear[k] = true;
    for (int sh = group.begin; sh < group.end;) {
      const int link = shapes_[static_cast<std::size_t>(sh)].link;
      const auto i = static_cast<std::size_t>(link_ball_of_link_[static_cast<std::size_t>(link)]);
      const double radius = link_balls_[i].radius + kSlack;
      const double* cx = s.ball_centers.data() + (i * 3) * kLanes;
      const double* cy = cx + kLanes;
      const double* cz = cy + kLanes;
      for (int k = 0; k < kLanes; ++k) {
        clear[k] = clear[k] && clear_of_box(box, cx[k], cy[k], cz[k], radius);
      }
      while (sh < group.end && shapes_[static_cast<std::size_t>(sh)].link == link) ++sh;
    }
    bool any = false;
    for (int k = 0; k < count; ++k) any = any || !clear[k];
    if (!any) continue;
    // The block's shapes' covering spheres, for the lanes the link balls left: the block is
    // decided when each is clear of the box.
    bool open[kLanes];
    for (int k = 0; k < kLanes; ++k) open[k] = false;
    for (int p = block.begin; p < block.end; ++p) {
      const int shape = environment_pairs_[static_cast<std::size_t>(p)].shape;
      const double* spheres = place_cover(shape, shape + 1, s);
      const int n = cover_begin_[static_cast<std::size_t>(shape) + 1] -
                    cover_begin_[static_cast<std::size_t>(shape)];
      for (int i = 0; i < n; ++i) {
        const double* c = spheres + static_cast<std::size_t>(i) * 4 * kLanes;
        for (int k = 0; k < kLanes; ++k) {
          open[k] = open[k] || !clear_of_box(box, c[k], c[kLanes + k], c[2 * kLanes + k],
                                             c[3 * kLanes + k] + kSlack);
        }
      }
    }
    for (int k = 0; k < count; ++k) {
      if (!clear[k] && open[k]) s.undecided[k].push_back(static_cast<int>(b));
    }
  }
  // Self blocks: the two link balls apart, their covering spheres apart, or the block's table
  // proving the links apart at the column's values (self_block_tables.cpp).
  const FreeCells& cells = free_cells();
  for (std::size_t b = 0; b < self_blocks_.size(); ++b) {
    const SelfBlock& block = self_blocks_[b];
    const auto ia = static_cast<std::size_t>(block.link_a);
    const auto ib = static_cast<std::size_t>(block.link_b);
    const double reach = link_balls_[ia].radius + link_balls_[ib].radius + kSlack;
    const double* a = s.ball_centers.data() + ia * 3 * kLanes;
    const double* c = s.ball_centers.data() + ib * 3 * kLanes;
    bool near[kLanes];
    bool any = false;
    for (int k = 0; k < kLanes; ++k) {
      const double dx = a[k] - c[k], dy = a[kLanes + k] - c[kLanes + k],
                   dz = a[2 * kLanes + k] - c[2 * kLanes + k];
      near[k] = k < count && dx * dx + dy * dy + dz * dz <= reach * reach;
      any = any || near[k];
    }
    if (!any) continue;
    // The two links' covering spheres, pair by pair, when they are few.
    const int la = link_balls_[ia].link, lb = link_balls_[ib].link;
    const int first_a = shape_begin_[static_cast<std::size_t>(la)];
    const int end_a = shape_begin_[static_cast<std::size_t>(la) + 1];
    const int first_b = shape_begin_[static_cast<std::size_t>(lb)];
    const int end_b = shape_begin_[static_cast<std::size_t>(lb) + 1];
    const int pairs = (cover_begin_[static_cast<std::size_t>(end_a)] -
                       cover_begin_[static_cast<std::size_t>(first_a)]) *
                      (cover_begin_[static_cast<std::size_t>(end_b)] -
                       cover_begin_[static_cast<std::size_t>(first_b)]);
    bool open[kLanes];
    for (int k = 0; k < kLanes; ++k) open[k] = near[k];
    if (pairs <= kMaxSpherePairs) {
      for (int k = 0; k < kLanes; ++k) open[k] = false;
      const double* spheres_a = place_cover(first_a, end_a, s);
      const double* spheres_b = place_cover(first_b, end_b, s);
      const int na = cover_begin_[static_cast<std::size_t>(end_a)] -
                     cover_begin_[static_cast<std::size_t>(first_a)];
      const int nb = cover_begin_[static_cast<std::size_t>(end_b)] -
                     cover_begin_[static_cast<std::size_t>(first_b)];
      for (int i = 0; i < na; ++i) {
        const double* p = spheres_a + static_cast<std::size_t>(i) * 4 * kLanes;
        for (int j = 0; j < nb; ++j) {
          const double* q = spheres_b + static_cast<std::size_t>(j) * 4 * kLanes;
          for (int k = 0; k < kLanes; ++k) {
            const double dx = p[k] - q[k], dy = p[kLanes + k] - q[kLanes + k],
                         dz = p[2 * kLanes + k] - q[2 * kLanes + k];
            const double r = p[3 * kLanes + k] + q[3 * kLanes + k] + kSlack;
            open[k] = open[k] || dx * dx + dy * dy + dz * dz <= r * r;
          }
        }
      }
    }
    for (int k = 0; k < count; ++k) {
      if (near[k] && open[k] &&
          !self_block_free(cells, static_cast<int>(b), configurations.col(first + k).data())) {
        s.undecided[k].push_back(-1 - static_cast<int>(b));
      }
    }
  }
  // The exact tests, lane by lane, for what the balls left.
  for (int k = 0; k < count; ++k) {
    valid[k] = true;
    if (s.undecided[k].empty()) continue;
    model_->compute_link_poses_unchecked(configurations.col(first + k).data(), s.link_poses.data());
    place(s.link_poses, s);
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
