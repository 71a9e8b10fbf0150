// MotionPlanRequest reading: values from the YAML, and clear errors for bad requests.
#include <gtest/gtest.h>

#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>
#include <string>

#include "robot_test_support.hpp"

namespace hullcheck {
namespace {

const RobotModel& arm() {
  static const RobotModel model = RobotModel::from_urdf_file(test::own_arm().urdf);
  return model;
}

// The message of the InputError `parse` throws ("" when it throws none).
std::string error_of(const std::string& yaml) {
  try {
    parse_motion_plan_request(yaml, arm(), "req.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* const kStart = R"(
start_state:
  joint_state:
    name: [joint1, joint2, virtual_joint, finger_joint2]
    position: [0.5, -0.25, 7, 0.03]
)";

TEST(MotionPlanRequest, ValuesGroupAndIgnoredNames) {
  const MotionPlanRequest r = parse_motion_plan_request(
      std::string("group_name: arm\nallowed_planning_time: 4\n") + kStart + R"(
goal_constraints:
  - joint_constraints:
      - {joint_name: joint1, position: -0.5}
      - {joint_name: finger_joint2, position: 0.01}
)",
      arm());
  EXPECT_EQ(r.group, "arm");
  EXPECT_EQ(r.allowed_planning_time, 4.0);
  Eigen::VectorXd start = arm().default_configuration();
  start[0] = 0.5;
  start[1] = -0.25;  // virtual_joint (not in the URDF) and the mimic finger_joint2 ignored
  EXPECT_EQ(r.start, start);
  Eigen::VectorXd goal = start;
  goal[0] = -0.5;  // the mimic joint's goal follows its leader, it sets nothing
  EXPECT_EQ(r.goal, goal);
  EXPECT_EQ(r.goal_variables, std::vector<int>{0});
}

TEST(MotionPlanRequest, Errors) {
  EXPECT_NE(error_of(kStart).find("request 'req.yaml': no joint-space goal"), std::string::npos);
  EXPECT_NE(error_of(std::string(kStart) + R"(
goal_constraints:
  - joint_constraints:
      - {joint_name: elbow, position: 1}
)")
                .find("goal joint 'elbow' is not a joint of robot 'hullcheck_arm'"),
            std::string::npos);
  EXPECT_NE(error_of(R"(
start_state: {joint_state: {name: [joint1, joint2], position: [1]}}
goal_constraints: [{joint_constraints: [{joint_name: joint1, position: 1}]}]
)")
                .find("name and position must be lists of equal length"),
            std::string::npos);
  EXPECT_NE(error_of(R"(
goal_constraints: [{joint_constraints: [{joint_name: joint1, position: .nan}]}]
)")
                .find("goal value of joint1 is not finite"),
            std::string::npos);
  EXPECT_NE(error_of(R"(
goal_constraints: [{joint_constraints: [{joint_name: joint1}]}]
)")
                .find("a joint constraint needs joint_name and position"),
            std::string::npos);
  EXPECT_NE(error_of("goal: [unclosed").find("request 'req.yaml': YAML error"), std::string::npos);
  try {
    read_motion_plan_request("/nonexistent/request.yaml", arm());
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("request '/nonexistent/request.yaml': cannot open file"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace hullcheck
