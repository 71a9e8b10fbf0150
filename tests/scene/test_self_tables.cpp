// The self blocks' distance tables (src/scene/self_block_tables.cpp) against brute force: at
// configurations anywhere in a cell (its corners included) the links' smallest signed distance
// over every shape pair, by signed_distance, lies within the cell's bounds; along a motion the
// distance never falls below the bound of the cells the motion crosses. And the verdicts the
// tables decide are those of the exact tests alone (is_valid against is_valid_at, which uses
// no table), on random and near-contact states. Tables of links moved by three values sweep
// one link about a joint (swept_links.cpp): their bounds are checked the same way, at random
// values of the swept joint. The own arm always; the MotionBenchMaker Panda
// and UR5 (decomposed meshes) when ../shared is present.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "collision_checker_internals.hpp"
#include "robot_test_support.hpp"
#include "scene_test_support.hpp"

namespace hullcheck {

// The checker's private tables, for this test only (a friend of CollisionChecker).
struct SelfTableTestAccess {
  static int blocks(const CollisionChecker& c) { return static_cast<int>(c.self_blocks_.size()); }
  static const CollisionChecker::JointGrid* grid(const CollisionChecker& c, int block) {
    return c.set_up_self_tables()[static_cast<std::size_t>(block)];
  }
  static std::pair<int, int> links(const CollisionChecker& c, int block) {
    const auto& b = c.self_blocks_[static_cast<std::size_t>(block)];
    return {c.link_balls_[static_cast<std::size_t>(b.link_a)].link,
            c.link_balls_[static_cast<std::size_t>(b.link_b)].link};
  }
  static bool bounds(const CollisionChecker& c, int block, const Eigen::VectorXd& q, double* lower,
                     double* upper) {
    const auto* table = c.set_up_self_tables()[static_cast<std::size_t>(block)];
    const long cell = table == nullptr ? -1 : table->cell(q.data(), false);
    if (cell >= 0) c.measure_self_table_cell(block, cell, c.scratch());
    return c.self_block_bounds(block, q.data(), lower, upper);
  }
  // The near shapes of q's cell (after bounds() measured it); false when the table keeps none.
  static bool near_shapes(const CollisionChecker& c, int block, const Eigen::VectorXd& q,
                          std::uint64_t* near) {
    double lower = 0.0, upper = 0.0;
    *near = CollisionChecker::kAllShapesNear;
    c.self_block_bounds(block, q.data(), &lower, &upper, near);
    return *near != CollisionChecker::kAllShapesNear;
  }
  // True when block's table sweeps one link (its links are moved by three values).
  static bool swept(const CollisionChecker& c, int block) {
    const auto* table = c.set_up_self_tables()[static_cast<std::size_t>(block)];
    return table != nullptr && table->swept != nullptr;
  }
  // Every cell's stored word (bounds packed; kUnmeasured where not measured), block's table.
  static std::vector<std::uint64_t> cells(const CollisionChecker& c, int block) {
    const auto* table = c.set_up_self_tables()[static_cast<std::size_t>(block)];
    std::vector<std::uint64_t> out;
    for (std::size_t i = 0; table != nullptr && i < table->cell_count; ++i) {
      out.push_back(table->bounds[i].load());
    }
    return out;
  }
  // True once the checker's tables are set up (lever arms built, cells allocated).
  static bool set_up(const CollisionChecker& c) { return !c.self_tables_->per_block.empty(); }
  // Measures every block's cell holding q.
  static void measure_at(const CollisionChecker& c, const Eigen::VectorXd& q) {
    for (int k = 0; k < blocks(c); ++k) {
      const auto* table = c.set_up_self_tables()[static_cast<std::size_t>(k)];
      const long cell = table == nullptr ? -1 : table->cell(q.data(), false);
      if (cell >= 0) c.measure_self_table_cell(k, cell, c.scratch());
    }
  }
  static bool segment(const CollisionChecker& c, int block, const Eigen::VectorXd& q0,
                      const Eigen::VectorXd& dq, double* lower) {
    // Measures the cells the motion crosses (at 200 points of it, finer than the cells of the
    // motions tested), then walks them.
    const auto* table = c.set_up_self_tables()[static_cast<std::size_t>(block)];
    if (table == nullptr) return false;
    for (int i = 0; i <= 200; ++i) {
      const Eigen::VectorXd q = q0 + (i / 200.0) * dq;
      const long cell = table->cell(q.data(), false);
      if (cell >= 0) c.measure_self_table_cell(block, cell, c.scratch());
    }
    return c.self_block_segment_lower(block, q0.data(), dq.data(), 0.0, 1.0, 1 << 20,
                                      -std::numeric_limits<double>::infinity(), lower);
  }
  // The summary levels' verdict on the box of cells the motion spans (after
  // measure_self_tables), and the cell walk's over the cells it crosses.
  static bool box(const CollisionChecker& c, int block, const Eigen::VectorXd& q0,
                  const Eigen::VectorXd& dq, double needed, bool* walk) {
    double lower = 0.0;
    *walk =
        c.self_block_segment_lower(block, q0.data(), dq.data(), 0.0, 1.0, 1 << 20, needed, &lower);
    return c.self_block_box_lower(block, q0.data(), dq.data(), 0.0, 1.0, needed);
  }
  // The walk as far as it goes with cells above `needed` (after segment() measured them).
  static double reach(const CollisionChecker& c, int block, const Eigen::VectorXd& q0,
                      const Eigen::VectorXd& dq, double needed) {
    double lower = 0.0, reached = -1.0;
    c.self_block_segment_lower(block, q0.data(), dq.data(), 0.0, 1.0, 1 << 20, needed, &lower,
                               &reached);
    return reached;
  }
};

namespace {

constexpr double kTol = 1e-9;

// The smallest signed distance between any shape of link a and any shape of link b.
double brute_force(const RobotModel& model, int a, int b, const Eigen::VectorXd& q) {
  std::vector<Eigen::Isometry3d> poses;
  model.compute_link_poses(q, poses);
  double d = std::numeric_limits<double>::infinity();
  for (const CollisionShape& sa : model.link(a).shapes) {
    for (const CollisionShape& sb : model.link(b).shapes) {
      d = std::min(d, signed_distance(sa.shape, poses[static_cast<std::size_t>(a)] * sa.origin,
                                      sb.shape, poses[static_cast<std::size_t>(b)] * sb.origin)
                          .signed_distance);
    }
  }
  return d;
}

struct Counts {
  int blocks_with_tables = 0, swept_tables = 0;
  long points = 0, decided_apart = 0, decided_overlap = 0, segments = 0, partial_walks = 0;
  long near_pairs_checked = 0, near_pairs_marked = 0;  // in cells the bounds leave undecided
};

// Random points of random cells of every table, corners included, and random motions.
void check_bounds(const CollisionChecker& checker, int cells_per_block, Counts* counts) {
  const RobotModel& model = checker.model();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < SelfTableTestAccess::blocks(checker); ++k) {
    const auto* grid = SelfTableTestAccess::grid(checker, k);
    if (grid == nullptr) continue;
    ++counts->blocks_with_tables;
    counts->swept_tables += SelfTableTestAccess::swept(checker, k);
    const auto [a, b] = SelfTableTestAccess::links(checker, k);
    SCOPED_TRACE(model.link(a).name + " / " + model.link(b).name);
    for (int n = 0; n < cells_per_block; ++n) {
      Eigen::VectorXd q = test::random_configuration(model, rng);
      // A point of q's cell: its centre, a corner, or anywhere (the other values as drawn).
      Eigen::VectorXd centre = q;
      grid->center(static_cast<std::size_t>(grid->cell(q.data(), true)), centre);
      for (int d = 0; d < grid->dims; ++d) {
        const int v = grid->variables[d];
        const double w = grid->half_width(d);
        q[v] = n % 3 == 0   ? centre[v]
               : n % 3 == 1 ? centre[v] + (unit(rng) < 0 ? -w : w) * (1.0 - 1e-12)
                            : centre[v] + unit(rng) * w;
      }
      double lower = 0.0, upper = 0.0;
      if (!SelfTableTestAccess::bounds(checker, k, q, &lower, &upper)) continue;
      const double d = brute_force(model, a, b, q);
      ++counts->points;
      counts->decided_apart += lower > kTableSlack;
      counts->decided_overlap += upper < -kTableSlack;
      ASSERT_LE(lower, d + kTol) << "q = " << q.transpose();
      ASSERT_GE(upper, d - kTol) << "q = " << q.transpose();
      // Every shape pair within kTableSlack has both shapes among the cell's near shapes.
      std::uint64_t near = 0;
      if (SelfTableTestAccess::near_shapes(checker, k, q, &near) && !(lower > kTableSlack)) {
        std::vector<Eigen::Isometry3d> poses;
        model.compute_link_poses(q, poses);
        const auto& shapes_a = model.link(a).shapes;
        const auto& shapes_b = model.link(b).shapes;
        for (std::size_t i = 0; i < shapes_a.size(); ++i) {
          for (std::size_t j = 0; j < shapes_b.size(); ++j) {
            ++counts->near_pairs_checked;
            const bool marked = ((near >> i) & (near >> (shapes_a.size() + j)) & 1) != 0;
            counts->near_pairs_marked += marked;
            if (marked) continue;
            const double dij =
                signed_distance(
                    shapes_a[i].shape, poses[static_cast<std::size_t>(a)] * shapes_a[i].origin,
                    shapes_b[j].shape, poses[static_cast<std::size_t>(b)] * shapes_b[j].origin)
                    .signed_distance;
            ASSERT_GT(dij, kTableSlack - kTol)
                << "shapes " << i << ", " << j << " not marked near; q = " << q.transpose();
          }
        }
      }
      // A motion from q, up to a few cells long along each keying value.
      Eigen::VectorXd dq = Eigen::VectorXd::Zero(q.size());
      for (int d2 = 0; d2 < grid->dims; ++d2) {
        dq[grid->variables[d2]] = 8.0 * grid->half_width(d2) * unit(rng);
      }
      double segment_lower = 0.0;
      if (!SelfTableTestAccess::segment(checker, k, q, dq, &segment_lower)) continue;
      ++counts->segments;
      for (int i = 0; i <= 40; ++i) {
        const Eigen::VectorXd qi = q + (i / 40.0) * dq;
        ASSERT_LE(segment_lower, brute_force(model, a, b, qi) + kTol)
            << "q0 = " << q.transpose() << ", dq = " << dq.transpose() << ", t = " << i / 40.0;
      }
      // The walk as far as the cells stay above a bound between the motion's smallest and its
      // start cell's: it stops inside the motion, and the distance is above that bound up to
      // where it stopped.
      if (!(lower > segment_lower)) continue;
      const double needed = 0.5 * (lower + segment_lower);
      const double reached = SelfTableTestAccess::reach(checker, k, q, dq, needed);
      ASSERT_GT(reached, 0.0);
      ASSERT_LT(reached, 1.0);
      ++counts->partial_walks;
      for (int i = 0; i < 40; ++i) {
        const double t = reached * i / 40.0;
        ASSERT_GT(brute_force(model, a, b, q + t * dq), needed - kTol)
            << "q0 = " << q.transpose() << ", dq = " << dq.transpose() << ", t = " << t
            << " < reached " << reached;
      }
    }
  }
}

// is_valid (tables) against is_valid_at (exact tests only) on random states and on both ends
// of a bisection to contact.
void check_verdicts(const CollisionChecker& checker, int states) {
  const RobotModel& model = checker.model();
  std::mt19937_64 rng(9);
  std::vector<Eigen::Isometry3d> poses;
  std::vector<Eigen::VectorXd> qs;
  for (int n = 0; n < states; ++n) qs.push_back(test::random_configuration(model, rng));
  for (int n = 0; n + 1 < states && static_cast<int>(qs.size()) < 2 * states; n += 2) {
    const Eigen::VectorXd a = qs[static_cast<std::size_t>(n)];
    const Eigen::VectorXd b = qs[static_cast<std::size_t>(n + 1)];
    model.compute_link_poses(a, poses);
    const bool va = checker.is_valid_at(poses);
    model.compute_link_poses(b, poses);
    if (va == checker.is_valid_at(poses)) continue;
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      model.compute_link_poses(Eigen::VectorXd(a + mid * (b - a)), poses);
      (checker.is_valid_at(poses) == va ? lo : hi) = mid;
    }
    qs.push_back(a + lo * (b - a));
    qs.push_back(a + hi * (b - a));
  }
  int valid = 0;
  for (const Eigen::VectorXd& q : qs) {
    model.compute_link_poses(q, poses);
    const bool exact = checker.is_valid_at(poses);
    SelfTableTestAccess::measure_at(checker, q);
    ASSERT_EQ(checker.is_valid(q), exact) << "q = " << q.transpose();
    valid += exact;
  }
  EXPECT_GT(valid, 0);
  EXPECT_LT(valid, static_cast<int>(qs.size()));
}

