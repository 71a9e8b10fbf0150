// The lever arms behind every motion bound (src/scene/motion_bounds.cpp), shape by shape and
// pair by pair, against forward kinematics: along random straight joint-space motions
//   - every point of a robot shape travels (polyline through dense samples, at most the path
//     length) no more than the shape's levers dotted with |q1 - q0|;
//   - for every self pair, the two shapes' points travel, in the frame of the links' deepest
//     common ancestor (where their distance is decided), no more than the pair's levers dotted
//     with |q1 - q0| between them.
// A bound that is too tight (an axis distance measured in the wrong frame, a joint forgotten)
// fails; the ratio printed shows how much is left. The own arm, hand-made chains with fixed,
// prismatic and offset joints, and every shared robot when ../shared is present.
// The speed bounds check_motion takes from the configuration at an interval's middle
// (chain_speed.hpp), the same way: within [m - h, m + h] every point of a shape, of a link ball's
// link and of a shape group stays within |t - m| (speed + h accel / 2) of where it is at q(m),
// in the world and, for a pair of links, in their common ancestor's frame; along a direction
// fixed in that frame, within |t - m| (along(n) + h accel / 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "chain_speed.hpp"
#include "collision_checker_internals.hpp"
#include "robot_test_support.hpp"
#include "scene_test_support.hpp"

namespace hullcheck {

// The checker's lever arms, for this test only (a friend of CollisionChecker).
struct MotionLeverTestAccess {
  static int shapes(const CollisionChecker& c) { return static_cast<int>(c.shapes_.size()); }
  static std::pair<int, int> link_and_shape(const CollisionChecker& c, int shape) {
    const auto& rs = c.shapes_[static_cast<std::size_t>(shape)];
    return {rs.link, rs.shape};
  }
  static int self_pairs(const CollisionChecker& c) {
    return static_cast<int>(c.self_pairs_.size());
  }
  static std::pair<int, int> pair_shapes(const CollisionChecker& c, int pair) {
    const auto& p = c.self_pairs_[static_cast<std::size_t>(pair)];
    return {p.a, p.b};
  }
  static double shape_rate(const CollisionChecker& c, int shape, const Eigen::VectorXd& abs_dq) {
    return c.motion_levers().shape_levers.row(shape).dot(abs_dq);
  }
  static double pair_rate(const CollisionChecker& c, int pair, const Eigen::VectorXd& abs_dq) {
    return c.motion_levers().self_pair_levers.row(pair).dot(abs_dq);
  }
  // check_motion's speed bounds at link poses `poses`, relative to the frame of link `frame`
  // (-1: the world): of a robot shape (its ball), of link ball `ball`'s link, of shape group
  // `group` (its ball centred at `centre`, of `radius`; single-link groups only).
  static std::size_t from(const CollisionChecker& c, int frame) {
    return frame < 0 ? 0 : c.motion_levers().link_chains[static_cast<std::size_t>(frame)].size();
  }
  static ChainSpeed shape_speed(const CollisionChecker& c, int shape, int frame,
                                const std::vector<Eigen::Isometry3d>& poses,
                                const Eigen::VectorXd& dq) {
    const auto& rs = c.shapes_[static_cast<std::size_t>(shape)];
    const auto& levers = c.motion_levers();
    return chain_speed(c.model(), poses, levers.link_chains[static_cast<std::size_t>(rs.link)],
                       from(c, frame), dq, levers.joint_arms->col(shape).data(),
                       poses[static_cast<std::size_t>(rs.link)] * rs.center, rs.radius);
  }
  static int link_balls(const CollisionChecker& c) {
    return static_cast<int>(c.link_balls_.size());
  }
  static int ball_link(const CollisionChecker& c, int ball) {
    return c.link_balls_[static_cast<std::size_t>(ball)].link;
  }
  static ChainSpeed ball_speed(const CollisionChecker& c, int ball, int frame,
                               const std::vector<Eigen::Isometry3d>& poses,
                               const Eigen::VectorXd& dq) {
    const auto& b = c.link_balls_[static_cast<std::size_t>(ball)];
    const auto& levers = c.motion_levers();
    return chain_speed(c.model(), poses, levers.link_chains[static_cast<std::size_t>(b.link)],
                       from(c, frame), dq, levers.link_ball_arms.col(ball).data(),
                       poses[static_cast<std::size_t>(b.link)] * b.center, b.radius);
  }
  static int groups(const CollisionChecker& c) { return static_cast<int>(c.groups_.size()); }
  // Model link `link`'s robot shapes [first, second).
  static std::pair<int, int> shape_range(const CollisionChecker& c, int link) {
    return {c.shape_begin_[static_cast<std::size_t>(link)],
            c.shape_begin_[static_cast<std::size_t>(link) + 1]};
  }
  // The group's shapes [begin, end) and the link carrying them all (-1: several).
  static std::pair<int, int> group_shapes(const CollisionChecker& c, int group) {
    return {c.groups_[static_cast<std::size_t>(group)].begin,
            c.groups_[static_cast<std::size_t>(group)].end};
  }
  static int group_link(const CollisionChecker& c, int group) {
    return c.motion_levers().group_link[static_cast<std::size_t>(group)];
  }
  static ChainSpeed group_speed(const CollisionChecker& c, int group,
                                const std::vector<Eigen::Isometry3d>& poses,
                                const Eigen::VectorXd& dq, const Eigen::Vector3d& centre,
                                double radius) {
    const auto& levers = c.motion_levers();
    const int link = levers.group_link[static_cast<std::size_t>(group)];
    return chain_speed(c.model(), poses, levers.link_chains[static_cast<std::size_t>(link)], 0, dq,
                       levers.group_arms.col(group).data(), centre, radius);
  }
  // A ball holding every ball of shapes [begin, end) at `poses`.
  static std::pair<Eigen::Vector3d, double> enclosing_ball(
      const CollisionChecker& c, int begin, int end, const std::vector<Eigen::Isometry3d>& poses) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    const auto ball_centre = [&](int i) {
      const auto& rs = c.shapes_[static_cast<std::size_t>(i)];
      return Eigen::Vector3d(poses[static_cast<std::size_t>(rs.link)] * rs.center);
    };
    for (int i = begin; i < end; ++i) centre += ball_centre(i);
    centre /= static_cast<double>(end - begin);
    double radius = 0.0;
    for (int i = begin; i < end; ++i) {
      radius = std::max(
          radius, (ball_centre(i) - centre).norm() + c.shapes_[static_cast<std::size_t>(i)].radius);
    }
    return {centre, radius};
  }
};

