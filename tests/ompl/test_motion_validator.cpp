// GuaranteedMotionValidator: it rejects a motion through a thin plate that OMPL's discrete
// validator (default resolution) accepts; it reports the last valid state; every motion it
// accepts between random valid states (own arm scene, MotionBenchMaker Panda scenes) is valid
// at 2000 interpolated states; motions into collision are rejected; continuous joints move the
// short way round, as OMPL interpolates them. Also the StateValidityChecker's contract.
#include <gtest/gtest.h>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <hullcheck/ompl.hpp>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "ompl_test_support.hpp"

namespace hullcheck {
namespace {

namespace ob = ::ompl::base;
using test::LoadedRobot;

// A checker for the own arm in `scene` (obstacles only when `no_self`).
std::shared_ptr<const CollisionChecker> own_arm_checker(const LoadedRobot& robot,
                                                        PlanningScene scene, bool no_self = false) {
  return test::make_checker(robot, std::move(scene), !no_self);
}

Obstacle box_obstacle(const std::string& name, const Eigen::Vector3d& sizes,
                      const Eigen::Isometry3d& pose) {
  return Obstacle{name, name, Shape(Box(sizes)), pose, "box"};
}

// Statistics of the states certified motion checks evaluate.
struct StepStats {
  std::vector<int> accepted, rejected;
  static std::string describe(std::vector<int> v) {
    if (v.empty()) return "none";
    std::sort(v.begin(), v.end());
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    char buf[128];
    std::snprintf(buf, sizeof buf, "n %zu, mean %.1f, median %d, max %d", v.size(), mean,
                  v[v.size() / 2], v.back());
    return buf;
  }
};

// ---------------------------------------------------------------------------- thin plate

// The own arm swings about joint1 by 1 rad. A 2 mm plate stands in a vertical plane through the
// base axis, at the arm's outermost point halfway between two of the states OMPL's discrete
// validator checks (longest valid segment fraction 0.01). The discrete validator accepts the
// motion; the robot passes through the plate; the guaranteed validator rejects it.
class ThinPlate : public ::testing::Test {
 protected:
  void SetUp() override {
    robot_ = test::load_robot(test::own_arm());
    const RobotModel& model = *robot_.model;
    group_ = group_variables(model, robot_.srdf, "arm");
    fixed_ = model.default_configuration();
    // Arm stretched forward and down a little, tool pointing outwards.
    const double pose[] = {0.0, 1.1, 0.0, -0.5, 0.0, 0.4, 0.3};
    for (int i = 0; i < 7; ++i) fixed_[group_[static_cast<std::size_t>(i)]] = pose[i];
    qa_ = qb_ = fixed_;
    qa_[group_[0]] = -0.5;
    qb_[group_[0]] = 0.5;

    // Where the discrete validator checks: states j / nd of the motion.
    PlanningSetup empty = make_planning_setup(own_arm_checker(robot_, PlanningScene{}), group_,
                                              fixed_, MotionChecking::kDiscrete, 0.01);
    empty.setup->getSpaceInformation()->setup();
    segments_ = empty.setup->getStateSpace()->validSegmentCount(empty.state(qa_).get(),
                                                                empty.state(qb_).get());
    // The plate goes halfway between two checked states near the middle.
    t_mid_ = (std::floor(segments_ / 2.0) + 0.5) / segments_;
    const double theta = qa_[group_[0]] + t_mid_ * (qb_[group_[0]] - qa_[group_[0]]);
    const Eigen::Vector3d radial(std::cos(theta), std::sin(theta), 0.0);

    // The arm's outermost point along `radial` at t_mid: the witness point on the robot against
    // a large probe box 3 m out (robot against obstacles only).
    PlanningScene probe;
    Eigen::Isometry3d probe_pose = Eigen::Isometry3d::Identity();
    probe_pose.linear() = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    probe_pose.translation() = 3.5 * radial;
    probe.obstacles.push_back(box_obstacle("probe", Eigen::Vector3d(1.0, 10.0, 10.0), probe_pose));
    Eigen::VectorXd q_mid = qa_ + t_mid_ * (qb_ - qa_);
    const ClearanceResult extreme = own_arm_checker(robot_, probe, true)->clearance(q_mid);
    tip_ = extreme.point_a;
    tip_link_ = std::string(extreme.name_a);

    // The plate: 2 mm thick (tangentially), from 1 cm inside the outermost point to 5 cm
    // beyond it radially, 6 cm tall, its mid-plane through that point.
    Eigen::Isometry3d plate_pose = Eigen::Isometry3d::Identity();
    plate_pose.linear() = probe_pose.linear();  // x radial, y tangential, z up
    plate_pose.translation() = tip_ + 0.02 * radial;
    PlanningScene scene;
    scene.name = "thin_plate";
    scene.obstacles.push_back(
        box_obstacle("plate", Eigen::Vector3d(0.06, 0.002, 0.06), plate_pose));
    checker_ = own_arm_checker(robot_, scene);
    guaranteed_ = make_planning_setup(checker_, group_, fixed_);
    discrete_ = make_planning_setup(checker_, group_, fixed_, MotionChecking::kDiscrete, 0.01);
    guaranteed_.setup->getSpaceInformation()->setup();
    discrete_.setup->getSpaceInformation()->setup();
  }