void report(const std::string& id, const Counts& c) {
  std::printf(
      "[ %-8s ] %d blocks with tables (%d sweeping a link): %ld points within their cell's bounds "
      "(%ld proven apart, %ld proven overlapping), %ld motions above their cells' bound, %ld "
      "walks stopped inside; in undecided cells %ld of %ld shape pairs near\n",
      id.c_str(), c.blocks_with_tables, c.swept_tables, c.points, c.decided_apart,
      c.decided_overlap, c.segments, c.partial_walks, c.near_pairs_marked, c.near_pairs_checked);
}

// A tiny ball on a 1 m arm swung about z towards a tiny ball fixed 3.5 mm ahead of it: near
// q = 0 the gap closes at nearly the lever arm's rate (1 m/rad), so a cell's bounds are tight
// at its ends (a reach too small by a tenth shows). Lower bounds are measured up to a cap
// (2 mm): tightness is checked below it.
const char* const kPendulum = R"(<robot name="pendulum">
  <link name="base"><collision><origin xyz="1 0.0035 0"/>
    <geometry><sphere radius="0.001"/></geometry></collision></link>
  <link name="arm"><collision><origin xyz="1 0 0"/>
    <geometry><sphere radius="0.001"/></geometry></collision></link>
  <joint name="swing" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/>
  </joint>
