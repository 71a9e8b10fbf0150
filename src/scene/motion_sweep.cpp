// CollisionChecker::sweep_environment and sweep_self: check_motion's certificate for a whole
// motion at once, its kPoseBlockLanes sampled intervals in one block (SIMD forward kinematics and
// ball tests, as is_valid_batch's).
//
// The bound. Lane k holds q(t_k), t_k = (2k + 1) h with h = 1 / (2 kPoseBlockLanes): the lanes'
// intervals [t_k - h, t_k + h] tile [0, 1]. Within its interval a shape of group g moves at most
// h rate_g (rate_g >= every member shape's rate, motion_bounds.cpp), and a volume containing the
// shape at q(t_k) (its group's link balls, its covering spheres) holds it at q(t_k); so that
// volume clear of an obstacle's box by more than h rate + min_clearance proves the shape keeps
// clearance > min_clearance from the obstacle over the whole interval. The box contains the
// obstacle. A self block likewise with its relative rate (joints above both links do not
// count): its links' balls or all pairs of their covering spheres apart by more than
// h rate + min_clearance; else its distance table's cells over the box of values the interval
// spans all above min_clearance (self_block_box_lower, no rate needed). The block poses differ
// from the scalar ones by rounding (below 1e-14 m, test RobotFk.*), far below kSlack, which
// every ball test adds.
//
// Collisions. A lane whose shape's inner ball reaches more than kSlack into a box obstacle (the
// box is the obstacle itself) collides there: is_valid_batch's proof. The first such shape ends
// the sweep.
#include <cstdint>
#include <hullcheck/scene/collision_checker.hpp>

#include "ball_tests_block.hpp"
#include "collision_checker_internals.hpp"

