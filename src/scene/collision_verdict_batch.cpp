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
    // The block's shape balls, for the lanes the link balls left: the block is decided when
    // each of its shapes' balls is clear of the box.
    bool open[kLanes];
    for (int k = 0; k < kLanes; ++k) open[k] = false;
    for (int p = block.begin; p < block.end; ++p) {
      const RobotShape& rs =
          shapes_[static_cast<std::size_t>(environment_pairs_[static_cast<std::size_t>(p)].shape)];
      double center[3][kLanes];
      for (int r = 0; r < 3; ++r) {
        const double* r0 = s.pose_block.entry(rs.link, 3 * r);
        const double* r1 = s.pose_block.entry(rs.link, 3 * r + 1);
        const double* r2 = s.pose_block.entry(rs.link, 3 * r + 2);
        const double* t = s.pose_block.entry(rs.link, 9 + r);
        for (int k = 0; k < kLanes; ++k) {
          center[r][k] = r0[k] * rs.center[0] + r1[k] * rs.center[1] + r2[k] * rs.center[2] + t[k];
        }
      }
      const double radius = rs.radius + kSlack;
      for (int k = 0; k < kLanes; ++k) {
        open[k] = open[k] || !clear_of_box(box, center[0][k], center[1][k], center[2][k], radius);
      }
    }
    for (int k = 0; k < count; ++k) {
      if (!clear[k] && open[k]) s.undecided[k].push_back(static_cast<int>(b));
    }
  }
  // Self blocks: the two link balls apart.
  for (std::size_t b = 0; b < self_blocks_.size(); ++b) {
    const SelfBlock& block = self_blocks_[b];
    const auto ia = static_cast<std::size_t>(block.link_a);
    const auto ib = static_cast<std::size_t>(block.link_b);
    const double reach = link_balls_[ia].radius + link_balls_[ib].radius + kSlack;
    const double* a = s.ball_centers.data() + ia * 3 * kLanes;
    const double* c = s.ball_centers.data() + ib * 3 * kLanes;
    for (int k = 0; k < count; ++k) {
      const double dx = a[k] - c[k], dy = a[kLanes + k] - c[kLanes + k],
                   dz = a[2 * kLanes + k] - c[2 * kLanes + k];
      if (dx * dx + dy * dy + dz * dz <= reach * reach) {
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