  LoadedRobot robot_;
  std::vector<int> group_;
  Eigen::VectorXd fixed_, qa_, qb_;
  unsigned segments_ = 0;
  double t_mid_ = 0.0;
  Eigen::Vector3d tip_;
  std::string tip_link_;
  std::shared_ptr<const CollisionChecker> checker_;
  PlanningSetup guaranteed_, discrete_;
};

TEST_F(ThinPlate, DiscreteValidatorMissesItGuaranteedValidatorRejects) {
  const ob::SpaceInformationPtr& gsi = guaranteed_.setup->getSpaceInformation();
  const ob::SpaceInformationPtr& dsi = discrete_.setup->getSpaceInformation();
  ASSERT_NE(std::dynamic_pointer_cast<GuaranteedMotionValidator>(gsi->getMotionValidator()),
            nullptr);
  ASSERT_NE(std::dynamic_pointer_cast<ob::DiscreteMotionValidator>(dsi->getMotionValidator()),
            nullptr);
  EXPECT_DOUBLE_EQ(dsi->getStateValidityCheckingResolution(), 0.01);
  const auto a = guaranteed_.state(qa_), b = guaranteed_.state(qb_);
  ASSERT_TRUE(gsi->isValid(a.get()));
  ASSERT_TRUE(gsi->isValid(b.get()));
  // The robot passes through the plate: invalid at the plate's place (dense re-check).
  const test::DenseCheck dense =
      test::dense_check(*gsi, *guaranteed_.validity, a.get(), b.get(), 2000);
  ASSERT_FALSE(dense.valid) << "construction: the arm does not reach the plate";
  EXPECT_NEAR(dense.first_invalid, t_mid_, 0.5 / segments_);
  std::printf(
      "[thin plate] outermost point on %s at (%.3f %.3f %.3f); discrete validator: %u "
      "segments; robot inside the plate from t = %.4f, min clearance %.4f m\n",
      tip_link_.c_str(), tip_.x(), tip_.y(), tip_.z(), segments_, dense.first_invalid,
      dense.min_clearance);
  // OMPL's discrete validator checks only states j / segments: it accepts.
  ASSERT_GE(segments_, 3u);
  for (unsigned j = 0; j <= segments_; ++j) {
    ob::ScopedState<> s(dsi->getStateSpace());
    dsi->getStateSpace()->interpolate(a.get(), b.get(), static_cast<double>(j) / segments_,
                                      s.get());
    ASSERT_TRUE(dsi->isValid(s.get())) << "construction: checked state " << j << " collides";
  }
  EXPECT_TRUE(dsi->checkMotion(a.get(), b.get())) << "the discrete validator should miss it";
  // Ours does not, in both directions and with the last-valid overload.
  EXPECT_FALSE(gsi->checkMotion(a.get(), b.get()));
  EXPECT_FALSE(gsi->checkMotion(b.get(), a.get()));
  const auto* mv = dynamic_cast<const GuaranteedMotionValidator*>(gsi->getMotionValidator().get());
  std::printf("[thin plate] guaranteed validator: rejected after %d steps\n",
              test::count_advancement_steps(*mv, *guaranteed_.validity, a.get(), b.get()));
  // Without the plate, the same motion is accepted by ours too.
  PlanningSetup free =
      make_planning_setup(own_arm_checker(robot_, PlanningScene{}), group_, fixed_);
  free.setup->getSpaceInformation()->setup();
  EXPECT_TRUE(
      free.setup->getSpaceInformation()->checkMotion(free.state(qa_).get(), free.state(qb_).get()));
}

TEST_F(ThinPlate, LastValidStateAndFraction) {
  const ob::SpaceInformationPtr& si = guaranteed_.setup->getSpaceInformation();
  const auto a = guaranteed_.state(qa_), b = guaranteed_.state(qb_);
  const test::DenseCheck dense =
      test::dense_check(*si, *guaranteed_.validity, a.get(), b.get(), 2000);
  ASSERT_FALSE(dense.valid);
  ob::ScopedState<> last(si->getStateSpace());
  std::pair<ob::State*, double> last_valid(last.get(), -1.0);
  ASSERT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last_valid));
  EXPECT_GE(last_valid.second, 0.0);
  EXPECT_LT(last_valid.second, dense.first_invalid) << "the last valid state is before contact";
  EXPECT_GT(last_valid.second, 0.5 * dense.first_invalid) << "and not needlessly far back";
  // The returned state is the motion's state at that fraction, valid, and reachable.
  ob::ScopedState<> expected(si->getStateSpace());
  si->getStateSpace()->interpolate(a.get(), b.get(), last_valid.second, expected.get());
  EXPECT_LT(si->distance(expected.get(), last.get()), 1e-12);
  EXPECT_TRUE(si->isValid(last.get()));
  EXPECT_GT(guaranteed_.validity->clearance(last.get()), 0.0);
  EXPECT_TRUE(si->checkMotion(a.get(), last.get()));
  EXPECT_TRUE(test::dense_check(*si, *guaranteed_.validity, a.get(), last.get(), 500).valid);
  // A null state pointer only gets the fraction.
  std::pair<ob::State*, double> fraction_only(nullptr, -1.0);
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), fraction_only));
  EXPECT_EQ(fraction_only.second, last_valid.second);
  std::printf("[thin plate] last valid fraction %.4f, contact at %.4f\n", last_valid.second,
              dense.first_invalid);
}