namespace hullcheck {

namespace {

constexpr int kLanes = kPoseBlockLanes;
constexpr double kSlack = 1e-9;  // m, as is_valid_batch's

}  // namespace

std::uint8_t CollisionChecker::sweep_environment(const Eigen::Ref<const Eigen::VectorXd>& q0,
                                                 const Eigen::VectorXd& dq,
                                                 const Eigen::VectorXd& abs_dq, double extra,
                                                 double min_clearance, std::uint8_t* colliding,
                                                 Scratch& s) const {
  const MotionLevers& levers = motion_levers();
  const int n = model_->variable_count();
  if (s.motion_probes.rows() != n) s.motion_probes.resize(n, kLanes);
  const double h = 0.5 / kLanes;
  for (int k = 0; k < kLanes; ++k) s.motion_probes.col(k) = q0 + ((2 * k + 1) * h) * dq;
  place_block(s.motion_probes, 0, kLanes, s);
  const std::size_t obstacles = boxes_.size();
  s.ball_box_clear.resize(link_balls_.size() * obstacles);
  std::uint8_t clear_all = 0xff;  // lanes with every block proven so far
  *colliding = 0;
  s.sweep_group_lanes.assign(groups_.size(), 0);
  // Per group: its links' balls against every box, with the group's rate.
  for (std::size_t g = 0; g < groups_.size() && clear_all != 0; ++g) {
    const int first = group_block_begin_[g], last = group_block_begin_[g + 1];
    if (first == last) continue;
    const std::uint8_t open = clear_all;  // the lanes this group is tested in
    const double group_slack =
        h * (levers.group_levers.row(static_cast<Eigen::Index>(g)).dot(abs_dq) + extra) +
        min_clearance + kSlack;
    for (int i = group_ball_begin_[g]; i < group_ball_begin_[g + 1]; ++i) {
      const auto ball = static_cast<std::size_t>(group_balls_[static_cast<std::size_t>(i)]);
      detail::spheres_clear_of_boxes(s.ball_centers.data() + ball * 4 * kLanes, 1,
                                     box_values_.data(), obstacles, group_slack,
                                     s.ball_box_clear.data() + ball * obstacles);
    }
    const ShapeGroup& group = groups_[g];
    bool shape_balls = false;  // the group's shapes' balls placed
    for (int b = first; b < last && clear_all != 0; ++b) {
      const EnvironmentBlock& block = blocks_[static_cast<std::size_t>(b)];
      const auto o = static_cast<std::size_t>(block.obstacle);
      std::uint8_t clear = 0xff;
      for (int i = group_ball_begin_[g]; i < group_ball_begin_[g + 1]; ++i) {
        const auto ball = static_cast<std::size_t>(group_balls_[static_cast<std::size_t>(i)]);
        clear &= s.ball_box_clear[ball * obstacles + o];
      }
      if ((clear_all & ~clear) == 0) continue;
      // The block's shapes: their balls, each grown by its own rate's margin, all in one test;
      // then the covering spheres of those whose ball leaves lanes.
      if (!shape_balls) {
        place_group_shape_balls(group, h, abs_dq, extra, min_clearance, s);
        shape_balls = true;
      }
      const auto shapes = static_cast<std::size_t>(group.end - group.begin);
      s.group_shape_clear.resize(shapes);  // its own buffer: the covering spheres' is reused below
      detail::spheres_clear_of_boxes(s.group_shape_balls.data(), shapes,
                                     box_values_.data() + o * detail::kBoxValues, 1, kSlack,
                                     s.group_shape_clear.data());
      for (int p = block.begin; p < block.end && (clear_all & ~clear) != 0; ++p) {
        const int shape = environment_pairs_[static_cast<std::size_t>(p)].shape;
        std::uint8_t shape_clear =
            s.group_shape_clear[static_cast<std::size_t>(shape - group.begin)];
        if ((clear_all & ~clear & ~shape_clear) != 0) {
          const double slack =
              h * (levers.shape_levers.row(shape).dot(abs_dq) + extra) + min_clearance + kSlack;
          shape_clear |= cover_clear_of_box(shape, o, slack, s);
        }
        if (shape_clear != 0xff && exact_box_[o]) {
          double inner[4 * kLanes];
          detail::place_spheres(
              s.pose_block.entry(shapes_[static_cast<std::size_t>(shape)].link, 0),
              inner_[static_cast<std::size_t>(shape)].data(), 1, inner);
          *colliding |=
              detail::spheres_in_box(inner, 1, box_values_.data() + o * detail::kBoxValues, kSlack);
          // The motion collides: the rest would only look for more contacts. Measured
          // (bench_vamp, 30 Panda / 10 UR5 problems per family, cycle counters, two
          // alternations): motions the sweep proves colliding 5.8-6.3k -> 4.1k cycles (Panda),
          // 13.8-15.4k -> 8.6-8.8k (UR5).
          if (*colliding != 0) return 0;
        }
        clear_all &= shape_clear | clear;
      }
    }
    s.sweep_group_lanes[g] = open & clear_all;
  }
  return clear_all;
}

void CollisionChecker::place_group_shape_balls(const ShapeGroup& group, double h,
                                               const Eigen::VectorXd& abs_dq, double extra,
                                               double min_clearance, Scratch& s) const {
  const MotionLevers& levers = motion_levers();
  const auto shapes = static_cast<std::size_t>(group.end - group.begin);
  s.group_shape_spheres.resize(4 * shapes);
  s.group_shape_balls.resize(4 * kLanes * shapes);
  for (std::size_t i = 0; i < shapes; ++i) {
    const int shape = group.begin + static_cast<int>(i);
    const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
    double* sphere = s.group_shape_spheres.data() + 4 * i;
    sphere[0] = rs.center.x();
    sphere[1] = rs.center.y();
    sphere[2] = rs.center.z();
    sphere[3] =
        rs.radius + h * (levers.shape_levers.row(shape).dot(abs_dq) + extra) + min_clearance;
  }
  // One placement per run of shapes on the same link.
  for (std::size_t i = 0; i < shapes;) {
    const int link = shapes_[static_cast<std::size_t>(group.begin) + i].link;
    std::size_t j = i + 1;
    while (j < shapes && shapes_[static_cast<std::size_t>(group.begin) + j].link == link) ++j;
    detail::place_spheres(s.pose_block.entry(link, 0), s.group_shape_spheres.data() + 4 * i, j - i,
                          s.group_shape_balls.data() + 4 * kLanes * i);
    i = j;
  }
}

std::uint8_t CollisionChecker::sweep_self(const Eigen::Ref<const Eigen::VectorXd>& q0,
                                          const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_dq,
                                          double extra, double min_clearance, Scratch& s) const {
  // After sweep_environment: the block's poses, link balls and covering spheres are placed.
  // Lanes stop being tested once some block fails them.
  const MotionLevers& levers = motion_levers();
  const double h = 0.5 / kLanes;
  std::uint8_t clear_all = 0xff;
  s.sweep_block_lanes.assign(self_blocks_.size(), 0);
  for (std::size_t b = 0; b < self_blocks_.size() && clear_all != 0; ++b) {
    const SelfBlock& block = self_blocks_[b];
    const std::uint8_t open = clear_all;  // the lanes this block is tested in
    const double slack =
        h * (levers.self_block_levers.row(static_cast<Eigen::Index>(b)).dot(abs_dq) + 2.0 * extra) +
        min_clearance + kSlack;
    std::uint8_t apart = 0;
    detail::sphere_pairs_apart(s.ball_centers.data(), self_block_balls_.data() + 2 * b, 1, slack,
                               &apart);
    if ((clear_all & ~apart) == 0) {
      s.sweep_block_lanes[b] = open;
      continue;
    }
    const LinkCover cover_a = link_cover(block.link_a);
    const LinkCover cover_b = link_cover(block.link_b);
    if (cover_a.spheres * cover_b.spheres <= detail::kMaxSpherePairs) {
      apart |= detail::spheres_apart(
          place_cover(cover_a.first_shape, cover_a.end_shape, s), cover_a.spheres,
          place_cover(cover_b.first_shape, cover_b.end_shape, s), cover_b.spheres, slack);
    }
    // The table over runs of lanes, from the whole motion down to single lanes: a run whose
    // box of cells is apart proves all its lanes at once.
    for (int width = kLanes; width >= 1; width /= 2) {
      for (int k = 0; k < kLanes; k += width) {
        const auto run = static_cast<std::uint8_t>(((1u << width) - 1u) << k);
        if (!(clear_all & ~apart & run)) continue;
        if (self_block_box_lower(static_cast<int>(b), q0.data(), dq.data(), 2 * k * h,
                                 (2 * (k + width)) * h, min_clearance)) {
          apart |= run;
        }
      }
    }
    clear_all &= apart;
    s.sweep_block_lanes[b] = open & apart;
  }
  return clear_all;
}

}  // namespace hullcheck
