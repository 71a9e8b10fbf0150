// CollisionChecker::check_motion against independent answers:
//  - analytic first contacts of a ball swung on a lever into a plate (both sides), and a thin
//    plate that evenly spaced samples step over;
//  - FCL 0.7 (oracles/fcl_checker) densely along random motions of the MotionBenchMaker Panda
//    and UR5 problems: accepted motions free at every sample, the reported contact a state
//    FCL finds within min_clearance + resolution of touching, the part before it free;
//  - a two-piece link crossing a box (analytic: which motions cross it);
//  - bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fcl_checker.hpp"
#include "scene_test_support.hpp"

namespace hullcheck {
namespace {

// A ball of radius r at distance R from a vertical revolute axis (z), swung from angle 0 into a
// plate of thickness 2e whose lower face is the plane y = y_plate - e.
struct SweptBall {
  double R = 0.5, r = 0.05, y_plate = 0.3, e = 0.0005;
  std::shared_ptr<const RobotModel> model;
  std::unique_ptr<CollisionChecker> checker;

  SweptBall(double ball_radius, double plate_y) : r(ball_radius), y_plate(plate_y) {
    const std::string urdf =
        R"(<robot name="swing"><link name="base"/>
  <link name="arm"><collision><origin xyz=")" +
        std::to_string(R) + R"( 0 0"/><geometry><sphere radius=")" + std::to_string(r) +
        R"("/></geometry></collision></link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>)";
    model = std::make_shared<const RobotModel>(
        RobotModel::from_urdf_string(urdf, ".", {}, "swing.urdf"));
    PlanningScene scene;
    // x in [-0.5, 1.5]: the ball meets a face, not an edge.
    scene.obstacles.push_back(Obstacle{"plate", "plate", Shape(Box(2.0, 2.0 * e, 1.0)),
                                       Eigen::Isometry3d(Eigen::Translation3d(0.5, y_plate, 0.0)),
                                       "box"});
    checker = std::make_unique<CollisionChecker>(
        model, AllowedCollisionMatrix(static_cast<int>(model->links().size())), scene);
  }
  Eigen::VectorXd q(double angle) const { return Eigen::VectorXd::Constant(1, angle); }
  // The angles at which the ball first meets the plate's lower face swinging up from 0, and
  // its upper face swinging down from above.
  double rising_contact() const { return std::asin((y_plate - e - r) / R); }
  double falling_contact() const { return std::asin((y_plate + e + r) / R); }
  double rate() const { return R + r; }  // the lever arm: the ball's farthest point
};

TEST(MotionCheck, SwingStopsAtTheAnalyticContact) {
  const SweptBall swing(0.05, 0.3);
  const MotionCheckOptions options;
  const double end = 1.2;
  const MotionCheckResult up = swing.checker->check_motion(swing.q(0), swing.q(end), options);
  ASSERT_EQ(up.verdict, MotionVerdict::kContact);
  const double t_up = swing.rising_contact() / end;
  // last_free lies before the true contact; the contact reported within `resolution` of
  // travel after last_free (the lever-arm bound: rate x angle), and within the ball's travel to
  // the plate of min_clearance + resolution from the true contact.
  const double travel_per_t = end * swing.rate();
  const double band = (options.min_clearance + options.resolution) /
                      (swing.R * std::cos(swing.rising_contact()) * end);
  EXPECT_LE(up.last_free, t_up + 1e-12);
  EXPECT_LE(up.last_free, up.contact);
  EXPECT_LE((up.contact - up.last_free) * travel_per_t, options.resolution + 1e-12);
  EXPECT_NEAR(up.contact, t_up, band);
  std::printf("[ swing    ] up: contact at t = %.9f (analytic %.9f), last free %.9f, %d states\n",
              up.contact, t_up, up.last_free, up.states);

  // Swinging down from beyond the plate meets its upper face.
  const MotionCheckResult down = swing.checker->check_motion(swing.q(end), swing.q(0), options);
  ASSERT_EQ(down.verdict, MotionVerdict::kContact);
  const double t_down = (end - swing.falling_contact()) / end;
  EXPECT_LE(down.last_free, t_down + 1e-12);
  EXPECT_LE((down.contact - down.last_free) * travel_per_t, options.resolution + 1e-12);
  EXPECT_NEAR(down.contact, t_down,
              (options.min_clearance + options.resolution) /
                  (swing.R * std::cos(swing.falling_contact()) * end));

  // Stopping 1 cm of ball travel short of the plate: free.
  const double stop = swing.rising_contact() - 0.01 / swing.R;
  const MotionCheckResult short_of = swing.checker->check_motion(swing.q(0), swing.q(stop));
  EXPECT_EQ(short_of.verdict, MotionVerdict::kFree);
  EXPECT_EQ(short_of.last_free, 1.0);
  // Stopping 1e-5 m short: within resolution of the plate, so kFree or kNearContact, never
  // kContact; with a finer resolution it is proven free.
  const double close = swing.rising_contact() - 1e-5 / swing.R;
  const MotionCheckResult near = swing.checker->check_motion(swing.q(0), swing.q(close));
  EXPECT_NE(near.verdict, MotionVerdict::kContact);
  MotionCheckOptions fine;
  fine.resolution = 1e-7;
  EXPECT_TRUE(swing.checker->check_motion(swing.q(0), swing.q(close), fine).free());
}

TEST(MotionCheck, ThinPlateBetweenSamplesIsRejected) {
  // A 2 mm ball and a 1 mm plate, swept over 1.2 rad: 61 evenly spaced states (0.02 rad, 10 mm
  // of travel apart) all miss the plate, which the ball crosses between two of them.
  const SweptBall swing(0.002, 0.5 * std::sin(0.65));
  const double end = 1.2;
  for (int k = 0; k <= 60; ++k) {
    ASSERT_TRUE(swing.checker->is_valid(swing.q(end * k / 60.0))) << "sample " << k;
  }
  const MotionCheckResult r = swing.checker->check_motion(swing.q(0), swing.q(end));
  EXPECT_EQ(r.verdict, MotionVerdict::kContact);
  EXPECT_LE(r.last_free * end, swing.rising_contact());
  EXPECT_NEAR(r.contact * end, swing.rising_contact(),
              2e-4 / (swing.R * std::cos(swing.rising_contact())));
  // The yes/no mode (a block of sampled intervals first, then the search on the ones left)
  // rejects it too, with a contact on the plate; so in both directions, and a swing stopping
  // 1 mm of ball travel short of it is free.
  MotionCheckOptions yes_no;
  yes_no.locate_contact = false;
  for (const double from : {0.0, end}) {
    const MotionCheckResult first =
        swing.checker->check_motion(swing.q(from), swing.q(end - from), yes_no);
    EXPECT_EQ(first.verdict, MotionVerdict::kContact) << "from " << from;
    const double angle = from + first.contact * (end - 2.0 * from);
    EXPECT_NEAR(swing.R * std::sin(angle), swing.y_plate,
                swing.e + swing.r + yes_no.min_clearance + 1e-9)
        << "from " << from;
  }
  const double short_of = swing.rising_contact() - 0.001 / swing.R;
  EXPECT_TRUE(swing.checker->check_motion(swing.q(0), swing.q(short_of), yes_no).free());
  // Without the end state first: the same verdicts.
  yes_no.end_first = false;
  EXPECT_EQ(swing.checker->check_motion(swing.q(0), swing.q(end), yes_no).verdict,
            MotionVerdict::kContact);
  EXPECT_TRUE(swing.checker->check_motion(swing.q(0), swing.q(short_of), yes_no).free());
}

TEST(MotionCheck, BadInputIsAnError) {
  const SweptBall swing(0.05, 0.3);
  Eigen::VectorXd nan = swing.q(0);
  nan[0] = std::nan("");
  EXPECT_THROW(swing.checker->check_motion(nan, swing.q(1)), InputError);
  EXPECT_THROW(swing.checker->check_motion(swing.q(0), Eigen::VectorXd::Zero(2)), InputError);
  MotionCheckOptions bad;
  bad.resolution = 0.0;
  EXPECT_THROW(swing.checker->check_motion(swing.q(0), swing.q(1), bad), InputError);
  bad = {};
  bad.min_clearance = -1.0;
  EXPECT_THROW(swing.checker->check_motion(swing.q(0), swing.q(1), bad), InputError);
  bad = {};
  bad.max_states = 0;
  EXPECT_THROW(swing.checker->check_motion(swing.q(0), swing.q(1), bad), InputError);
  // A budget too small to decide is reported, not taken for success.
  bad = {};
  bad.max_states = 1;
  const MotionCheckResult r = swing.checker->check_motion(swing.q(0), swing.q(1.2), bad);
  EXPECT_EQ(r.verdict, MotionVerdict::kStateBudget);
  EXPECT_FALSE(r.free());
}

// A link of two pieces sliding along x past a box: a long rod (its ball, radius 0.3 m, reaches
// the box; the rod itself stays 0.2 m from it) and a small cube at y = 0.25 m that passes
// through the box. Analytically the cube meets the box while |x - 0.5| < 0.045 (half widths
// 0.02 + 0.025) and the rod never does. The sweep must keep each piece's ball verdict apart from
// the other's covering spheres (b891229: the rod's covering spheres, clear, were once read as
// the cube's ball verdict and the crossing accepted); both orders of the pieces.
TEST(MotionCheck, TwoPieceLinkCrossingABoxIsRejected) {
  // The rod a mesh (a hull, so it has covering spheres besides its ball), the cube a primitive.
  const test::TempDir dir("two_pieces");
  std::string obj;
  for (int i = 0; i < 8; ++i) {
    obj += "v " + std::to_string(i & 1 ? 0.01 : -0.01) + " " +
           std::to_string(i & 2 ? 0.01 : -0.01) + " " + std::to_string(i & 4 ? 0.3 : -0.3) + "\n";
  }
  // The cuboid's faces (vertex bits x = 1, y = 2, z = 4), outward.
  obj += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  dir.write("rod.obj", obj);
  const std::string rod =
      R"(<collision><geometry><mesh filename="rod.obj"/></geometry></collision>)";
  const std::string cube =
      R"(<collision><origin xyz="0 0.25 0"/><geometry><box size="0.04 0.04 0.04"/></geometry></collision>)";
  const double contact_half_width = 0.045, box_x = 0.5;
  for (const bool rod_first : {true, false}) {
    const std::string urdf = R"(<robot name="slider"><link name="base"/><link name="carriage">)" +
                             (rod_first ? rod + cube : cube + rod) + R"(</link>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="carriage"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1.5" effort="1" velocity="1"/></joint>
</robot>)";
    const auto model = std::make_shared<const RobotModel>(
        RobotModel::from_urdf_string(urdf, dir.str(), {}, "slider.urdf"));
    PlanningScene scene;
    scene.obstacles.push_back(Obstacle{"block", "block", Shape(Box(0.05, 0.05, 0.05)),
                                       Eigen::Isometry3d(Eigen::Translation3d(box_x, 0.25, 0.0)),
                                       "box"});
    const CollisionChecker checker(
        model, AllowedCollisionMatrix(static_cast<int>(model->links().size())), scene);
    const auto q = [](double x) { return Eigen::VectorXd::Constant(1, x); };
    ASSERT_TRUE(checker.is_valid(q(0.0)));
    ASSERT_FALSE(checker.is_valid(q(box_x)));
    std::mt19937 rng(16);
    std::uniform_real_distribution<double> x(-1.0, 1.5);
    int crossing = 0, free = 0;
    for (int i = 0; i < 400; ++i) {
      const double a = x(rng), b = x(rng);
      const double lo = std::min(a, b), hi = std::max(a, b);
      // The motion's distance (in x) from the interval where the cube overlaps the box.
      const double gap =
          std::max({0.0, (box_x - contact_half_width) - hi, lo - (box_x + contact_half_width)});
      for (const bool locate : {true, false}) {
        MotionCheckOptions options;
        options.locate_contact = locate;
        const MotionCheckResult r = checker.check_motion(q(a), q(b), options);
        const std::string what = std::string(rod_first ? "rod first" : "cube first") +
                                 (locate ? ", located" : ", yes/no") + ", from " +
                                 std::to_string(a) + " to " + std::to_string(b);
        if (gap == 0.0) {
          ASSERT_FALSE(r.free()) << what;
          EXPECT_EQ(r.verdict, MotionVerdict::kContact) << what;
          // The contact reported is a state within min_clearance + resolution of the box.
          const double at = a + r.contact * (b - a);
          EXPECT_LE(std::abs(at - box_x),
                    contact_half_width + options.min_clearance + options.resolution + 1e-9)
              << what;
          crossing += locate;
        } else if (gap > options.min_clearance + options.resolution) {
          EXPECT_TRUE(r.free()) << what;
          free += locate;
        }
      }
    }
    EXPECT_GT(crossing, 50);
    EXPECT_GT(free, 50);
  }
}

