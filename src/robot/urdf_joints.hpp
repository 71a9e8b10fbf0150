// The joints of a URDF: types, axes, limits, and mimic joints resolved to active joints.
#pragma once

#include <urdf_model/joint.h>

#include <hullcheck/robot/robot_model.hpp>
#include <map>
#include <string>
#include <vector>

namespace hullcheck::detail {

/// What a mimic joint follows, as its <mimic> element gives it:
/// value = multiplier * value(leader) + offset.
struct MimicSpec {
  std::string leader;
  double multiplier = 1.0;
  double offset = 0.0;
};

/// The <mimic> elements of the movable joints, by joint name.
using MimicMap = std::map<std::string, MimicSpec>;

/// The joint `uj` below link `parent_link`, with its origin, type, axis, limits and velocity
/// checked; records its <mimic> (unless fixed) in `mimics`. Throws InputError prefixed with
/// `where` (e.g. "URDF 'arm.urdf'") and the joint.
Joint joint_from_urdf(const urdf::Joint& uj, int parent_link, const std::string& where,
                      MimicMap& mimics);

/// Numbers the active joints (neither fixed nor mimics) in the order of their child links in
/// `links` (depth-first): sets their Joint::variable and returns their indices in that order.
std::vector<int> number_variables(const std::vector<Link>& links, std::vector<Joint>& joints,
                                  const MimicMap& mimics);

/// Resolves each mimic joint, through chains of mimics, to the active joint at the chain's end
/// and sets its mimic_variable, multiplier and offset. Throws InputError prefixed with `where`
/// for a cycle, a mimic of no joint, or of a fixed joint.
void resolve_mimics(const MimicMap& mimics, const std::map<std::string, int>& joint_by_name,
                    std::vector<Joint>& joints, const std::string& where);

}  // namespace hullcheck::detail