</robot>)";

TEST(SelfTables, PendulumBoundsAreTightAndHold) {
  const auto model = std::make_shared<const RobotModel>(
      RobotModel::from_urdf_string(kPendulum, ".", {}, "pendulum.urdf"));
  const CollisionChecker checker(model, AllowedCollisionMatrix(2));
  ASSERT_EQ(SelfTableTestAccess::blocks(checker), 1);
  const auto* grid = SelfTableTestAccess::grid(checker, 0);
  ASSERT_NE(grid, nullptr);
  const double w = grid->half_width(0);
  const auto gap = [](double q) {
    return std::hypot(std::cos(q) - 1.0, std::sin(q) - 0.0035) - 0.002;
  };
  double tightest_lower = std::numeric_limits<double>::infinity();
  double tightest_upper = std::numeric_limits<double>::infinity();
  for (int n = -200; n <= 200; ++n) {
    const double q = n * 0.37 * w;
    double lower = 0.0, upper = 0.0;
    ASSERT_TRUE(
        SelfTableTestAccess::bounds(checker, 0, Eigen::VectorXd::Constant(1, q), &lower, &upper));
    ASSERT_LE(lower, gap(q) + kTol) << q;
    ASSERT_GE(upper, gap(q) - kTol) << q;
    // The cell's bounds against the gap at its ends (the lever arm is 1.001 m).
    Eigen::VectorXd centre = Eigen::VectorXd::Constant(1, q);
    grid->center(static_cast<std::size_t>(grid->cell(centre.data(), true)), centre);
    if (std::abs(centre[0]) < 0.02 && lower < 0.0015) {
      tightest_lower = std::min(tightest_lower, gap(centre[0] + w) - lower);
    }
    if (std::abs(centre[0]) < 0.02 && std::isfinite(upper)) {
      tightest_upper = std::min(tightest_upper, upper - gap(centre[0] - w));
    }
  }
  EXPECT_LT(tightest_lower, 0.1 * w);
  EXPECT_LT(tightest_upper, 0.1 * w);
  // Motions both ways over a few cells, across the contact at q = 0.0035 or not: the bound
  // never exceeds the gap anywhere on the motion, and is that of the nearest cell.
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> where(-0.02, 0.02);
  for (int n = 0; n < 400; ++n) {
    const double a = where(rng), b = where(rng);
    double lower = 0.0;
    ASSERT_TRUE(SelfTableTestAccess::segment(checker, 0, Eigen::VectorXd::Constant(1, a),
                                             Eigen::VectorXd::Constant(1, b - a), &lower));
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 1000; ++i) nearest = std::min(nearest, gap(a + (b - a) * i / 1000.0));
    ASSERT_LE(lower, nearest + kTol) << a << " -> " << b;
    // At most the bound of the nearest cell (a cell's reach on both sides, the cap above).
    EXPECT_GT(lower, std::min(nearest, 0.002) - 2.2 * w) << a << " -> " << b;
  }
}

