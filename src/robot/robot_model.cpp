#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <sstream>
#include <utility>

#include "urdf_collision.hpp"
#include "urdf_joints.hpp"
#include "urdf_messages.hpp"
#include "urdf_tree.hpp"

namespace hullcheck {
namespace {

// The <link> names and <joint> edges of <robot>, in file order; throws on malformed XML.
struct UrdfGraph {
  std::vector<std::string> links;
  std::vector<detail::UrdfJointEdge> joints;
};

// The `name` attribute of the first <tag> child of `e` (for <parent>/<child>: `link`).
std::string child_attribute(const tinyxml2::XMLElement& e, const char* tag, const char* attr) {
  const tinyxml2::XMLElement* c = e.FirstChildElement(tag);
  const char* value = c == nullptr ? nullptr : c->Attribute(attr);
  return value == nullptr ? "" : value;
}

// The link names and joint edges of the URDF text, read with tinyxml2 (no urdfdom yet).
UrdfGraph graph_in_file(const std::string& xml, const std::string& source) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw InputError("URDF '" + source + "': malformed XML: " + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) {
    throw InputError("URDF '" + source + "': no <robot> root element");
  }
  UrdfGraph graph;
  for (const tinyxml2::XMLElement* l = robot->FirstChildElement("link"); l != nullptr;
       l = l->NextSiblingElement("link")) {
    const char* name = l->Attribute("name");
    graph.links.emplace_back(name == nullptr ? "" : name);
  }
  for (const tinyxml2::XMLElement* j = robot->FirstChildElement("joint"); j != nullptr;
       j = j->NextSiblingElement("joint")) {
    const char* name = j->Attribute("name");
    graph.joints.push_back({name == nullptr ? "" : name, child_attribute(*j, "parent", "link"),
                            child_attribute(*j, "child", "link")});
  }
  return graph;
}

// The link/joint graph of the URDF text, checked to be one tree. Before urdfdom builds its link
// pointers: the walk of the tree needs one (a cycle would make it endless, a detached one would
// drop links silently).
UrdfGraph checked_graph(const std::string& xml, const std::string& source,
                        const std::string& where) {
  UrdfGraph graph = graph_in_file(xml, source);
  detail::check_joint_tree(graph.links, graph.joints, where);
  return graph;
}

// Throws unless `padding` is finite and >= 0; `what` names it in the message.
void check_padding(const std::string& what, double padding) {
  if (!std::isfinite(padding) || padding < 0.0) {
    std::ostringstream msg;
    msg << what << ": padding must be finite and >= 0 (got " << padding << ")";
    throw InputError(msg.str());
  }
}

// urdfdom's model of the URDF text; throws with urdfdom's own messages when it fails.
urdf::ModelInterfaceSharedPtr parse_urdf(const std::string& xml, const std::string& where) {
  urdf::ModelInterfaceSharedPtr urdf;
  std::string parse_messages = detail::capture_urdf_messages([&] {
    try {
      urdf = urdf::parseURDF(xml);
    } catch (const std::exception& e) {
      urdf.reset();
      throw InputError(where + ": not a valid URDF: " + e.what());
    }
  });
  if (!urdf || !urdf->getRoot()) {
    throw InputError(where + ": not a valid URDF: " +
                     (parse_messages.empty() ? "urdfdom gave no reason" : parse_messages));
  }
  return urdf;
}

// The position of each joint name in the file, for ordering children as the file does.
class JointRank {
 public:
  explicit JointRank(const std::vector<detail::UrdfJointEdge>& joints) {
    for (std::size_t i = 0; i < joints.size(); ++i) rank_.emplace(joints[i].name, i);
  }
  // The joint's position in the file (0 for a name the file does not have).
  std::size_t operator()(const std::string& name) const {
    const auto it = rank_.find(name);
    return it == rank_.end() ? 0 : it->second;
  }