namespace {

// Points of a collision shape (its link's frame) whose travel bounds every point's: a rigid
// motion's point velocity is affine in the point, so a path length is convex in it and largest
// at an extreme point (round shapes: points on their rims and poles, a close approximation).
std::vector<Eigen::Vector3d> extreme_points(const CollisionShape& cs) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& p : test::shape_points(cs.shape)) out.push_back(cs.origin * p);
  return out;
}

int depth(const RobotModel& model, int link) {
  int d = 0;
  for (; model.link(link).parent_joint >= 0; ++d) {
    link = model.joint(model.link(link).parent_joint).parent_link;
  }
  return d;
}

int parent(const RobotModel& model, int link) {
  return model.joint(model.link(link).parent_joint).parent_link;
}

int common_ancestor(const RobotModel& model, int a, int b) {
  int da = depth(model, a), db = depth(model, b);
  for (; da > db; --da) a = parent(model, a);
  for (; db > da; --db) b = parent(model, b);
  while (a != b) a = parent(model, a), b = parent(model, b);
  return a;
}

struct LeverStats {
  int motions = 0;
  int shape_checks = 0;
  int pair_checks = 0;
  double worst_shape_ratio = 0.0;  // largest travel / bound seen (<= 1 when the bounds hold)
  double worst_pair_ratio = 0.0;
};