// Three joints between a small ball on the base and a ball on the last link's joint axis:
// that link, turned about its own joint, fills its ball again, so the table sweeps it (not the
// base, whose ball the first joint would turn into a ring) and its bounds over the first two
// values are as tight as a two-value table's: within twice a cell's reach of the distance.
const char* const kWrist = R"(<robot name="wrist">
  <link name="base"><collision><origin xyz="0.62 0 0"/>
    <geometry><sphere radius="0.01"/></geometry></collision></link>
  <link name="upper"/>
  <link name="lower"/>
  <link name="hand"><collision><origin xyz="0.05 0 0"/>
    <geometry><sphere radius="0.02"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="upper"/><child link="lower"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/></joint>
  <joint name="j3" type="revolute"><parent link="lower"/><child link="hand"/>
    <origin xyz="0.25 0 0"/><axis xyz="1 0 0"/>
    <limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/></joint>
</robot>)";

TEST(SelfTables, SweptLinkOfRevolutionIsTight) {
  const auto model = std::make_shared<const RobotModel>(
      RobotModel::from_urdf_string(kWrist, ".", {}, "wrist.urdf"));
  const CollisionChecker checker(model, AllowedCollisionMatrix(4));
  ASSERT_EQ(SelfTableTestAccess::blocks(checker), 1);
  ASSERT_TRUE(SelfTableTestAccess::swept(checker, 0));
  const auto* grid = SelfTableTestAccess::grid(checker, 0);
  ASSERT_EQ(grid->dims, 2);
  // The hand ball's centre turns with j1 and j2 only: its gap to the base ball in closed form.
  const auto gap = [](const Eigen::VectorXd& q) {
    const Eigen::Vector2d p = 0.3 * Eigen::Vector2d(std::cos(q[0]), std::sin(q[0])) +
                              0.3 * Eigen::Vector2d(std::cos(q[0] + q[1]), std::sin(q[0] + q[1]));
    return (p - Eigen::Vector2d(0.62, 0.0)).norm() - 0.03;
  };
  // A cell's reach: its half-widths times the lever arms of the hand ball's farthest point
  // about j1 (0.6 + 0.02 m) and j2 (0.3 + 0.02 m).
  const double reach = grid->half_width(0) * 0.62 + grid->half_width(1) * 0.32;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> j1(-0.3, 0.3), j2(-0.8, 0.8), j3(-3.1, 3.1);
  int near = 0;
  for (int n = 0; n < 4000; ++n) {
    const Eigen::Vector3d q(j1(rng), j2(rng), j3(rng));
    double lower = 0.0, upper = 0.0;
    ASSERT_TRUE(SelfTableTestAccess::bounds(checker, 0, q, &lower, &upper));
    const double d = gap(q);
    ASSERT_LE(lower, d + kTol) << q.transpose();
    EXPECT_EQ(upper, std::numeric_limits<double>::infinity());  // a sweep proves no contact
    if (lower < 0.0015) {  // below the cap (2 mm) the bound is measured, not capped
      ++near;
      ASSERT_LT(d - lower, 2.0 * reach + 1e-6) << q.transpose();
    }
  }
  EXPECT_GT(near, 100);
}

