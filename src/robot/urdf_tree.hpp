// Checks that the joints of a URDF connect its links into one tree, before anything walks it.
#pragma once

#include <string>
#include <vector>

namespace hullcheck::detail {

/// One <joint> element as the file gives it: its name and the names of its parent and child
/// links (empty when the element lacks them).
struct UrdfJointEdge {
  std::string name;
  std::string parent;
  std::string child;
};

/// Throws InputError, prefixed with `where` (e.g. "URDF 'arm.urdf'"), unless `links` (link
/// names in file order) and `joints` form one tree: names unique, every joint naming defined
/// links, every link the child of at most one joint, exactly one root link (the child of no
/// joint), and every link reachable from it (so no cycle). The message names the links and
/// joints at fault. Linear in the number of links and joints; never recurses.
void check_joint_tree(const std::vector<std::string>& links,
                      const std::vector<UrdfJointEdge>& joints, const std::string& where);

}  // namespace hullcheck::detail