// Random motions q0 -> q1 (`sample` draws each end), `steps` forward kinematics samples each.
template <typename Sample>
void check_levers(const CollisionChecker& checker, int motions, int steps, Sample sample,
                  LeverStats* stats) {
  using Access = MotionLeverTestAccess;
  const RobotModel& model = checker.model();
  std::vector<Eigen::Isometry3d> poses;
  for (int m = 0; m < motions; ++m) {
    const Eigen::VectorXd q0 = sample(), q1 = sample();
    const Eigen::VectorXd abs_dq = (q1 - q0).cwiseAbs();
    std::vector<std::vector<Eigen::Isometry3d>> trajectory;  // per step, per link
    for (int k = 0; k <= steps; ++k) {
      model.compute_link_poses(q0 + (k / static_cast<double>(steps)) * (q1 - q0), poses);
      trajectory.push_back(poses);
    }
    // Largest path length of a shape's points, in the frame of link `frame` (-1: the world).
    std::map<std::pair<int, int>, double> memo;
    const auto travel = [&](int shape, int frame) {
      const auto key = std::make_pair(shape, frame);
      if (const auto it = memo.find(key); it != memo.end()) return it->second;
      const auto [link, index] = Access::link_and_shape(checker, shape);
      const std::vector<Eigen::Vector3d> points =
          extreme_points(model.link(link).shapes[static_cast<std::size_t>(index)]);
      double worst = 0.0;
      for (const Eigen::Vector3d& p : points) {
        double length = 0.0;
        Eigen::Vector3d prev;
        for (int k = 0; k <= steps; ++k) {
          const auto& at = trajectory[static_cast<std::size_t>(k)];
          const Eigen::Isometry3d to_frame =
              frame < 0 ? Eigen::Isometry3d::Identity()
                        : Eigen::Isometry3d(at[static_cast<std::size_t>(frame)].inverse());
          const Eigen::Vector3d x = to_frame * at[static_cast<std::size_t>(link)] * p;
          if (k > 0) length += (x - prev).norm();
          prev = x;
        }
        worst = std::max(worst, length);
      }
      memo[key] = worst;
      return worst;
    };
    for (int sh = 0; sh < Access::shapes(checker); ++sh) {
      const double bound = Access::shape_rate(checker, sh, abs_dq);
      const double moved = travel(sh, -1);
      const auto [link, index] = Access::link_and_shape(checker, sh);
      EXPECT_LE(moved, bound * (1.0 + 1e-9) + 1e-12)
          << model.link(link).name << " shape " << index << "\nq0 = " << q0.transpose()
          << "\nq1 = " << q1.transpose();
      if (bound > 1e-9)
        stats->worst_shape_ratio = std::max(stats->worst_shape_ratio, moved / bound);
      ++stats->shape_checks;
    }
    // Decomposed robots have tens of thousands of piece pairs: every k-th one (all on the
    // smaller robots).
    const int stride = std::max(1, Access::self_pairs(checker) / 4000);
    for (int p = 0; p < Access::self_pairs(checker); p += stride) {
      const auto [a, b] = Access::pair_shapes(checker, p);
      const int link_a = Access::link_and_shape(checker, a).first;
      const int link_b = Access::link_and_shape(checker, b).first;
      const int ancestor = common_ancestor(model, link_a, link_b);
      const double moved = travel(a, ancestor) + travel(b, ancestor);
      const double bound = Access::pair_rate(checker, p, abs_dq);
      EXPECT_LE(moved, bound * (1.0 + 1e-9) + 1e-12)
          << model.link(link_a).name << " / " << model.link(link_b).name
          << "\nq0 = " << q0.transpose() << "\nq1 = " << q1.transpose();
      if (bound > 1e-9) stats->worst_pair_ratio = std::max(stats->worst_pair_ratio, moved / bound);
      ++stats->pair_checks;
    }
    ++stats->motions;
  }
}

struct SpeedStats {
  int intervals = 0;
  long checks = 0;           // (bound, point, sample) triples
  int unusable = 0;          // bounds with a moving prismatic joint (the levers' rate used instead)
  double worst = 0.0;        // largest displacement / bound seen (<= 1 when the bounds hold)
  double worst_along = 0.0;  // the same along a direction
};