TEST(SelfTables, OwnArmBoundsHoldAgainstBruteForce) {
  const test::RobotFile arm = test::own_arm();
  const auto model = test::cached_model(arm.urdf);
  const CollisionChecker checker(model, AllowedCollisionMatrix::from_adjacency(*model));
  Counts counts;
  check_bounds(checker, test::sample_count(300), &counts);
  report("own arm", counts);
  EXPECT_GT(counts.blocks_with_tables, 0);
  EXPECT_GT(counts.swept_tables, 0);  // e.g. the first link against the fourth
  EXPECT_GT(counts.decided_apart, 0);
  EXPECT_GT(counts.segments, 0);
}

TEST(SelfTables, MbmRobotsBoundsHoldAgainstBruteForce) {
  const auto robots = test::mbm_robots();
  if (robots.empty()) GTEST_SKIP() << "MotionBenchMaker robots absent";
  for (const test::MbmRobot& robot : robots) {
    const auto model = test::cached_model(robot.urdf);
    const CollisionChecker checker(
        model, AllowedCollisionMatrix::from_srdf(*model, read_srdf_file(robot.srdf)));
    Counts counts;
    // The UR5's decomposed links make the brute force slow: fewer points per block.
    check_bounds(checker, test::sample_count(robot.id == "ur5" ? 40 : 200), &counts);
    report(robot.id, counts);
    EXPECT_GT(counts.blocks_with_tables, 0);
    // The UR5's forearm against its wrist's last link and the gripper's links: three values
    // (the wrist's joints) move them, one of them swept.
    if (robot.id == "ur5") {
      EXPECT_GE(counts.swept_tables, 10);
      // Its decomposed links: in cells the bounds leave undecided, most pairs are not near.
      EXPECT_GT(counts.near_pairs_checked, 0);
      EXPECT_LT(2 * counts.near_pairs_marked, counts.near_pairs_checked);
    }
    EXPECT_GT(counts.decided_apart, 0);
  }
}