 private:
  std::map<std::string, std::size_t> rank_;
};

// The links and joints of a URDF in depth-first order, with their name indices and mimics.
struct KinematicTree {
  std::vector<Link> links;
  std::vector<Joint> joints;
  std::map<std::string, int> link_by_name;
  std::map<std::string, int> joint_by_name;
  detail::MimicMap mimics;
};

// Appends `ulink` (child of joint `parent_joint`, -1 for the root) with its collision shapes
// to `tree`; returns its index.
int add_link(const urdf::Link& ulink, int parent_joint, detail::CollisionLoader& loader,
             KinematicTree& tree) {
  Link link;
  link.name = ulink.name;
  link.parent_joint = parent_joint;
  link.shapes = loader.link_shapes(ulink);
  const int link_id = static_cast<int>(tree.links.size());
  if (parent_joint >= 0) tree.joints[static_cast<std::size_t>(parent_joint)].child_link = link_id;
  tree.link_by_name[link.name] = link_id;
  tree.links.push_back(std::move(link));
  return link_id;
}

// Appends `joint` to `tree` as a child joint of its parent link; returns its index.
int add_joint(Joint joint, KinematicTree& tree) {
  const int joint_id = static_cast<int>(tree.joints.size());
  const std::size_t parent = static_cast<std::size_t>(joint.parent_link);
  tree.joint_by_name[joint.name] = joint_id;
  tree.joints.push_back(std::move(joint));
  tree.links[parent].child_joints.push_back(joint_id);
  return joint_id;
}

// The links and joints of `urdf` depth-first from the root, the children of a link in file
// order; each link's shapes are made before its child joints are read.
KinematicTree walk_tree(const urdf::ModelInterface& urdf, const JointRank& rank,
                        detail::CollisionLoader& loader, const std::string& where) {
  KinematicTree tree;
  std::vector<std::pair<urdf::LinkConstSharedPtr, int>> stack{{urdf.getRoot(), -1}};
  while (!stack.empty()) {
    const urdf::LinkConstSharedPtr ulink = stack.back().first;
    const int parent_joint = stack.back().second;
    stack.pop_back();
    const int link_id = add_link(*ulink, parent_joint, loader, tree);

    std::vector<urdf::JointSharedPtr> children = ulink->child_joints;
    std::sort(children.begin(), children.end(),
              [&](const auto& a, const auto& b) { return rank(a->name) < rank(b->name); });
    // Push in reverse so that the first child in the file is visited first.
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      const urdf::Joint& uj = **it;
      const int joint_id =
          add_joint(detail::joint_from_urdf(uj, link_id, where, tree.mimics), tree);
      const urdf::LinkConstSharedPtr child = urdf.getLink(uj.child_link_name);
      if (!child) {
        throw InputError(where + ": joint '" + uj.name + "': child link '" + uj.child_link_name +
                         "' not found");
      }
      stack.emplace_back(child, joint_id);
    }
  }
  return tree;
}

// Child joint lists were filled in reverse push order; restores file order.
void sort_child_joints(const JointRank& rank, const std::vector<Joint>& joints,
                       std::vector<Link>& links) {
  for (Link& link : links) {
    std::sort(link.child_joints.begin(), link.child_joints.end(), [&](int a, int b) {
      return rank(joints[static_cast<std::size_t>(a)].name) <
             rank(joints[static_cast<std::size_t>(b)].name);
    });
  }
}

// The per-link paddings of `options`, checked: known links, finite and >= 0.
std::map<std::string, double> checked_link_padding(const RobotLoadOptions& options,
                                                   const std::map<std::string, int>& link_by_name,
                                                   const std::string& where) {
  std::map<std::string, double> out;
  for (const auto& [link_name, padding] : options.link_padding) {
    if (link_by_name.count(link_name) == 0) {
      throw InputError(where + ": padding given for unknown link '" + link_name + "'");
    }
    check_padding(where + ": link '" + link_name + "'", padding);
    out[link_name] = padding;
  }
  return out;
}

}  // namespace

RobotModel RobotModel::from_urdf_file(const std::string& path, const RobotLoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("URDF '" + path + "': cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return from_urdf_string(text.str(), dir.empty() ? "." : dir, options, path);
}

RobotModel RobotModel::from_urdf_string(const std::string& xml, const std::string& base_dir,
                                        const RobotLoadOptions& options,
                                        const std::string& source_name) {
  const std::string where = "URDF '" + source_name + "'";
  const UrdfGraph graph = checked_graph(xml, source_name, where);
  check_padding(where + ": default", options.default_padding);
  // A package folder that does not exist is a mistake (a typo, a missing checkout): it would
  // otherwise be passed over silently for the environment's folders.
  for (const auto& [package, folder] : options.packages) {
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error)) {
      throw InputError(where + ": package '" + package + "' maps to '" + folder +
                       "', which is not a folder");
    }
  }
  const urdf::ModelInterfaceSharedPtr urdf = parse_urdf(xml, where);

  RobotModel model;
  model.name_ = urdf->getName();
  model.source_ = source_name;
  model.default_padding_ = options.default_padding;

  const JointRank rank(graph.joints);
  detail::CollisionLoader loader(source_name, base_dir, options);
  KinematicTree tree = walk_tree(*urdf, rank, loader, where);
  sort_child_joints(rank, tree.joints, tree.links);
  model.variable_joints_ = detail::number_variables(tree.links, tree.joints, tree.mimics);
  detail::resolve_mimics(tree.mimics, tree.joint_by_name, tree.joints, where);
  model.links_ = std::move(tree.links);
  model.joints_ = std::move(tree.joints);
  model.link_by_name_ = std::move(tree.link_by_name);
  model.joint_by_name_ = std::move(tree.joint_by_name);
  model.link_padding_ = checked_link_padding(options, model.link_by_name_, where);
  model.apply_padding();
  model.build_kinematics();
  return model;
}