// Random motions q0 -> q1 (`sample` draws each end) and an interval [m - h, m + h] of each,
// `steps` forward kinematics samples in it: chain_speed's bounds for every shape (in the world
// and in the frame of every link above it), every link ball and every single-link shape group,
// against the displacement of their shapes' extreme points from q(m).
template <typename Sample>
void check_speeds(const CollisionChecker& checker, int motions, int steps, std::mt19937_64& rng,
                  Sample sample, SpeedStats* stats) {
  using Access = MotionLeverTestAccess;
  const RobotModel& model = checker.model();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Isometry3d> at_m;
  std::vector<std::vector<Eigen::Isometry3d>> samples(static_cast<std::size_t>(steps) + 1);
  std::vector<double> ts(static_cast<std::size_t>(steps) + 1);
  for (int motion = 0; motion < motions; ++motion) {
    const auto [q0, q1] = sample();
    const Eigen::VectorXd dq = q1 - q0;
    const double m = unit(rng);
    const double h = std::exp(std::log(1e-3) + unit(rng) * (std::log(0.5) - std::log(1e-3)));
    model.compute_link_poses(q0 + m * dq, at_m);
    for (int k = 0; k <= steps; ++k) {
      ts[static_cast<std::size_t>(k)] = m + h * (2.0 * k / steps - 1.0);
      model.compute_link_poses(q0 + ts[static_cast<std::size_t>(k)] * dq,
                               samples[static_cast<std::size_t>(k)]);
    }
    // The bound against shapes [begin, end)'s points, in link `frame`'s frame (-1: the world).
    const auto check = [&](const ChainSpeed& bound, int begin, int end, int frame,
                           const char* what) {
      if (!bound.usable) {
        ++stats->unusable;
        return;
      }
      const double rate = bound.speed + 0.5 * h * bound.accel;
      // A random unit direction, fixed in the frame: at q(m) it is `along_world`.
      Eigen::Vector3d along_world =
          Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) - Eigen::Vector3d::Constant(0.5);
      along_world.normalize();
      const Eigen::Vector3d along_frame =
          frame < 0 ? along_world
                    : Eigen::Vector3d(at_m[static_cast<std::size_t>(frame)].linear().transpose() *
                                      along_world);
      const double along_rate = bound.along(along_world) + 0.5 * h * bound.accel;
      const auto in_frame = [&](const std::vector<Eigen::Isometry3d>& poses, int link,
                                const Eigen::Vector3d& p) {
        const Eigen::Vector3d world = poses[static_cast<std::size_t>(link)] * p;
        return frame < 0
                   ? world
                   : Eigen::Vector3d(poses[static_cast<std::size_t>(frame)].inverse() * world);
      };
      // A decomposed link's pieces: about 40 of them.
      for (int sh = begin; sh < end; sh += std::max(1, (end - begin) / 40)) {
        const auto [link, index] = Access::link_and_shape(checker, sh);
        const std::vector<Eigen::Vector3d> points =
            extreme_points(model.link(link).shapes[static_cast<std::size_t>(index)]);
        // Meshes' hulls: about 24 of their vertices.
        for (std::size_t i = 0; i < points.size();
             i += std::max<std::size_t>(1, points.size() / 24)) {
          const Eigen::Vector3d& p = points[i];
          const Eigen::Vector3d x_m = in_frame(at_m, link, p);
          for (int k = 0; k <= steps; ++k) {
            const double dt = std::abs(ts[static_cast<std::size_t>(k)] - m);
            const double moved =
                (in_frame(samples[static_cast<std::size_t>(k)], link, p) - x_m).norm();
            const double allowed = dt * rate;
            ASSERT_LE(moved, allowed * (1.0 + 1e-9) + 1e-12)
                << what << " " << model.link(link).name << " shape " << index << " frame " << frame
                << " m " << m << " h " << h << " t " << ts[static_cast<std::size_t>(k)]
                << "\nq0 = " << q0.transpose() << "\nq1 = " << q1.transpose();
            if (allowed > 1e-9) stats->worst = std::max(stats->worst, moved / allowed);
            const double moved_along = std::abs(
                along_frame.dot(in_frame(samples[static_cast<std::size_t>(k)], link, p) - x_m));
            ASSERT_LE(moved_along, dt * along_rate * (1.0 + 1e-9) + 1e-12)
                << what << " along " << along_world.transpose() << " " << model.link(link).name
                << " shape " << index << " frame " << frame << " m " << m << " h " << h;
            if (dt * along_rate > 1e-9) {
              stats->worst_along = std::max(stats->worst_along, moved_along / (dt * along_rate));
            }
            ++stats->checks;
          }
        }
      }
    };
    // Decomposed robots have thousands of pieces: every k-th one (all on the smaller robots).
    const int stride = std::max(1, Access::shapes(checker) / 150);
    for (int sh = 0; sh < Access::shapes(checker); sh += stride) {
      const int link = Access::link_and_shape(checker, sh).first;
      for (int frame = link; frame >= 0;) {  // the link itself: nothing moves relative to it
        const int up = model.link(frame).parent_joint < 0 ? -1 : parent(model, frame);
        check(Access::shape_speed(checker, sh, up, at_m, dq), sh, sh + 1, up, "shape");
        frame = up;
      }
    }
    for (int b = 0; b < Access::link_balls(checker); ++b) {
      const int link = Access::ball_link(checker, b);
      const auto [first, last] = std::make_pair(Access::shape_range(checker, link).first,
                                                Access::shape_range(checker, link).second);
      for (int frame = link; frame >= 0;) {
        const int up = model.link(frame).parent_joint < 0 ? -1 : parent(model, frame);
        check(Access::ball_speed(checker, b, up, at_m, dq), first, last, up, "link ball");
        frame = up;
      }
    }
    for (int g = 0; g < Access::groups(checker); ++g) {
      if (Access::group_link(checker, g) < 0) continue;
      const auto [first, last] = Access::group_shapes(checker, g);
      const auto [centre, radius] = Access::enclosing_ball(checker, first, last, at_m);
      check(Access::group_speed(checker, g, at_m, dq, centre, radius), first, last, -1, "group");
    }
    ++stats->intervals;
  }
}