// ---------------------------------------------------------------------------- random motions

struct MotionStats {
  int accepted = 0, rejected = 0;
  int rejected_but_dense_valid = 0;   // conservative rejections (the dense check found no contact)
  int discrete_accepted_invalid = 0;  // OMPL's discrete validator accepted a colliding motion
  StepStats steps;
};

// A valid pair whose straight motion passes through a random valid state closer than 15 mm to
// something (a grazing motion): a = m - v, b = m + v for a random group offset v.
bool sample_grazing_pair(const PlanningSetup& setup, test::StateSampler& sampler, ob::State* a,
                         ob::State* b) {
  const ob::SpaceInformationPtr& si = setup.setup->getSpaceInformation();
  const JointStateSpace& joints = *setup.joints;
  const Eigen::VectorXd lo = joints.model().lower_limits(), hi = joints.model().upper_limits();
  ob::ScopedState<> m(si->getStateSpace());
  Eigen::VectorXd qm(lo.size()), qa(lo.size()), qb(lo.size());
  std::uniform_real_distribution<double> offset(-0.3, 0.3);
  for (int tries = 0; tries < 20000; ++tries) {
    sampler.uniform(m.get());
    const double d = setup.validity->clearance(m.get());
    if (!(d > 0.0 && d < 0.015)) continue;
    joints.to_configuration(m.get(), qm);
    for (int k = 0; k < 20; ++k) {
      qa = qb = qm;
      for (int v : joints.variables()) {
        const double o = offset(sampler.rng());
        qa[v] = std::min(std::max(qm[v] - o, lo[v]), hi[v]);
        qb[v] = std::min(std::max(qm[v] + o, lo[v]), hi[v]);
      }
      joints.from_configuration(qa, a);
      joints.from_configuration(qb, b);
      if (si->isValid(a) && si->isValid(b)) return true;
    }
  }
  return false;
}