// The tables' summary levels (measure_self_tables) against brute force: a motion whose box of
// cells the summary proves apart is apart at every sample, and the cell walk, over a subset of
// that box's cells, proves it too. Motions from one cell to a few hundred long.
TEST(SelfTables, SummaryBoxesHoldAgainstBruteForce) {
  std::vector<std::pair<std::string, std::string>> robots = {
      {test::own_arm().urdf, test::own_arm().srdf}};
  // Measuring every table of the MotionBenchMaker robots takes most of a sanitizer stage's
  // minute: there, the own arm only (the Release run checks them all).
  if (test::kSanitizerDivisor == 1) {
    for (const test::MbmRobot& robot : test::mbm_robots()) {
      robots.emplace_back(robot.urdf, robot.srdf);
    }
  }
  for (const auto& [urdf, srdf] : robots) {
    SCOPED_TRACE(urdf);
    const auto model = test::cached_model(urdf);
    const CollisionChecker checker(model,
                                   AllowedCollisionMatrix::from_srdf(*model, read_srdf_file(srdf)));
    checker.measure_self_tables();
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const int motions = test::sample_count(urdf.find("ur5") != std::string::npos ? 20 : 100);
    long proven = 0, refused = 0;
    for (int k = 0; k < SelfTableTestAccess::blocks(checker); ++k) {
      const auto* grid = SelfTableTestAccess::grid(checker, k);
      if (grid == nullptr) continue;
      const auto [a, b] = SelfTableTestAccess::links(checker, k);
      for (int n = 0; n < motions; ++n) {
        const Eigen::VectorXd q = test::random_configuration(*model, rng);
        Eigen::VectorXd dq = Eigen::VectorXd::Zero(q.size());
        const double cells = std::pow(2.0, 8.0 * std::abs(unit(rng)));  // 1 to 256 cells long
        for (int d = 0; d < grid->dims; ++d) {
          dq[grid->variables[d]] = 2.0 * cells * grid->half_width(d) * unit(rng);
        }
        const double needed = n % 2 == 0 ? 0.0 : 0.0005;
        bool walk = false;
        if (!SelfTableTestAccess::box(checker, k, q, dq, needed, &walk)) {
          ++refused;
          continue;
        }
        ++proven;
        EXPECT_TRUE(walk) << "the summary proves a box whose crossed cells the walk does not";
        for (int i = 0; i <= 40; ++i) {
          const double t = i / 40.0;
          ASSERT_GT(brute_force(*model, a, b, q + t * dq), needed - kTol)
              << "q0 = " << q.transpose() << ", dq = " << dq.transpose() << ", t = " << t;
        }
      }
    }
    std::printf("[ summary  ] %s: %ld motions proven by their box, %ld not\n",
                model->name().c_str(), proven, refused);
    EXPECT_GT(proven, 0);
  }
}

TEST(SelfTables, VerdictsEqualTheExactTests) {
  const test::RobotFile arm = test::own_arm();
  const auto arm_model = test::cached_model(arm.urdf);
  check_verdicts(CollisionChecker(arm_model, AllowedCollisionMatrix::from_adjacency(*arm_model)),
                 test::sample_count(4000));
  for (const test::MbmRobot& robot : test::mbm_robots()) {
    SCOPED_TRACE(robot.id);
    const auto model = test::cached_model(robot.urdf);
    check_verdicts(CollisionChecker(model, AllowedCollisionMatrix::from_srdf(
                                               *model, read_srdf_file(robot.srdf))),
                   test::sample_count(robot.id == "ur5" ? 2000 : 4000));
  }
}