void report(const std::string& id, const SpeedStats& s) {
  std::printf(
      "[ speeds   ] %s: %d intervals, %ld checks, %d bounds with a prismatic joint moving; "
      "largest displacement / bound %.3f, along a direction %.3f\n",
      id.c_str(), s.intervals, s.checks, s.unusable, s.worst, s.worst_along);
}

void report(const std::string& id, const LeverStats& s) {
  std::printf(
      "[ levers   ] %s: %d motions, %d shape and %d pair checks; largest travel / bound: shapes "
      "%.3f, pairs %.3f\n",
      id.c_str(), s.motions, s.shape_checks, s.pair_checks, s.worst_shape_ratio,
      s.worst_pair_ratio);
}

// Every link pair checked (no SRDF needed).
AllowedCollisionMatrix nothing_allowed(const RobotModel& model) {
  return AllowedCollisionMatrix(static_cast<int>(model.links().size()));
}

// Chains where the exact parts of the bounds matter: offset and tilted axes, a fixed joint
// between two revolute ones, a prismatic joint in the middle, a mimic joint turning the other
// way, and boxes, spheres and cylinders off their links' origins.
std::shared_ptr<const RobotModel> hand_made_chain() {
  return std::make_shared<const RobotModel>(
      RobotModel::from_urdf_string(R"(<robot name="hand_made_chain">
  <link name="base"/>
  <link name="upper"><collision><origin xyz="0.3 0.05 0.1" rpy="0.3 0.2 0.1"/>
    <geometry><box size="0.4 0.05 0.08"/></geometry></collision></link>
  <link name="bracket"><collision><origin xyz="0.1 0 -0.05"/>
    <geometry><sphere radius="0.04"/></geometry></collision></link>
  <link name="fore"><collision><origin xyz="0 0.2 0" rpy="1.2 0 0"/>
    <geometry><cylinder radius="0.03" length="0.3"/></geometry></collision></link>
  <link name="slider"><collision><origin xyz="0.05 0 0.02"/>
    <geometry><cylinder radius="0.02" length="0.1"/></geometry></collision></link>
  <link name="tip"><collision><origin xyz="0 0 0.1" rpy="0 0.7 0"/>
    <geometry><box size="0.05 0.1 0.2"/></geometry></collision>
    <collision><origin xyz="0.1 0 0.25"/><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><origin xyz="0 0 0.4"/><axis xyz="0 0.6 0.8"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="mount" type="fixed">
    <parent link="upper"/><child link="bracket"/><origin xyz="0.5 0.1 0" rpy="0 0.5 0"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="bracket"/><child link="fore"/><origin xyz="0.1 0 0.05" rpy="0.4 0 0"/>
    <axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="extend" type="prismatic">
    <parent link="fore"/><child link="slider"/><origin xyz="0 0.35 0"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.2" effort="1" velocity="1"/>
  </joint>
  <joint name="wrist" type="continuous">
    <parent link="slider"/><child link="tip"/><origin xyz="0.02 0.1 0" rpy="0 0 0.3"/>
    <axis xyz="0 0 1"/>
  </joint>
  <joint name="wrist_mimic" type="revolute">
    <parent link="base"/><child link="twin"/><origin xyz="0.2 0 0.1"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
    <mimic joint="shoulder" multiplier="-1.5" offset="0.2"/>
  </joint>
  <link name="twin"><collision><origin xyz="0 0 0.2"/>
    <geometry><box size="0.05 0.05 0.3"/></geometry></collision></link>
</robot>)",
                                   ".", {}, "hand_made_chain.urdf"));
}