std::vector<int> RobotModel::links_with_geometry() const {
  std::vector<int> out;
  for (int l = 0; l < static_cast<int>(links_.size()); ++l) {
    if (!links_[static_cast<std::size_t>(l)].shapes.empty()) out.push_back(l);
  }
  return out;
}

int RobotModel::link_index(const std::string& name) const {
  const auto it = link_by_name_.find(name);
  return it == link_by_name_.end() ? -1 : it->second;
}

int RobotModel::joint_index(const std::string& name) const {
  const auto it = joint_by_name_.find(name);
  return it == joint_by_name_.end() ? -1 : it->second;
}

std::vector<std::string> RobotModel::variable_names() const {
  std::vector<std::string> names;
  names.reserve(variable_joints_.size());
  for (int j : variable_joints_) names.push_back(joints_[static_cast<std::size_t>(j)].name);
  return names;
}

int RobotModel::variable_index(const std::string& name) const {
  const int j = joint_index(name);
  return j < 0 ? -1 : joints_[static_cast<std::size_t>(j)].variable;
}

Eigen::VectorXd RobotModel::lower_limits() const {
  Eigen::VectorXd out(variable_count());
  for (int i = 0; i < variable_count(); ++i) out[i] = joint(variable_joint(i)).lower;
  return out;
}

Eigen::VectorXd RobotModel::upper_limits() const {
  Eigen::VectorXd out(variable_count());
  for (int i = 0; i < variable_count(); ++i) out[i] = joint(variable_joint(i)).upper;
  return out;
}

Eigen::VectorXd RobotModel::default_configuration() const {
  Eigen::VectorXd out(variable_count());
  for (int i = 0; i < variable_count(); ++i) {
    const Joint& j = joint(variable_joint(i));
    // MoveIt's default: 0 when within the limits, else the middle of the range.
    out[i] = (j.lower <= 0.0 && 0.0 <= j.upper) ? 0.0 : 0.5 * (j.lower + j.upper);
  }
  return out;
}

void RobotModel::set_link_padding(const std::string& link, double padding) {
  if (link_index(link) < 0) {
    throw InputError("robot '" + name_ + "': set_link_padding: unknown link '" + link + "'");
  }
  check_padding("robot '" + name_ + "': link '" + link + "'", padding);
  link_padding_[link] = padding;
  apply_padding();
  ++padding_revision_;
}

void RobotModel::set_default_padding(double padding) {
  check_padding("robot '" + name_ + "': default", padding);
  default_padding_ = padding;
  apply_padding();
  ++padding_revision_;
}

void RobotModel::apply_padding() {
  for (Link& link : links_) {
    const auto it = link_padding_.find(link.name);
    link.padding = it == link_padding_.end() ? default_padding_ : it->second;
    for (std::size_t k = 0; k < link.shapes.size(); ++k) {
      CollisionShape& s = link.shapes[k];
      s.shape = link.padding > 0.0 ? s.unpadded.inflated(link.padding) : s.unpadded;
      if (s.element_hull_unpadded && s.piece > 0) {
        s.element_hull = link.shapes[k - 1].element_hull;  // the element's, made at piece 0
      } else if (s.element_hull_unpadded) {
        const Shape hull(*s.element_hull_unpadded);
        s.element_hull =
            std::make_shared<const Shape>(link.padding > 0.0 ? hull.inflated(link.padding) : hull);
      }
      if (s.unpadded.kind() == ShapeKind::kConvexHull) {
        const ConvexHull& hull = std::get<ConvexHull>(s.unpadded.geometry());
        s.bounding_center = hull.bounding_ball_center();
        s.bounding_radius = hull.bounding_ball_radius() + s.shape.margin();
      } else {
        s.bounding_center.setZero();
        s.bounding_radius = s.shape.bounding_radius();
      }
    }
  }
}

}  // namespace hullcheck