// Random valid pairs (a third uniform, a third near each other as planners extend, a third
// grazing obstacles): every motion the guaranteed validator accepts is valid at `dense` + 1
// interpolated states, with positive clearance, and so is its reverse; OMPL's discrete validator
// is run on the same motions for comparison.
void check_random_motions(const PlanningSetup& setup, const PlanningSetup& discrete, int pairs,
                          int dense, unsigned seed, MotionStats* stats) {
  const ob::SpaceInformationPtr& si = setup.setup->getSpaceInformation();
  const ob::SpaceInformationPtr& dsi = discrete.setup->getSpaceInformation();
  const auto* mv = dynamic_cast<const GuaranteedMotionValidator*>(si->getMotionValidator().get());
  ASSERT_NE(mv, nullptr);
  test::StateSampler sampler(*setup.joints, seed);
  ob::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace());
  for (int k = 0; k < pairs; ++k) {
    if (k % 3 == 2) {
      ASSERT_TRUE(sample_grazing_pair(setup, sampler, a.get(), b.get()));
    } else {
      ASSERT_TRUE(test::sample_valid(*si, sampler, a.get()));
      ASSERT_TRUE(k % 3 == 1 ? test::sample_valid_near(*si, sampler, a.get(), 0.4, b.get())
                             : test::sample_valid(*si, sampler, b.get()));
    }
    const bool ok = si->checkMotion(a.get(), b.get());
    const int steps = test::count_advancement_steps(*mv, *setup.validity, a.get(), b.get());
    const test::DenseCheck d = test::dense_check(*si, *setup.validity, a.get(), b.get(), dense);
    if (ok) {
      ++stats->accepted;
      stats->steps.accepted.push_back(steps);
      EXPECT_TRUE(d.valid) << "accepted motion " << k << " collides at t = " << d.first_invalid;
      EXPECT_GT(d.min_clearance, 0.0);
      // The reverse motion is the same set of states.
      EXPECT_TRUE(si->checkMotion(b.get(), a.get()));
    } else {
      ++stats->rejected;
      stats->steps.rejected.push_back(steps);
      if (d.valid) ++stats->rejected_but_dense_valid;
    }
    if (dsi->checkMotion(a.get(), b.get()) && !d.valid) ++stats->discrete_accepted_invalid;
  }
}

void report(const std::string& what, const MotionStats& s) {
  std::printf(
      "[%s] accepted %d, rejected %d (dense-valid among rejected: %d); discrete validator "
      "accepted %d colliding motions\n  steps of accepted motions: %s\n  steps of rejected "
      "motions: %s\n",
      what.c_str(), s.accepted, s.rejected, s.rejected_but_dense_valid, s.discrete_accepted_invalid,
      StepStats::describe(s.steps.accepted).c_str(), StepStats::describe(s.steps.rejected).c_str());
}

TEST(GuaranteedMotions, OwnArmTableWallAcceptedMotionsAreValid) {
  const LoadedRobot robot = test::load_robot(test::own_arm());
  auto checker =
      test::make_checker(robot, read_planning_scene(test::own_arm_scene(), *robot.model));
  const std::vector<int> group = group_variables(*robot.model, robot.srdf, "arm");
  const Eigen::VectorXd fixed = robot.model->default_configuration();
  PlanningSetup setup = make_planning_setup(checker, group, fixed);
  PlanningSetup discrete = make_planning_setup(checker, group, fixed, MotionChecking::kDiscrete);
  setup.setup->getSpaceInformation()->setup();
  discrete.setup->getSpaceInformation()->setup();
  MotionStats stats;
  check_random_motions(setup, discrete, test::scaled(40, 6), test::scaled(2000, 300), 17, &stats);
  report("own arm table_wall", stats);
  EXPECT_GE(stats.accepted, test::scaled(8, 1)) << "too few accepted motions to mean anything";
  const auto* mv = dynamic_cast<const GuaranteedMotionValidator*>(
      setup.setup->getSpaceInformation()->getMotionValidator().get());
  ASSERT_NE(mv, nullptr);
  // Its counters saw every verdict (motions are also checked again for step counts and reversed).
  EXPECT_GE(mv->valid_motion_count(), static_cast<unsigned long>(stats.accepted));
  EXPECT_GE(mv->invalid_motion_count(), static_cast<unsigned long>(stats.rejected));
}

