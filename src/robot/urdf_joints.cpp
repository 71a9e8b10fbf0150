#include "urdf_joints.hpp"

#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/length_checks.hpp>

#include "urdf_pose.hpp"

namespace hullcheck::detail {
namespace {

// The supported joint type of `uj`; throws for floating, planar and unknown joints.
JointType joint_type(const urdf::Joint& uj, const std::string& jwhere) {
  switch (uj.type) {
    case urdf::Joint::REVOLUTE:
      return JointType::kRevolute;
    case urdf::Joint::CONTINUOUS:
      return JointType::kContinuous;
    case urdf::Joint::PRISMATIC:
      return JointType::kPrismatic;
    case urdf::Joint::FIXED:
      return JointType::kFixed;
    case urdf::Joint::FLOATING:
      throw InputError(jwhere +
                       ": floating joints are not supported (model the free "
                       "body as a separate robot or environment object)");
    case urdf::Joint::PLANAR:
      throw InputError(jwhere + ": planar joints are not supported");
    default:
      throw InputError(jwhere + ": unknown joint type");
  }
}

// The unit <axis> of a movable joint; throws unless finite and non-zero.
Eigen::Vector3d joint_axis(const urdf::Joint& uj, const std::string& jwhere) {
  const Eigen::Vector3d axis(uj.axis.x, uj.axis.y, uj.axis.z);
  if (!axis.allFinite() || axis.norm() < 1e-12) {
    throw InputError(jwhere + ": <axis> must be a finite non-zero vector");
  }
  return axis.normalized();
}

// Sets the position limits of a revolute or prismatic joint from its required <limit>.
void set_position_limits(const urdf::Joint& uj, Joint& joint, const std::string& jwhere) {
  if (!uj.limits) throw InputError(jwhere + ": needs <limit lower upper> (revolute/prismatic)");
  joint.lower = uj.limits->lower;
  joint.upper = uj.limits->upper;
  if (!std::isfinite(joint.lower) || !std::isfinite(joint.upper) || joint.lower > joint.upper) {
    throw InputError(jwhere + ": <limit> lower must be <= upper, both finite");
  }
  const char* unit = joint.type == JointType::kRevolute ? "rad" : "m";
  check_joint_value(joint.lower, jwhere + ": <limit lower>", unit);
  check_joint_value(joint.upper, jwhere + ": <limit upper>", unit);
}

// Checks the <mimic> of a movable joint and records it in `mimics`.
void record_mimic(const urdf::JointMimic& mimic, const Joint& joint, const std::string& jwhere,
                  MimicMap& mimics) {
  check_joint_value(mimic.multiplier, jwhere + ": <mimic multiplier>", "");
  check_joint_value(mimic.offset, jwhere + ": <mimic offset>",
                    joint.type == JointType::kPrismatic ? "m" : "rad");
  mimics[joint.name] = {mimic.joint_name, mimic.multiplier, mimic.offset};
}

}  // namespace

Joint joint_from_urdf(const urdf::Joint& uj, int parent_link, const std::string& where,
                      MimicMap& mimics) {
  const std::string jwhere = where + ": joint '" + uj.name + "'";
  Joint joint;
  joint.name = uj.name;
  joint.parent_link = parent_link;
  joint.origin = to_isometry(uj.parent_to_joint_origin_transform);
  check_lengths(joint.origin.translation(), jwhere + ": <origin xyz>");
  joint.type = joint_type(uj, jwhere);
  if (joint.type != JointType::kFixed) joint.axis = joint_axis(uj, jwhere);
  if (joint.type == JointType::kRevolute || joint.type == JointType::kPrismatic) {
    set_position_limits(uj, joint, jwhere);
  }
  if (uj.limits && uj.limits->velocity > 0.0) joint.max_velocity = uj.limits->velocity;
  if (uj.mimic && joint.type != JointType::kFixed) record_mimic(*uj.mimic, joint, jwhere, mimics);
  return joint;
}

std::vector<int> number_variables(const std::vector<Link>& links, std::vector<Joint>& joints,
                                  const MimicMap& mimics) {
  std::vector<int> variable_joints;
  for (std::size_t l = 1; l < links.size(); ++l) {
    const int j = links[l].parent_joint;
    Joint& joint = joints[static_cast<std::size_t>(j)];
    if (joint.type == JointType::kFixed || mimics.count(joint.name) != 0) continue;
    joint.variable = static_cast<int>(variable_joints.size());
    variable_joints.push_back(j);
  }
  return variable_joints;
}

void resolve_mimics(const MimicMap& mimics, const std::map<std::string, int>& joint_by_name,
                    std::vector<Joint>& joints, const std::string& where) {
  for (const auto& entry : mimics) {
    const std::string& name = entry.first;
    Joint& joint = joints[static_cast<std::size_t>(joint_by_name.at(name))];
    double multiplier = 1.0;
    double offset = 0.0;
    std::string current = name;
    for (std::size_t hops = 0;; ++hops) {
      const auto m = mimics.find(current);
      if (m == mimics.end()) break;
      if (hops > mimics.size()) {
        throw InputError(where + ": joint '" + name + "': <mimic> chain forms a cycle");
      }
      const std::string& target = m->second.leader;
      const auto t = joint_by_name.find(target);
      if (t == joint_by_name.end()) {
        throw InputError(where + ": joint '" + current + "': <mimic joint='" + target +
                         "'> names no joint");
      }
      if (joints[static_cast<std::size_t>(t->second)].type == JointType::kFixed) {
        throw InputError(where + ": joint '" + current + "': mimics fixed joint '" + target + "'");
      }
      // value(current) = mul * value(target) + off; compose with what we have so far.
      offset += multiplier * m->second.offset;
      multiplier *= m->second.multiplier;
      current = target;
    }
    const Joint& leader_joint = joints[static_cast<std::size_t>(joint_by_name.at(current))];
    joint.mimic_variable = leader_joint.variable;
    joint.mimic_multiplier = multiplier;
    joint.mimic_offset = offset;
  }
}

}  // namespace hullcheck::detail