TEST(SelfTables, NothingBuiltUntilMeasured) {
  // Queries of a model whose tables nobody measured read no table and set none up (a long
  // chain's lever arms are large); measuring sets them up, and a checker made before reads them.
  const test::RobotFile arm = test::own_arm();
  const auto model = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(arm.urdf));
  const AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_adjacency(*model);
  const CollisionChecker before(model, matrix);
  std::mt19937_64 rng(4);
  for (int n = 0; n < 20; ++n) {
    const Eigen::VectorXd q = test::random_configuration(*model, rng);
    before.is_valid(q);
    before.check_motion(q, test::random_configuration(*model, rng));
  }
  EXPECT_FALSE(SelfTableTestAccess::set_up(before));
  const CollisionChecker measuring(model, matrix);
  measuring.measure_self_tables();
  EXPECT_TRUE(SelfTableTestAccess::set_up(measuring));
  before.is_valid(test::random_configuration(*model, rng));
  EXPECT_TRUE(SelfTableTestAccess::set_up(before));
}

TEST(SelfTables, SameTablesOnAnyNumberOfThreads) {
  // Two model objects (their tables are not shared), measured on one and on three threads:
  // every cell of every table holds the same bounds, and none is left unmeasured.
  const test::RobotFile arm = test::own_arm();
  const auto one = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(arm.urdf));
  const auto three = std::make_shared<const RobotModel>(RobotModel::from_urdf_file(arm.urdf));
  const CollisionChecker a(one, AllowedCollisionMatrix::from_adjacency(*one));
  const CollisionChecker b(three, AllowedCollisionMatrix::from_adjacency(*three));
  EXPECT_THROW(a.measure_self_tables(-1), InputError);
  a.measure_self_tables(1);
  b.measure_self_tables(3);
  std::size_t compared = 0;
  for (int k = 0; k < SelfTableTestAccess::blocks(a); ++k) {
    const std::vector<std::uint64_t> ca = SelfTableTestAccess::cells(a, k);
    ASSERT_EQ(ca, SelfTableTestAccess::cells(b, k)) << "block " << k;
    for (const std::uint64_t word : ca) ASSERT_NE(word, ~std::uint64_t{0});
    compared += ca.size();
  }
  EXPECT_GT(compared, 100000u);
}

TEST(SelfTables, SharedByCheckersOfOneModel) {
  // A second checker of the same model (another scene) reads the cells the first measured:
  // same bounds, and no table for a model whose padding changed (its shapes are others).
  const test::RobotFile arm = test::own_arm();
  auto model = std::make_shared<RobotModel>(RobotModel::from_urdf_file(arm.urdf));
  const AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_adjacency(*model);
  const CollisionChecker first(model, matrix);
  const CollisionChecker second(model, matrix);
  std::mt19937_64 rng(3);
  int compared = 0;
  for (int n = 0; n < 50; ++n) {
    const Eigen::VectorXd q = test::random_configuration(*model, rng);
    for (int k = 0; k < SelfTableTestAccess::blocks(first); ++k) {
      double l1 = 0, u1 = 0, l2 = 0, u2 = 0;
      if (!SelfTableTestAccess::bounds(first, k, q, &l1, &u1)) continue;
      ASSERT_TRUE(SelfTableTestAccess::bounds(second, k, q, &l2, &u2));
      EXPECT_EQ(l1, l2);
      EXPECT_EQ(u1, u2);
      ++compared;
    }
  }
  EXPECT_GT(compared, 0);
  EXPECT_EQ(SelfTableTestAccess::grid(first, 0), SelfTableTestAccess::grid(second, 0));
  model->set_default_padding(0.02);
  const CollisionChecker padded(model, matrix);
  for (int k = 0; k < SelfTableTestAccess::blocks(padded); ++k) {
    if (SelfTableTestAccess::grid(padded, k) != nullptr) {
      EXPECT_NE(SelfTableTestAccess::grid(padded, k), SelfTableTestAccess::grid(first, k));
    }
  }
}

}  // namespace
}  // namespace hullcheck
