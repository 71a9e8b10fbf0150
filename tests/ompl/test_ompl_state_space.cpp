// JointStateSpace and planning groups: the OMPL space of a group (real dimensions for bounded
// joints, SO2 for continuous ones), conversions to and from full configurations, held joints,
// wrapping, bounds from the URDF, input errors; groups from real SRDFs.
#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <cmath>
#include <hullcheck/ompl.hpp>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "ompl_test_support.hpp"

namespace hullcheck {
namespace {

namespace ob = ::ompl::base;
using test::LoadedRobot;

const std::vector<std::string> kArmJoints = {"joint1", "joint2", "joint3", "joint4",
                                             "joint5", "joint6", "joint7"};
const std::vector<std::string> kPandaJoints = {"panda_joint1", "panda_joint2", "panda_joint3",
                                               "panda_joint4", "panda_joint5", "panda_joint6",
                                               "panda_joint7"};
const std::vector<std::string> kUrJoints = {"shoulder_pan_joint", "shoulder_lift_joint",
                                            "elbow_joint",        "wrist_1_joint",
                                            "wrist_2_joint",      "wrist_3_joint"};

using test::random_configuration;

// The wrapped angle: in [-pi, pi) and equal to `a` modulo 2 pi (up to the rounding of 2 pi,
// which grows with |a|).
void expect_wrapped(double wrapped, double a) {
  EXPECT_GE(wrapped, -M_PI);
  EXPECT_LT(wrapped, M_PI);
  const double tolerance = 1e-12 * std::max(1.0, std::abs(a));
  EXPECT_NEAR(std::cos(wrapped), std::cos(a), tolerance);
  EXPECT_NEAR(std::sin(wrapped), std::sin(a), tolerance);
}

// Round trips on random configurations: group values come back exactly (continuous ones
// modulo 2 pi, already in range here), held joints take the space's fixed values whatever q
// held, and the state lies within the space's bounds.
void check_round_trips(const JointStateSpace& joints, std::mt19937_64& rng, int count) {
  const RobotModel& model = joints.model();
  ob::ScopedState<> state(joints.space());
  Eigen::VectorXd back(model.variable_count());
  for (int k = 0; k < count; ++k) {
    const Eigen::VectorXd q = random_configuration(model, rng);
    joints.from_configuration(q, state.get());
    EXPECT_TRUE(joints.space()->satisfiesBounds(state.get()));
    joints.to_configuration(state.get(), back);
    for (int v = 0; v < model.variable_count(); ++v) {
      const bool in_group = std::find(joints.variables().begin(), joints.variables().end(), v) !=
                            joints.variables().end();
      const double want = in_group ? q[v] : joints.fixed_configuration()[v];
      EXPECT_EQ(back[v], want) << model.variable_names()[static_cast<std::size_t>(v)];
    }
    // Group values in dimension order.
    Eigen::VectorXd values(joints.dimension());
    joints.to_group_values(state.get(), values);
    for (int i = 0; i < joints.dimension(); ++i) {
      EXPECT_EQ(values[i], q[joints.variables()[static_cast<std::size_t>(i)]]);
    }
    // And back again: the same state.
    ob::ScopedState<> again(joints.space());
    joints.from_configuration(back, again.get());
    EXPECT_TRUE(joints.space()->equalStates(state.get(), again.get()));
  }
}

// Every kind of bad input is an InputError, never a silent wrong state.
void check_input_errors(const JointStateSpace& joints) {
  const RobotModel& model = joints.model();
  const Eigen::VectorXd q = joints.fixed_configuration();
  ob::ScopedState<> state(joints.space());
  const Eigen::VectorXd shorter = q.head(q.size() - 1);
  Eigen::VectorXd longer(q.size() + 1);
  longer << q, 0.0;
  EXPECT_THROW(joints.from_configuration(shorter, state.get()), InputError);
  EXPECT_THROW(joints.from_configuration(longer, state.get()), InputError);
  EXPECT_THROW(joints.from_configuration(Eigen::VectorXd(), state.get()), InputError);
  for (int v = 0; v < model.variable_count(); ++v) {
    for (double bad :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
      Eigen::VectorXd b = q;
      b[v] = bad;
      EXPECT_THROW(joints.from_configuration(b, state.get()), InputError)
          << model.variable_names()[static_cast<std::size_t>(v)] << " = " << bad;
    }
  }
  Eigen::VectorXd out_short(q.size() - 1), out_long(q.size() + 1);
  EXPECT_THROW(joints.to_configuration(state.get(), out_short), InputError);
  EXPECT_THROW(joints.to_configuration(state.get(), out_long), InputError);
  Eigen::VectorXd values(joints.dimension() + 1);
  EXPECT_THROW(joints.to_group_values(state.get(), values), InputError);

  // Construction: empty group, repeated or out-of-range index, bad held configuration.
  const auto model_ptr = std::shared_ptr<const RobotModel>(&model, [](const RobotModel*) {});
  const std::vector<int> group = joints.variables();
  EXPECT_THROW(JointStateSpace(model_ptr, {}, q), InputError);
  EXPECT_THROW(JointStateSpace(model_ptr, {group[0], group[0]}, q), InputError);
  EXPECT_THROW(JointStateSpace(model_ptr, {model.variable_count()}, q), InputError);
  EXPECT_THROW(JointStateSpace(model_ptr, {-1}, q), InputError);
  EXPECT_THROW(JointStateSpace(model_ptr, group, shorter), InputError);
  Eigen::VectorXd nan_fixed = q;
  nan_fixed[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(JointStateSpace(model_ptr, group, nan_fixed), InputError);
  EXPECT_THROW(JointStateSpace(nullptr, group, q), InputError);
}

// Real bounds of a RealVectorStateSpace equal the URDF limits of the joints in dimension order.
void expect_urdf_bounds(const RobotModel& model, const std::vector<int>& variables,
                        const ob::RealVectorStateSpace& real) {
  const ob::RealVectorBounds& bounds = real.getBounds();
  ASSERT_EQ(bounds.low.size(), variables.size());
  for (std::size_t i = 0; i < variables.size(); ++i) {
    const Joint& j = model.joint(model.variable_joint(variables[i]));
    EXPECT_EQ(bounds.low[i], j.lower) << j.name;
    EXPECT_EQ(bounds.high[i], j.upper) << j.name;
    EXPECT_TRUE(std::isfinite(j.lower) && std::isfinite(j.upper)) << j.name;
    EXPECT_EQ(real.getDimensionName(static_cast<unsigned>(i)), j.name);
  }
}

// ------------------------------------------------------------------ own arm (continuous joint7)

class OwnArmSpace : public ::testing::Test {
 protected:
  void SetUp() override {
    robot_ = test::load_robot(test::own_arm());
    group_ = group_variables(*robot_.model, robot_.srdf, "arm");
    fixed_ = robot_.model->default_configuration();
    fixed_[robot_.model->variable_index("finger_joint1")] = 0.031;
    joints_ = std::make_shared<JointStateSpace>(robot_.model, group_, fixed_);
  }
  LoadedRobot robot_;
  std::vector<int> group_;
  Eigen::VectorXd fixed_;
  std::shared_ptr<JointStateSpace> joints_;
};

TEST_F(OwnArmSpace, CompoundOfRealAndSO2) {
  const RobotModel& model = *robot_.model;
  EXPECT_EQ(test::names_of(model, group_), kArmJoints);
  ASSERT_EQ(joints_->dimension(), 7);
  EXPECT_EQ(joints_->space()->getDimension(), 7u);
  // Bounded joints first (joint1..6), then the continuous joint7.
  EXPECT_EQ(test::names_of(model, joints_->variables()), kArmJoints);
  const auto compound = std::dynamic_pointer_cast<ob::CompoundStateSpace>(joints_->space());
  ASSERT_NE(compound, nullptr) << "joint7 is continuous: the space must be compound";
  ASSERT_EQ(compound->getSubspaceCount(), 2u);
  const auto real = std::dynamic_pointer_cast<ob::RealVectorStateSpace>(compound->getSubspace(0));
  ASSERT_NE(real, nullptr);
  EXPECT_EQ(real->getDimension(), 6u);
  expect_urdf_bounds(model, std::vector<int>(group_.begin(), group_.begin() + 6), *real);
  const auto so2 = std::dynamic_pointer_cast<ob::SO2StateSpace>(compound->getSubspace(1));
  ASSERT_NE(so2, nullptr);
  EXPECT_EQ(so2->getName(), "joint7");
  // URDF values of the arm joints: +-2.9671 and +-2.0944 alternate.
  EXPECT_EQ(real->getBounds().low[0], -2.9671);
  EXPECT_EQ(real->getBounds().high[1], 2.0944);
}

TEST_F(OwnArmSpace, RoundTripAndHeldJoints) {
  std::mt19937_64 rng(11);
  check_round_trips(*joints_, rng, 200);
  // The held finger keeps the space's value whatever the configuration given says.
  const int finger = robot_.model->variable_index("finger_joint1");
  Eigen::VectorXd q = fixed_;
  q[finger] = 0.0;
  q[group_[2]] = 0.7;
  ob::ScopedState<> state(joints_->space());
  joints_->from_configuration(q, state.get());
  Eigen::VectorXd back(q.size());
  joints_->to_configuration(state.get(), back);
  EXPECT_EQ(back[finger], 0.031);
  EXPECT_EQ(back[group_[2]], 0.7);
}

TEST_F(OwnArmSpace, ContinuousJointWrapsIntoMinusPiPi) {
  const int j7 = robot_.model->variable_index("joint7");
  const auto compound = joints_->space()->as<ob::CompoundStateSpace>();
  ob::ScopedState<> state(joints_->space());
  const auto so2_value = [&] {
    return state->as<ob::CompoundStateSpace::StateType>()
        ->as<ob::SO2StateSpace::StateType>(1)
        ->value;
  };
  Eigen::VectorXd q = fixed_;
  for (double a : {0.0, 1.0, -1.0, 3.0, 3.5, -3.5, M_PI, -M_PI, 2 * M_PI, -2 * M_PI, 7.0, -7.0,
                   100.0, -100.0, 1e6, std::nextafter(M_PI, 0.0), 3 * M_PI}) {
    q[j7] = a;
    joints_->from_configuration(q, state.get());
    SCOPED_TRACE(a);
    expect_wrapped(so2_value(), a);
    EXPECT_TRUE(compound->satisfiesBounds(state.get()));
    Eigen::VectorXd back(q.size());
    joints_->to_configuration(state.get(), back);
    EXPECT_EQ(back[j7], so2_value());
  }
  q[j7] = M_PI;
  joints_->from_configuration(q, state.get());
  EXPECT_EQ(so2_value(), -M_PI) << "pi itself maps to -pi: the range is half-open";
  q[j7] = 3.5;
  joints_->from_configuration(q, state.get());
  EXPECT_NEAR(so2_value(), 3.5 - 2 * M_PI, 1e-15);
}

TEST_F(OwnArmSpace, BoundedJointsAreNotClamped) {
  // Data sets hold values slightly outside the limits: within RobotModel::kLimitTolerance they
  // are kept, and OMPL sees them as out of bounds (planners then reject such states as starts,
  // as MoveIt does); farther out, a group value is an InputError naming the joint (a value far
  // outside would make motion checks crawl).
  Eigen::VectorXd q = fixed_;
  const double beyond = 2.9671 + 0.5 * RobotModel::kLimitTolerance;
  q[group_[0]] = beyond;
  ob::ScopedState<> state(joints_->space());
  joints_->from_configuration(q, state.get());
  Eigen::VectorXd back(q.size());
  joints_->to_configuration(state.get(), back);
  EXPECT_EQ(back[group_[0]], beyond);
  EXPECT_FALSE(joints_->space()->satisfiesBounds(state.get()));
  q[group_[0]] = 3.2;
  EXPECT_THROW(joints_->from_configuration(q, state.get()), InputError);
}

TEST_F(OwnArmSpace, InputErrors) { check_input_errors(*joints_); }

TEST_F(OwnArmSpace, OtherGroups) {
  const RobotModel& model = *robot_.model;
  EXPECT_EQ(test::names_of(model, group_variables(model, robot_.srdf, "gripper")),
            std::vector<std::string>{"finger_joint1"});
  std::vector<std::string> both = kArmJoints;
  both.push_back("finger_joint1");
  EXPECT_EQ(test::names_of(model, group_variables(model, robot_.srdf, "arm_with_gripper")), both);
  EXPECT_THROW(group_variables(model, robot_.srdf, "no_such_group"), InputError);
  // The gripper alone: one bounded real dimension, the arm held.
  const auto gripper = group_variables(model, robot_.srdf, "gripper");
  JointStateSpace g(robot_.model, gripper, fixed_);
  EXPECT_NE(std::dynamic_pointer_cast<ob::RealVectorStateSpace>(g.space()), nullptr);
  expect_urdf_bounds(model, gripper, *g.space()->as<ob::RealVectorStateSpace>());
  // Only the continuous joint: a compound of one SO2 space.
  JointStateSpace only7(robot_.model, {model.variable_index("joint7")}, fixed_);
  const auto compound = std::dynamic_pointer_cast<ob::CompoundStateSpace>(only7.space());
  ASSERT_NE(compound, nullptr);
  ASSERT_EQ(compound->getSubspaceCount(), 1u);
  EXPECT_NE(std::dynamic_pointer_cast<ob::SO2StateSpace>(compound->getSubspace(0)), nullptr);
  std::mt19937_64 rng(5);
  check_round_trips(g, rng, 20);
  check_round_trips(only7, rng, 20);
}

TEST_F(OwnArmSpace, PlanningSetupStateAndConfiguration) {
  auto checker =
      test::make_checker(robot_, read_planning_scene(test::own_arm_scene(), *robot_.model));
  PlanningSetup setup = make_planning_setup(checker, group_, fixed_);
  Eigen::VectorXd q = fixed_;
  q[group_[1]] = 0.4;
  q[group_[6]] = 4.0;
  const ob::ScopedState<> s = setup.state(q);
  const Eigen::VectorXd back = setup.configuration(s.get());
  EXPECT_EQ(back[group_[1]], 0.4);
  expect_wrapped(back[group_[6]], 4.0);
  Eigen::VectorXd bad = q;
  bad[group_[3]] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(setup.state(bad), InputError);
  EXPECT_THROW(setup.state(q.head(3)), InputError);
  EXPECT_THROW(make_planning_setup(nullptr, group_, fixed_), InputError);
  EXPECT_THROW(make_planning_setup(checker, {}, fixed_), InputError);
  EXPECT_THROW(make_planning_setup(checker, group_, fixed_, MotionChecking::kDiscrete, 0.0),
               InputError);
}

// ------------------------------------------------------------------ Panda (bounded joints only)

TEST(PandaSpace, RealVectorSpaceWithHeldFingers) {
  const auto file = test::shared_robot("panda");
  if (!file) GTEST_SKIP() << "shared robots absent";
  const LoadedRobot robot = test::load_robot(*file);
  const RobotModel& model = *robot.model;
  const std::vector<int> group = group_variables(model, robot.srdf, "panda_arm");
  EXPECT_EQ(test::names_of(model, group), kPandaJoints);
  // The fingers are held; MBM start states put them at 0.065, beyond the limit 0.04: kept.
  Eigen::VectorXd fixed = model.default_configuration();
  const int finger = model.variable_index("panda_finger_joint1");
  ASSERT_GE(finger, 0);
  EXPECT_EQ(model.variable_index("panda_finger_joint2"), -1) << "a mimic joint is no variable";
  fixed[finger] = 0.065;
  JointStateSpace joints(robot.model, group, fixed);
  EXPECT_EQ(joints.dimension(), 7);
  const auto real = std::dynamic_pointer_cast<ob::RealVectorStateSpace>(joints.space());
  ASSERT_NE(real, nullptr) << "no continuous joint: one RealVectorStateSpace";
  expect_urdf_bounds(model, group, *real);
  EXPECT_EQ(real->getBounds().low[3], -3.1416);
  EXPECT_EQ(real->getBounds().high[3], 0.0873);
  std::mt19937_64 rng(3);
  check_round_trips(joints, rng, 200);
  ob::ScopedState<> state(joints.space());
  Eigen::VectorXd q = fixed;
  q[finger] = 0.01;
  joints.from_configuration(q, state.get());
  Eigen::VectorXd back(q.size());
  joints.to_configuration(state.get(), back);
  EXPECT_EQ(back[finger], 0.065);
  check_input_errors(joints);
}

// ------------------------------------------------------------------ planning groups of real SRDFs

TEST(PlanningGroups, RealSrdfGroups) {
  struct Case {
    const char* robot;
    const char* group;
    const std::vector<std::string>* joints;
  };
  const Case cases[] = {{"panda", "panda_arm", &kPandaJoints},
                        {"mbm_panda", "panda_arm", &kPandaJoints},
                        {"ur5e", "manipulator", &kUrJoints},
                        {"mbm_ur5", "manipulator", &kUrJoints}};
  int checked = 0;
  for (const Case& c : cases) {
    const auto file = test::shared_robot(c.robot);
    if (!file) continue;
    SCOPED_TRACE(c.robot);
    const LoadedRobot robot = test::load_robot(*file);
    const std::vector<int> group = group_variables(*robot.model, robot.srdf, c.group);
    EXPECT_EQ(test::names_of(*robot.model, group), *c.joints);
    EXPECT_TRUE(std::is_sorted(group.begin(), group.end()));
    // All bounded: one real space with the URDF bounds.
    JointStateSpace joints(robot.model, group, robot.model->default_configuration());
    const auto real = std::dynamic_pointer_cast<ob::RealVectorStateSpace>(joints.space());
    ASSERT_NE(real, nullptr);
    expect_urdf_bounds(*robot.model, group, *real);
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "shared robots absent";
  EXPECT_EQ(checked, 4);
}

}  // namespace
}  // namespace hullcheck
