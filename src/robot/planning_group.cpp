#include <algorithm>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/planning_group.hpp>
#include <set>

namespace hullcheck {
namespace {

void collect(const RobotModel& model, const Srdf& srdf, const std::string& name,
             std::set<std::string>* visiting, std::set<int>* joints) {
  const SrdfGroup* group = srdf.group(name);
  if (group == nullptr) {
    std::string known;
    for (const SrdfGroup& g : srdf.groups) known += (known.empty() ? "" : ", ") + g.name;
    throw InputError("robot '" + model.name() + "': no planning group '" + name +
                     "' in the SRDF (groups: " + (known.empty() ? "none" : known) + ")");
  }
  if (!visiting->insert(name).second) {
    throw InputError("SRDF group '" + name + "': subgroups form a cycle");
  }
  const std::string where = "SRDF group '" + name + "'";
  for (const std::string& j : group->joints) {
    const int index = model.joint_index(j);
    if (index < 0) {
      // MoveIt groups often list the virtual joint; it is not part of the URDF.
      bool is_virtual = false;
      for (const SrdfVirtualJoint& v : srdf.virtual_joints) is_virtual |= v.name == j;
      if (is_virtual) continue;
      throw InputError(where + ": robot '" + model.name() + "' has no joint '" + j + "'");
    }
    joints->insert(index);
  }
  for (const std::string& l : group->links) {
    const int index = model.link_index(l);
    if (index < 0)
      throw InputError(where + ": robot '" + model.name() + "' has no link '" + l + "'");
    if (model.link(index).parent_joint >= 0) joints->insert(model.link(index).parent_joint);
  }
  for (const auto& [base, tip] : group->chains) {
    const int b = model.link_index(base);
    const int t = model.link_index(tip);
    if (b < 0 || t < 0) {
      throw InputError(where + ": chain " + base + " -> " + tip + " names a link robot '" +
                       model.name() + "' lacks");
    }
    std::vector<int> path;
    int l = t;
    while (l != b && model.link(l).parent_joint >= 0) {
      path.push_back(model.link(l).parent_joint);
      l = model.joint(model.link(l).parent_joint).parent_link;
    }
    if (l != b)
      throw InputError(where + ": chain tip '" + tip + "' is not below base '" + base + "'");
    joints->insert(path.begin(), path.end());
  }
  for (const std::string& sub : group->subgroups) collect(model, srdf, sub, visiting, joints);
  visiting->erase(name);
}

std::vector<int> variables_of(const RobotModel& model, const std::set<int>& joints) {
  std::vector<int> out;
  for (int j : joints) {
    if (model.joint(j).variable >= 0) out.push_back(model.joint(j).variable);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<int> group_variables(const RobotModel& model, const std::vector<std::string>& joints) {
  std::set<int> indices;
  for (const std::string& name : joints) {
    const int j = model.joint_index(name);
    if (j < 0) throw InputError("robot '" + model.name() + "' has no joint '" + name + "'");
    indices.insert(j);
  }
  return variables_of(model, indices);
}

std::vector<int> group_variables(const RobotModel& model, const Srdf& srdf,
                                 const std::string& group) {
  std::set<std::string> visiting;
  std::set<int> joints;
  collect(model, srdf, group, &visiting, &joints);
  return variables_of(model, joints);
}

Eigen::VectorXd group_state_configuration(const RobotModel& model, const Srdf& srdf,
                                          const std::string& group, const std::string& state,
                                          const Eigen::VectorXd& base) {
  model.check_configuration(base);
  const SrdfGroupState* s = srdf.group_state(group, state);
  if (s == nullptr) {
    throw InputError("SRDF: no group_state '" + state + "' for group '" + group + "'");
  }
  Eigen::VectorXd q = base;
  for (const auto& [joint, value] : s->joint_values) {
    const int j = model.joint_index(joint);
    if (j < 0) {
      throw InputError("SRDF group_state '" + state + "': robot '" + model.name() +
                       "' has no joint '" + joint + "'");
    }
    if (model.joint(j).variable >= 0) q[model.joint(j).variable] = value;
  }
  return q;
}

}  // namespace hullcheck
