// MoveIt SRDF (semantic robot description): planning groups, named states, collision pairs.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace hullcheck {

/// A planning group: its joints, links, kinematic chains and subgroups, as listed.
struct SrdfGroup {
  std::string name;
  std::vector<std::string> joints;
  std::vector<std::string> links;
  std::vector<std::pair<std::string, std::string>> chains;  // (base_link, tip_link)
  std::vector<std::string> subgroups;
};

/// A named configuration of a group (<group_state>): joint name -> value (rad or m).
struct SrdfGroupState {
  std::string name;
  std::string group;
  std::vector<std::pair<std::string, double>> joint_values;
};

/// A link pair whose collisions are not checked, with MoveIt's reason ("Adjacent", "Never",
/// "Default", "Always", "User", ...).
struct SrdfLinkPair {
  std::string link1;
  std::string link2;
  std::string reason;
};

/// An end effector: a group attached to a parent link (of an optional parent group).
struct SrdfEndEffector {
  std::string name;
  std::string group;
  std::string parent_link;
  std::string parent_group;
};

/// A virtual joint: how the robot's root link attaches to a frame outside it (MoveIt).
struct SrdfVirtualJoint {
  std::string name;
  std::string type;  // "fixed", "floating", "planar"
  std::string parent_frame;
  std::string child_link;
};

/// The contents of an SRDF file. Elements hullcheck does not use (passive joints, sphere
/// approximations) are skipped.
struct Srdf {
  std::string robot_name;
  std::vector<SrdfVirtualJoint> virtual_joints;
  std::vector<SrdfGroup> groups;
  std::vector<SrdfGroupState> group_states;
  std::vector<SrdfEndEffector> end_effectors;
  std::vector<SrdfLinkPair> disabled_collisions;
  /// Pairs re-enabled by <enable_collisions> (newer MoveIt), applied after the disables.
  std::vector<SrdfLinkPair> enabled_collisions;
  /// Links whose collisions with every other link are disabled (<disable_default_collisions>).
  std::vector<std::string> disabled_links;

  /// The group called `name`, or nullptr.
  const SrdfGroup* group(const std::string& name) const;
  /// The group state called `name` of group `group`, or nullptr.
  const SrdfGroupState* group_state(const std::string& group, const std::string& name) const;
};

/// Parses an SRDF file / text. Throws InputError naming the source, the element and the
/// problem: malformed XML, root not <robot>, a required attribute missing, a joint value that
/// is not a number.
Srdf read_srdf_file(const std::string& path);
Srdf parse_srdf(const std::string& xml, const std::string& source_name = "<srdf string>");

/// SRDF text for `srdf` (every element this struct holds), readable by MoveIt. Joint values
/// are written with the fewest digits that read back exactly. `comment`, when not empty, is
/// placed as an XML comment right after the XML declaration.
std::string write_srdf(const Srdf& srdf, const std::string& comment = "");

}  // namespace hullcheck