TEST(GuaranteedMotions, MbmPandaAcceptedMotionsAreValid) {
  const auto file = test::mbm_robot("panda");
  if (!file) GTEST_SKIP() << "shared benchmarks absent";
  const LoadedRobot robot = test::load_robot(*file);
  const std::vector<int> group = group_variables(*robot.model, robot.srdf, "panda_arm");
  const std::vector<std::string> families =
      test::kSanitized ? std::vector<std::string>{"box"}
                       : std::vector<std::string>{"bookshelf_small", "box", "cage", "table_pick"};
  MotionStats total;
  for (std::size_t f = 0; f < families.size(); ++f) {
    SCOPED_TRACE(families[f]);
    const std::string scene_file = test::mbm_file("panda", families[f], 1, "scene");
    auto checker = test::make_checker(robot, read_planning_scene(scene_file, *robot.model));
    const MotionPlanRequest request =
        read_motion_plan_request(test::mbm_file("panda", families[f], 1, "request"), *robot.model);
    PlanningSetup setup = make_planning_setup(checker, group, request.start);
    PlanningSetup discrete =
        make_planning_setup(checker, group, request.start, MotionChecking::kDiscrete);
    setup.setup->getSpaceInformation()->setup();
    discrete.setup->getSpaceInformation()->setup();
    MotionStats stats;
    check_random_motions(setup, discrete, test::scaled(16, 4), test::scaled(2000, 300),
                         100 + static_cast<unsigned>(f), &stats);
    report("mbm panda " + families[f], stats);
    total.accepted += stats.accepted;
    total.rejected += stats.rejected;
  }
  EXPECT_GE(total.accepted, test::scaled(10, 1));
}

TEST(GuaranteedMotions, MotionIntoCollisionIsRejected) {
  const LoadedRobot robot = test::load_robot(test::own_arm());
  auto checker =
      test::make_checker(robot, read_planning_scene(test::own_arm_scene(), *robot.model));
  const std::vector<int> group = group_variables(*robot.model, robot.srdf, "arm");
  PlanningSetup setup = make_planning_setup(checker, group, robot.model->default_configuration());
  setup.setup->getSpaceInformation()->setup();
  const ob::SpaceInformationPtr& si = setup.setup->getSpaceInformation();
  test::StateSampler sampler(*setup.joints, 23);
  ob::ScopedState<> valid(si->getStateSpace()), colliding(si->getStateSpace()),
      last(si->getStateSpace());
  int checked = 0;
  // About 2% of these motions' last valid states lie inside the band where the yes/no search
  // says "near contact" (62 of 3000 on 2026-12-07): the validator moves them back.
  for (int k = 0; k < 6000 && checked < test::scaled(300, 30); ++k) {
    ASSERT_TRUE(test::sample_valid(*si, sampler, valid.get()));
    sampler.near(valid.get(), 0.5, colliding.get());
    if (si->isValid(colliding.get())) continue;
    ++checked;
    EXPECT_LE(setup.validity->clearance(colliding.get()), 0.0);
    EXPECT_FALSE(si->checkMotion(valid.get(), colliding.get()));
    EXPECT_FALSE(si->checkMotion(colliding.get(), valid.get()));
    std::pair<ob::State*, double> last_valid(last.get(), -1.0);
    EXPECT_FALSE(si->getMotionValidator()->checkMotion(valid.get(), colliding.get(), last_valid));
    EXPECT_GE(last_valid.second, 0.0);
    EXPECT_LT(last_valid.second, 1.0);
    EXPECT_TRUE(si->isValid(last.get()));
    // The motion up to it was proven free, and checked again it is accepted (a planner keeps
    // it as a motion of its own, which its path's re-check meets again), in both overloads.
    EXPECT_TRUE(si->checkMotion(valid.get(), last.get())) << "motion " << k;
    std::pair<ob::State*, double> unused(nullptr, -1.0);
    EXPECT_TRUE(si->getMotionValidator()->checkMotion(valid.get(), last.get(), unused));
    // Without a state to fill, the same fraction.
    std::pair<ob::State*, double> fraction_only(nullptr, -1.0);
    si->getMotionValidator()->checkMotion(valid.get(), colliding.get(), fraction_only);
    EXPECT_EQ(fraction_only.second, last_valid.second) << "motion " << k;
    // Starting in collision: nothing of the motion is valid.
    std::pair<ob::State*, double> from_collision(nullptr, -1.0);
    EXPECT_FALSE(
        si->getMotionValidator()->checkMotion(colliding.get(), valid.get(), from_collision));
    EXPECT_EQ(from_collision.second, 0.0);
  }
  EXPECT_GE(checked, test::scaled(300, 30));
  // A motion of length zero at a valid state is valid.
  EXPECT_TRUE(si->checkMotion(valid.get(), valid.get()));
}

