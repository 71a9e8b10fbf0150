#include "urdf_tree.hpp"

#include <cstddef>
#include <hullcheck/core/errors.hpp>
#include <unordered_map>
#include <unordered_set>

namespace hullcheck::detail {
namespace {

// "'a', 'b', 'c'" for at most `shown` names, then ", ... (N in all)".
std::string quoted_list(const std::vector<std::string>& names, std::size_t shown = 8) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < shown; ++i) {
    if (i > 0) out += ", ";
    out += "'" + names[i] + "'";
  }
  if (names.size() > shown) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

// Throws when a name occurs twice in `names`; `kind` is "link" or "joint".
void check_unique(const std::vector<std::string>& names, const std::string& kind,
                  const std::string& where) {
  std::unordered_set<std::string> seen;
  seen.reserve(names.size());
  for (const std::string& name : names) {
    if (!seen.insert(name).second) {
      throw InputError(where + ": " + kind + " '" + name + "' is defined twice");
    }
  }
}

// Throws when a joint lacks a parent or child, or names a link that is not defined.
void check_joint_ends(const std::unordered_set<std::string>& links,
                      const std::vector<UrdfJointEdge>& joints, const std::string& where) {
  for (const UrdfJointEdge& j : joints) {
    const std::string jwhere = where + ": joint '" + j.name + "'";
    if (j.parent.empty() || j.child.empty()) {
      throw InputError(jwhere + ": needs <parent link=...> and <child link=...>");
    }
    if (links.count(j.parent) == 0) {
      throw InputError(jwhere + ": parent link '" + j.parent + "' is not defined");
    }
    if (links.count(j.child) == 0) {
      throw InputError(jwhere + ": child link '" + j.child + "' is not defined");
    }
  }
}

// Index of the joint whose child each link is; throws when a link is the child of two joints.
std::unordered_map<std::string, std::size_t> parent_joints(const std::vector<UrdfJointEdge>& joints,
                                                           const std::string& where) {
  std::unordered_map<std::string, std::size_t> parent_of;
  parent_of.reserve(joints.size());
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const auto [it, fresh] = parent_of.emplace(joints[i].child, i);
    if (!fresh) {
      throw InputError(where + ": link '" + joints[i].child + "' is the child of two joints, '" +
                       joints[it->second].name + "' and '" + joints[i].name +
                       "' (each link has at most one parent joint: the joints must form a tree)");
    }
  }
  return parent_of;
}

// The one link that is the child of no joint; throws when there is none or more than one.
std::string root_link(const std::vector<std::string>& links,
                      const std::unordered_map<std::string, std::size_t>& parent_of,
                      const std::vector<UrdfJointEdge>& joints, const std::string& where) {
  std::vector<std::string> roots;
  for (const std::string& link : links) {
    if (parent_of.count(link) == 0) roots.push_back(link);
  }
  if (roots.size() > 1) {
    throw InputError(where + ": " + std::to_string(roots.size()) +
                     " root links (links that are the child of no joint): " + quoted_list(roots) +
                     "; the joints must connect every link to one root");
  }
  if (roots.empty()) {
    std::vector<std::string> names;
    for (const UrdfJointEdge& j : joints) names.push_back(j.name);
    throw InputError(where + ": no root link (every link is the child of a joint), so joints " +
                     quoted_list(names) + " form a cycle");
  }
  return roots.front();
}

// Throws when some link cannot be reached from `root` through the joints (it is then on or
// below a cycle of joints detached from the root).
void check_reachable(const std::string& root, const std::vector<std::string>& links,
                     const std::unordered_map<std::string, std::size_t>& parent_of,
                     const std::vector<UrdfJointEdge>& joints, const std::string& where) {
  std::unordered_map<std::string, std::vector<std::size_t>> children;
  children.reserve(links.size());
  for (std::size_t i = 0; i < joints.size(); ++i) children[joints[i].parent].push_back(i);
  std::unordered_set<std::string> reached{root};
  std::vector<std::string> todo{root};
  while (!todo.empty()) {
    const std::string link = std::move(todo.back());
    todo.pop_back();
    const auto it = children.find(link);
    if (it == children.end()) continue;
    for (std::size_t j : it->second) {
      if (reached.insert(joints[j].child).second) todo.push_back(joints[j].child);
    }
  }
  if (reached.size() == links.size()) return;
  std::vector<std::string> lost_links;
  std::vector<std::string> lost_joints;
  for (const std::string& link : links) {
    if (reached.count(link) != 0) continue;
    lost_links.push_back(link);
    lost_joints.push_back(joints[parent_of.at(link)].name);
  }
  throw InputError(where + ": links " + quoted_list(lost_links) +
                   " are not reachable from root link '" + root + "': their parent joints " +
                   quoted_list(lost_joints) + " form a cycle");
}

}  // namespace

void check_joint_tree(const std::vector<std::string>& links,
                      const std::vector<UrdfJointEdge>& joints, const std::string& where) {
  // Without links, or with unnamed elements, urdfdom's own reason is the clearer one.
  if (links.empty()) return;
  for (const std::string& link : links) {
    if (link.empty()) return;
  }
  for (const UrdfJointEdge& j : joints) {
    if (j.name.empty()) return;
  }
  check_unique(links, "link", where);
  std::vector<std::string> joint_names;
  joint_names.reserve(joints.size());
  for (const UrdfJointEdge& j : joints) joint_names.push_back(j.name);
  check_unique(joint_names, "joint", where);
  const std::unordered_set<std::string> link_set(links.begin(), links.end());
  check_joint_ends(link_set, joints, where);
  const auto parent_of = parent_joints(joints, where);
  const std::string root = root_link(links, parent_of, joints, where);
  check_reachable(root, links, parent_of, joints, where);
}

}  // namespace hullcheck::detail
