#include <yaml-cpp/yaml.h>

#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/motion_plan_request.hpp>

namespace hullcheck {
namespace {

MotionPlanRequest read(const YAML::Node& root, const RobotModel& model, const std::string& source) {
  const std::string where = "request '" + source + "'";
  if (!root.IsMap()) throw InputError(where + ": not a YAML map (a moveit_msgs/MotionPlanRequest)");
  MotionPlanRequest request;
  if (root["group_name"]) request.group = root["group_name"].as<std::string>();
  if (root["allowed_planning_time"]) {
    request.allowed_planning_time = root["allowed_planning_time"].as<double>();
  }
  const auto finite = [&](double v, const std::string& what) {
    if (!std::isfinite(v)) throw InputError(where + ": " + what + " is not finite");
    return v;
  };
  request.start = model.default_configuration();
  const YAML::Node js = root["start_state"] ? root["start_state"]["joint_state"] : YAML::Node();
  if (js && js["name"]) {
    const YAML::Node names = js["name"];
    const YAML::Node positions = js["position"];
    if (!names.IsSequence() || !positions || !positions.IsSequence() ||
        names.size() != positions.size()) {
      throw InputError(where +
                       ": start_state.joint_state name and position must be lists of "
                       "equal length");
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string name = names[i].as<std::string>();
      const int v = model.variable_index(name);
      if (v >= 0) request.start[v] = finite(positions[i].as<double>(), "start value of " + name);
    }
  }
  request.goal = request.start;
  const YAML::Node goals = root["goal_constraints"];
  if (!goals || !goals.IsSequence() || goals.size() == 0 || !goals[0]["joint_constraints"] ||
      goals[0]["joint_constraints"].size() == 0) {
    throw InputError(where + ": no joint-space goal (goal_constraints[0].joint_constraints)");
  }
  for (const YAML::Node& c : goals[0]["joint_constraints"]) {
    if (!c["joint_name"] || !c["position"]) {
      throw InputError(where + ": a joint constraint needs joint_name and position");
    }
    const std::string name = c["joint_name"].as<std::string>();
    const int j = model.joint_index(name);
    if (j < 0) {
      throw InputError(where + ": goal joint '" + name + "' is not a joint of robot '" +
                       model.name() + "'");
    }
    const int v = model.joint(j).variable;
    if (v < 0) continue;  // mimic or fixed: follows
    request.goal[v] = finite(c["position"].as<double>(), "goal value of " + name);
    request.goal_variables.push_back(v);
  }
  return request;
}

}  // namespace

MotionPlanRequest parse_motion_plan_request(const std::string& yaml, const RobotModel& model,
                                            const std::string& source_name) {
  try {
    return read(YAML::Load(yaml), model, source_name);
  } catch (const YAML::Exception& e) {
    throw InputError("request '" + source_name + "': YAML error: " + e.what());
  }
}

MotionPlanRequest read_motion_plan_request(const std::string& path, const RobotModel& model) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError("request '" + path + "': cannot open file");
  } catch (const YAML::Exception& e) {
    throw InputError("request '" + path + "': YAML error: " + e.what());
  }
  try {
    return read(root, model, path);
  } catch (const YAML::Exception& e) {
    throw InputError("request '" + path + "': " + e.what());
  }
}

}  // namespace hullcheck