// Continuous joints move the short way round (as OMPL's SO2 interpolation does): joint7 from
// 3.0 to -3.0 turns by 0.28 rad through pi. Small cubes sit where the fingers are at joint7 =
// +-pi/2, which only the long way (through 0) passes.
TEST(GuaranteedMotions, ContinuousJointMovesTheShortWay) {
  const LoadedRobot robot = test::load_robot(test::own_arm());
  const RobotModel& model = *robot.model;
  const std::vector<int> group = group_variables(model, robot.srdf, "arm");
  const int j7 = model.variable_index("joint7");
  Eigen::VectorXd q = model.default_configuration();
  const double pose[] = {0.0, 0.6, 0.0, -1.2, 0.0, 0.9, 0.0};
  for (int i = 0; i < 7; ++i) q[group[static_cast<std::size_t>(i)]] = pose[i];
  q[model.variable_index("finger_joint1")] = 0.04;
  std::vector<Eigen::Isometry3d> poses;
  PlanningScene scene;
  for (double angle : {M_PI / 2, -M_PI / 2}) {
    q[j7] = angle;
    model.compute_link_poses(q, poses);
    const int finger = model.link_index("finger_left");
    ASSERT_GE(finger, 0);
    const CollisionShape& shape = model.link(finger).shapes.at(0);
    const Eigen::Vector3d center =
        poses[static_cast<std::size_t>(finger)] * shape.origin * shape.bounding_center;
    scene.obstacles.push_back(box_obstacle("cube" + std::to_string(scene.obstacles.size()),
                                           Eigen::Vector3d(0.01, 0.01, 0.01),
                                           Eigen::Isometry3d(Eigen::Translation3d(center))));
  }
  auto checker = test::make_checker(robot, scene);
  PlanningSetup setup = make_planning_setup(checker, group, q);
  setup.setup->getSpaceInformation()->setup();
  const ob::SpaceInformationPtr& si = setup.setup->getSpaceInformation();
  Eigen::VectorXd qa = q, qb = q;
  qa[j7] = 3.0;
  qb[j7] = -3.0;
  const auto a = setup.state(qa), b = setup.state(qb);
  ASSERT_TRUE(si->isValid(a.get()));
  ASSERT_TRUE(si->isValid(b.get()));
  // The long way round collides (construction check, by configurations).
  bool long_way_collides = false;
  for (int i = 0; i <= 600; ++i) {
    Eigen::VectorXd qi = qa;
    qi[j7] = 3.0 - 6.0 * i / 600.0;
    long_way_collides |= !checker->is_valid(qi);
  }
  ASSERT_TRUE(long_way_collides);
  // OMPL's interpolation goes through pi, and so does the check.
  EXPECT_NEAR(si->distance(a.get(), b.get()), 2 * M_PI - 6.0, 1e-12);
  EXPECT_TRUE(test::dense_check(*si, *setup.validity, a.get(), b.get(), 500).valid);
  EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
  EXPECT_TRUE(si->checkMotion(b.get(), a.get()));
  // 3.0 to 0.5 has no short way avoiding +pi/2: rejected.
  Eigen::VectorXd qc = q;
  qc[j7] = 0.5;
  EXPECT_FALSE(si->checkMotion(a.get(), setup.state(qc).get()));
}

// ---------------------------------------------------------------------------- validity checker