// ------------------------------------------------------------------------------------------
// Random motions of the MotionBenchMaker problems against FCL, densely.

struct DenseStats {
  int motions = 0, accepted = 0, contact = 0, near_contact = 0;
  long states = 0;
  double worst_contact_distance = -1.0;  // FCL's distance at the reported contacts
};

// With `tables`, the self blocks' distance tables are measured first (and kept while
// `self_checker` lives): check_motion then certifies those blocks by walking their cells.
void dense_fcl_check(const test::MbmRobot& robot, int total_motions, bool tables = false) {
  const auto model = test::cached_model(robot.urdf);
  const Srdf srdf = read_srdf_file(robot.srdf);
  const AllowedCollisionMatrix matrix = AllowedCollisionMatrix::from_srdf(*model, srdf);
  const CollisionChecker self_checker(model, matrix);
  if (tables) self_checker.measure_self_tables();
  const MotionCheckOptions options;
  MotionCheckOptions first_found;
  first_found.locate_contact = false;
  const int scenes = 2 * static_cast<int>(robot.families.size());
  const int per_scene = std::max(1, test::sample_count(total_motions) / scenes);
  constexpr int kDense = 400;  // FCL states per accepted motion
  DenseStats stats;
  std::mt19937_64 rng(11);
  std::vector<Eigen::Isometry3d> poses;
  const Eigen::VectorXd lower = model->lower_limits(), upper = model->upper_limits();
  for (const std::string& family : robot.families) {
    for (const int number : {3, 42}) {
      const PlanningScene scene =
          read_planning_scene(test::mbm_file(robot, family, "scene", number), *model);
      const MotionPlanRequest request =
          read_motion_plan_request(test::mbm_file(robot, family, "request", number), *model);
      const std::vector<int> group = group_variables(*model, srdf, request.group);
      const CollisionChecker checker(model, matrix, scene);
      test::FclChecker fcl(*model, matrix, scene);
      const auto fcl_free = [&](const Eigen::VectorXd& q) {
        model->compute_link_poses(q, poses);
        fcl.set_link_poses(poses);
        return !fcl.in_collision();
      };
      // Motions from a valid state towards a random one up to 1.5 rad away in every group value
      // (RRTConnect's extensions are of that order): many pass near obstacles.
      std::uniform_real_distribution<double> step(-1.5, 1.5);
      for (int k = 0; k < per_scene; ++k) {
        Eigen::VectorXd q0, q1;
        do {
          q0 = test::random_configuration(*model, request.start, group, rng);
        } while (!checker.is_valid(q0));
        q1 = q0;
        for (int v : group) q1[v] = std::clamp(q0[v] + step(rng), lower[v], upper[v]);
        const MotionCheckResult r = checker.check_motion(q0, q1, options);
        ++stats.motions;
        stats.states += r.states;
        const auto at = [&](double t) { return Eigen::VectorXd(q0 + t * (q1 - q0)); };
        // [0, last_free] is free at every dense sample (all of it when accepted).
        for (int i = 0; i <= kDense; ++i) {
          const double t = r.last_free * i / kDense;
          EXPECT_TRUE(fcl_free(at(t)))
              << family << number << " motion " << k << " (" << static_cast<int>(r.verdict)
              << ") collides at t = " << t << " <= last_free " << r.last_free;
        }
        // The yes/no mode (level order, stopping at the first contact found) agrees; its
        // contact is one FCL finds within min_clearance (kContact) or min_clearance +
        // resolution (kNearContact) of touching.
        const MotionCheckResult yes_no = checker.check_motion(q0, q1, first_found);
        // (Both proofs; their intervals differ, so within `resolution` of contact one may
        // accept what the other calls near contact.)
        if (yes_no.free() != r.free()) {
          EXPECT_EQ((r.free() ? yes_no : r).verdict, MotionVerdict::kNearContact)
              << family << number << " motion " << k;
        }
        if (!yes_no.free()) {
          model->compute_link_poses(at(yes_no.contact), poses);
          fcl.set_link_poses(poses);
          const test::FclDistance d = fcl.min_distance();
          EXPECT_LE(d.collision ? 0.0 : d.distance,
                    options.min_clearance + 1e-6 +
                        (yes_no.verdict == MotionVerdict::kNearContact ? options.resolution : 0.0))
              << family << number << " motion " << k;
        }
        if (r.free()) {
          ++stats.accepted;
          continue;
        }
        ASSERT_NE(r.verdict, MotionVerdict::kStateBudget) << family << number << " motion " << k;
        (r.verdict == MotionVerdict::kContact ? stats.contact : stats.near_contact)++;
        // The contact state: FCL finds a pair within min_clearance + resolution (+ FCL's own
        // distance error on hulls, well below 1e-6 m) of touching. (kContact: some state of
        // the motion was found within min_clearance.)
        model->compute_link_poses(at(r.contact), poses);
        fcl.set_link_poses(poses);
        const test::FclDistance d = fcl.min_distance();
        const double distance = d.collision ? 0.0 : d.distance;
        const double limit = options.min_clearance + options.resolution;
        EXPECT_LE(distance, limit + 1e-6) << family << number << " motion " << k;
        stats.worst_contact_distance = std::max(stats.worst_contact_distance, distance);
      }
    }
  }
  std::printf(
      "[ %-8s ] %d motions: %d accepted (each free at %d FCL samples), %d contact, %d near "
      "contact; %.1f states per motion; largest FCL distance at a reported contact %.2e m\n",
      robot.id.c_str(), stats.motions, stats.accepted, kDense, stats.contact, stats.near_contact,
      static_cast<double>(stats.states) / stats.motions, stats.worst_contact_distance);
  EXPECT_GT(stats.accepted, stats.motions / 10);
  EXPECT_GT(stats.contact, stats.motions / 10);
}