TEST(MotionLevers, BoundEveryShapeAndPairOnTheRobots) {
  const int motions = test::sample_count(16);
  for (const test::RobotFile& robot : test::all_robots()) {
    SCOPED_TRACE(robot.urdf);
    const auto model = test::cached_model(robot.urdf);
    // Under the sanitizers the shared robots' forward kinematics along dense motions take most
    // of the stage's time: there, the own arm only (the Release run checks them all).
    if (test::kSanitizerDivisor > 1 && robot.id != test::own_arm().id) continue;
    const AllowedCollisionMatrix matrix =
        robot.srdf.empty() ? nothing_allowed(*model)
                           : AllowedCollisionMatrix::from_srdf(*model, read_srdf_file(robot.srdf));
    const CollisionChecker checker(model, matrix, PlanningScene{});
    std::mt19937_64 rng(41);
    LeverStats stats;
    check_levers(
        checker, motions, 64, [&] { return test::random_configuration(*model, rng); }, &stats);
    report(robot.id, stats);
    EXPECT_GT(stats.worst_shape_ratio, 0.2);  // the check sees real motion
  }
}

TEST(MotionLevers, BoundEveryShapeOnHandMadeChains) {
  const auto model = hand_made_chain();
  const CollisionChecker checker(model, nothing_allowed(*model), PlanningScene{});
  std::mt19937_64 rng(5);
  LeverStats stats;
  check_levers(
      checker, test::sample_count(200), 128,
      [&] { return test::random_configuration(*model, rng); }, &stats);
  report("hand_made_chain", stats);
  EXPECT_GT(stats.worst_shape_ratio, 0.5);
  EXPECT_GT(stats.pair_checks, 0);
}

TEST(ChainSpeed, BoundsHoldOnTheRobots) {
  const int motions = test::sample_count(10);
  for (const test::RobotFile& robot : test::all_robots()) {
    SCOPED_TRACE(robot.urdf);
    const auto model = test::cached_model(robot.urdf);
    if (test::kSanitizerDivisor > 1 && robot.id != test::own_arm().id) continue;
    const CollisionChecker checker(model, nothing_allowed(*model), PlanningScene{});
    std::mt19937_64 rng(43);
    SpeedStats stats;
    check_speeds(
        checker, motions, 16, rng,
        [&] {
          return std::make_pair(test::random_configuration(*model, rng),
                                test::random_configuration(*model, rng));
        },
        &stats);
    report(robot.id, stats);
    EXPECT_GT(stats.worst, 0.3);  // the check sees real motion
    EXPECT_GT(stats.worst_along, 0.3);
  }
}

// The hand-made chain (the bound gives way to the levers' rate while its prismatic joint moves).
TEST(ChainSpeed, BoundsHoldOnAHandMadeChain) {
  const auto model = hand_made_chain();
  const CollisionChecker checker(model, nothing_allowed(*model), PlanningScene{});
  const int slide = model->joint(model->joint_index("extend")).variable;
  std::mt19937_64 rng(9);
  SpeedStats stats;
  int motion = 0;
  check_speeds(
      checker, test::sample_count(300), 32, rng,
      [&] {
        const Eigen::VectorXd q0 = test::random_configuration(*model, rng);
        Eigen::VectorXd q1 = test::random_configuration(*model, rng);
        if (motion++ % 2 == 0) q1[slide] = q0[slide];  // half of them without the slide moving
        return std::make_pair(q0, q1);
      },
      &stats);
  report("hand_made_chain", stats);
  EXPECT_GT(stats.worst, 0.5);
  EXPECT_GT(stats.worst_along, 0.5);
  EXPECT_GT(stats.unusable, 0);  // the slide's motions fall back
  EXPECT_GT(stats.checks, 0);
}

}  // namespace
}  // namespace hullcheck