void check_validity_contract(const PlanningSetup& setup, int samples, unsigned seed) {
  const ob::SpaceInformationPtr& si = setup.setup->getSpaceInformation();
  const StateValidityChecker& v = *setup.validity;
  EXPECT_EQ(v.getSpecs().clearanceComputationType, ob::StateValidityCheckerSpecs::EXACT);
  EXPECT_FALSE(v.getSpecs().hasValidDirectionComputation);
  EXPECT_EQ(si->getStateValidityChecker().get(), &v);
  test::StateSampler sampler(*setup.joints, seed);
  ob::ScopedState<> s(si->getStateSpace());
  Eigen::VectorXd q(v.joint_space().fixed_configuration().size());
  int valid = 0, invalid = 0;
  for (int k = 0; k < samples; ++k) {
    sampler.uniform(s.get());
    double dist = std::numeric_limits<double>::quiet_NaN();
    const bool with_dist = v.isValid(s.get(), dist);
    const bool plain = v.isValid(s.get());
    EXPECT_EQ(plain, with_dist) << "sample " << k << ", clearance " << dist;
    EXPECT_EQ(with_dist, dist > 0.0);
    v.joint_space().to_configuration(s.get(), q);
    const ClearanceResult exact = v.collision_checker().clearance(q);
    EXPECT_EQ(v.clearance(s.get()), exact.distance);
    EXPECT_EQ(dist, exact.distance);
    EXPECT_EQ(plain, v.collision_checker().is_valid(q));
    const ClearanceResult closest = v.closest(s.get());
    EXPECT_EQ(closest.distance, exact.distance);
    EXPECT_EQ(closest.name_a, exact.name_a);
    EXPECT_EQ(closest.name_b, exact.name_b);
    // The last isValid(state) answer on this thread: this configuration, when valid.
    EXPECT_EQ(v.last_valid_is(q), plain);
    Eigen::VectorXd moved = q;
    moved[v.joint_space().variables().front()] += 1e-9;
    EXPECT_FALSE(v.last_valid_is(moved));
    (plain ? valid : invalid)++;
  }
  EXPECT_GT(valid, 0);
  EXPECT_GT(invalid, 0);
}

TEST(ValidityChecker, AgreesWithExactClearanceOwnArm) {
  const LoadedRobot robot = test::load_robot(test::own_arm());
  auto checker =
      test::make_checker(robot, read_planning_scene(test::own_arm_scene(), *robot.model));
  PlanningSetup setup =
      make_planning_setup(checker, group_variables(*robot.model, robot.srdf, "arm"),
                          robot.model->default_configuration());
  check_validity_contract(setup, test::scaled(400, 60), 31);
  // A clear state has the clearance of its closest pair and names it.
  Eigen::VectorXd q = robot.model->default_configuration();
  const auto s = setup.state(q);
  const ClearanceResult c = setup.validity->closest(s.get());
  EXPECT_GT(c.distance, 0.0);
  EXPECT_FALSE(c.name_a.empty());
  EXPECT_FALSE(c.name_b.empty());
  EXPECT_NEAR((c.point_b - c.point_a).norm(), c.distance, 1e-6);
}

TEST(ValidityChecker, AgreesWithExactClearanceMbmPanda) {
  const auto file = test::mbm_robot("panda");
  if (!file) GTEST_SKIP() << "shared benchmarks absent";
  const LoadedRobot robot = test::load_robot(*file);
  auto checker = test::make_checker(
      robot,
      read_planning_scene(test::mbm_file("panda", "bookshelf_tall", 1, "scene"), *robot.model));
  PlanningSetup setup =
      make_planning_setup(checker, group_variables(*robot.model, robot.srdf, "panda_arm"),
                          robot.model->default_configuration());
  check_validity_contract(setup, test::scaled(200, 30), 37);
}

}  // namespace
}  // namespace hullcheck

namespace hullcheck {
namespace {

TEST(GuaranteedMotions, BadOptionsNameTheValidatorAndTheOption) {
  const LoadedRobot robot = test::load_robot(test::own_arm());
  auto checker = test::make_checker(robot, PlanningScene{});
  const std::vector<int> group = group_variables(*robot.model, robot.srdf, "arm");
  PlanningSetup setup = make_planning_setup(checker, group, robot.model->default_configuration());
  const ob::SpaceInformationPtr& si = setup.setup->getSpaceInformation();
  MotionCheckOptions bad;
  bad.resolution = 0.0;
  const std::string message =
      test::input_error_of([&] { GuaranteedMotionValidator(si, setup.validity, bad); });
  EXPECT_NE(message.find("GuaranteedMotionValidator"), std::string::npos) << message;
  EXPECT_NE(message.find("resolution"), std::string::npos) << message;
  bad = {};
  bad.max_states = 0;
  EXPECT_THROW(GuaranteedMotionValidator(si, setup.validity, bad), InputError);
}

}  // namespace
}  // namespace hullcheck