TEST(MotionCheckFcl, PandaMotionsAgreeWithDenseFcl) {
  for (const test::MbmRobot& robot : test::mbm_robots()) {
    if (robot.id == "panda") return dense_fcl_check(robot, 2000);
  }
  GTEST_SKIP() << "MotionBenchMaker Panda absent";
}

TEST(MotionCheckFcl, Ur5MotionsAgreeWithDenseFcl) {
  for (const test::MbmRobot& robot : test::mbm_robots()) {
    if (robot.id == "ur5") return dense_fcl_check(robot, 200);
  }
  GTEST_SKIP() << "MotionBenchMaker UR5 absent";
}

TEST(MotionCheckFcl, WithSelfTablesPandaMotionsAgreeWithDenseFcl) {
  for (const test::MbmRobot& robot : test::mbm_robots()) {
    if (robot.id == "panda") return dense_fcl_check(robot, 1000, true);
  }
  GTEST_SKIP() << "MotionBenchMaker Panda absent";
}

TEST(MotionCheckFcl, WithSelfTablesUr5MotionsAgreeWithDenseFcl) {
  // Measuring the UR5's tables takes most of this test (37 s under ASan): sanitizer builds run
  // the same code on the Panda's tables (the test above) and this one in the Release stage.
  if (test::kSanitizerDivisor > 1) GTEST_SKIP() << "Release builds only (see the Panda's)";
  for (const test::MbmRobot& robot : test::mbm_robots()) {
    if (robot.id == "ur5") return dense_fcl_check(robot, 200, true);
  }
  GTEST_SKIP() << "MotionBenchMaker UR5 absent";
}

}  // namespace
}  // namespace hullcheck
