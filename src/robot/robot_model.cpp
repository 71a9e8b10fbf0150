#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/decomposition_cache.hpp>
#include <hullcheck/robot/length_checks.hpp>
#include <hullcheck/robot/mesh_file.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <sstream>
#include <tuple>

#include "urdf_messages.hpp"
#include "urdf_tree.hpp"

namespace hullcheck {
namespace {

Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  const double norm = q.norm();
  if (norm > 0.0) q.coeffs() /= norm;
  out.linear() = q.toRotationMatrix();
  out.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return out;
}

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

void check_padding(const std::string& what, double padding) {
  if (!std::isfinite(padding) || padding < 0.0) {
    std::ostringstream msg;
    msg << what << ": padding must be finite and >= 0 (got " << padding << ")";
    throw InputError(msg.str());
  }
}

// The distinct points, in the order of their first occurrence. Mesh files repeat a vertex for
// every triangle using it (binary STL about 6 times), and qhull's time grows with its input,
// duplicates included: removing them first halves the hull time of a large STL.
std::vector<Eigen::Vector3d> distinct_points(const std::vector<Eigen::Vector3d>& points) {
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto key = [&](std::size_t i) {
    return std::make_tuple(points[i].x(), points[i].y(), points[i].z(), i);
  };
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  std::vector<char> keep(points.size(), 0);
  for (std::size_t k = 0; k < order.size(); ++k) {
    keep[order[k]] = k == 0 || points[order[k]] != points[order[k - 1]];
  }
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (keep[i]) out.push_back(points[i]);
  }
  return out;
}

// The URDF element name of a geometry type.
const char* geometry_tag(int type) {
  switch (type) {
    case urdf::Geometry::SPHERE:
      return "sphere";
    case urdf::Geometry::BOX:
      return "box";
    case urdf::Geometry::CYLINDER:
      return "cylinder";
    case urdf::Geometry::MESH:
      return "mesh";
    default:
      return "geometry";
  }
}

// Throws unless every vertex coordinate is within the loaders' length range (m).
void check_mesh_extent(const std::vector<Eigen::Vector3d>& vertices, const std::string& what) {
  for (const Eigen::Vector3d& v : vertices) {
    if (v.array().abs().maxCoeff() > kMaxLoadedLength) {
      check_lengths(v, what + ": vertex");
    }
  }
}

struct MeshKey {
  std::string path;
  double sx, sy, sz;
  bool operator<(const MeshKey& o) const {
    return std::tie(path, sx, sy, sz) < std::tie(o.path, o.sx, o.sy, o.sz);
  }
};

// A mesh file's convex shapes (one hull, or the pieces of its decomposition).
struct MeshShapes {
  std::vector<ConvexHull> hulls;
  std::shared_ptr<const ConvexHull> hull_of_pieces;  // when there are several
  std::size_t vertex_count;
  double excess;  // CollisionShape::mesh_excess
};

class Loader {
 public:
  Loader(const std::string& source, const std::string& base_dir, const RobotLoadOptions& options)
      : source_(source), base_dir_(base_dir), options_(options) {}

  // The shapes of `link_name`'s <collision> element number `element`: one, or one per piece
  // of a decomposed mesh.
  std::vector<CollisionShape> make_shapes(const urdf::Collision& collision,
                                          const std::string& link_name, int element) {
    const std::string where = "URDF '" + source_ + "': link '" + link_name + "'";
    if (!collision.geometry) throw InputError(where + ": <collision> without <geometry>");
    CollisionShape out{Sphere(0.0),
                       Sphere(0.0),
                       Eigen::Isometry3d::Identity(),
                       Eigen::Vector3d::Zero(),
                       0.0,
                       std::string(),
                       0};
    out.element = element;
    out.origin = to_isometry(collision.origin);
    check_lengths(out.origin.translation(), where + ": <collision><origin xyz>");
    const urdf::Geometry& g = *collision.geometry;
    try {
      switch (g.type) {
        case urdf::Geometry::SPHERE: {
          const auto& s = static_cast<const urdf::Sphere&>(g);
          check_length(s.radius, where + ": <sphere radius>");
          out.unpadded = Sphere(s.radius);
          out.source = "sphere";
          break;
        }
        case urdf::Geometry::BOX: {
          const auto& b = static_cast<const urdf::Box&>(g);
          check_lengths(Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z), where + ": <box size>");
          out.unpadded = Box(b.dim.x, b.dim.y, b.dim.z);
          out.source = "box";
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& c = static_cast<const urdf::Cylinder&>(g);
          check_length(c.radius, where + ": <cylinder radius>");
          check_length(c.length, where + ": <cylinder length>");
          out.unpadded = Cylinder(c.radius, c.length);
          out.source = "cylinder";
          break;
        }
        case urdf::Geometry::MESH: {
          const auto& m = static_cast<const urdf::Mesh&>(g);
          const std::string path =
              resolve_resource_path(m.filename, base_dir_, options_.packages, where);
          const MeshShapes& mesh =
              mesh_shapes(path, Eigen::Vector3d(m.scale.x, m.scale.y, m.scale.z), where);
          out.mesh_vertex_count = mesh.vertex_count;
          out.mesh_excess = mesh.excess;
          out.source = path;
          out.piece_count = static_cast<int>(mesh.hulls.size());
          out.element_hull_unpadded = mesh.hull_of_pieces;
          std::vector<CollisionShape> pieces;
          for (std::size_t k = 0; k < mesh.hulls.size(); ++k) {
            out.unpadded = mesh.hulls[k];
            out.piece = static_cast<int>(k);
            pieces.push_back(out);
          }
          return pieces;
        }
        default:
          throw InputError("unknown geometry type");
      }
    } catch (const InputError& e) {
      // The loader's own errors carry the prefix already; the Shape constructors' get it once,
      // with the element.
      const std::string what = e.what();
      if (what.rfind("URDF '", 0) == 0) throw;
      throw InputError(where + ": <" + geometry_tag(g.type) + ">: " + what);
    }
    return {out};
  }

 private:
  // The convex shapes of the mesh file at `path` scaled by `scale`, read (and decomposed) once
  // per file and scale.
  const MeshShapes& mesh_shapes(const std::string& path, const Eigen::Vector3d& scale,
                                const std::string& where) {
    const MeshKey key{path, scale.x(), scale.y(), scale.z()};
    auto it = meshes_.find(key);
    if (it != meshes_.end()) return it->second;
    const std::string what = where + ": mesh '" + path + "' (after <mesh scale>)";
    MeshShapes shapes{{}, nullptr, 0, -1.0};
    if (options_.mesh_geometry == MeshGeometry::kHull) {
      const std::vector<Eigen::Vector3d> vertices =
          read_mesh_vertices(path, scale, options_.mesh_limits);
      check_mesh_extent(vertices, what);
      shapes.hulls.emplace_back(distinct_points(vertices));
      shapes.vertex_count = vertices.size();
    } else {
      const std::string cache_dir = !options_.use_decomposition_cache ? std::string()
                                    : options_.decomposition_cache_dir.empty()
                                        ? default_decomposition_cache_dir()
                                        : options_.decomposition_cache_dir;
      const MeshDecomposition d = decompose_mesh_file(
          path, scale, options_.decomposition, options_.mesh_limits, cache_dir,
          [&](const TriangleMesh& mesh) { check_mesh_extent(mesh.vertices, what); });
      for (const auto& piece : d.decomposition.pieces) {
        check_mesh_extent(piece, what);  // a cached entry's points, checked like a mesh's
        shapes.hulls.emplace_back(piece);
      }
      shapes.vertex_count = d.vertex_count;
      shapes.excess = d.decomposition.bound;
      if (shapes.hulls.size() > 1) {
        std::vector<Eigen::Vector3d> all;
        for (const ConvexHull& h : shapes.hulls) {
          all.insert(all.end(), h.vertices().begin(), h.vertices().end());
        }
        shapes.hull_of_pieces = std::make_shared<const ConvexHull>(distinct_points(all));
      }
    }
    return meshes_.emplace(key, std::move(shapes)).first->second;
  }

  std::string source_;
  std::string base_dir_;
  const RobotLoadOptions& options_;
  std::map<MeshKey, MeshShapes> meshes_;
};

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
  const UrdfGraph graph = graph_in_file(xml, source_name);
  // Before urdfdom builds its link pointers: the walk below needs a tree (a cycle would make
  // it endless, a detached one would drop links silently).
  detail::check_joint_tree(graph.links, graph.joints, where);
  check_padding(where + ": default", options.default_padding);

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

  RobotModel model;
  model.name_ = urdf->getName();
  model.source_ = source_name;
  model.default_padding_ = options.default_padding;

  std::map<std::string, std::size_t> file_rank;
  for (std::size_t i = 0; i < graph.joints.size(); ++i) file_rank.emplace(graph.joints[i].name, i);

  // Depth-first traversal from the root; children in file order.
  Loader loader(source_name, base_dir, options);
  std::vector<std::pair<urdf::LinkConstSharedPtr, int>> stack{{urdf->getRoot(), -1}};
  std::map<std::string, std::pair<std::string, urdf::JointMimicSharedPtr>> mimics;
  while (!stack.empty()) {
    const urdf::LinkConstSharedPtr ulink = stack.back().first;
    const int parent_joint = stack.back().second;
    stack.pop_back();
    Link link;
    link.name = ulink->name;
    link.parent_joint = parent_joint;
    int element = 0;
    for (const urdf::CollisionSharedPtr& c : ulink->collision_array) {
      if (!c) continue;
      for (CollisionShape& shape : loader.make_shapes(*c, ulink->name, element)) {
        link.shapes.push_back(std::move(shape));
      }
      ++element;
    }
    const int link_id = static_cast<int>(model.links_.size());
    if (parent_joint >= 0)
      model.joints_[static_cast<std::size_t>(parent_joint)].child_link = link_id;
    model.link_by_name_[link.name] = link_id;
    model.links_.push_back(std::move(link));

    std::vector<urdf::JointSharedPtr> children = ulink->child_joints;
    std::sort(children.begin(), children.end(), [&](const auto& a, const auto& b) {
      return file_rank[a->name] < file_rank[b->name];
    });
    // Push in reverse so that the first child in the file is visited first.
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      const urdf::Joint& uj = **it;
      const std::string jwhere = where + ": joint '" + uj.name + "'";
      Joint joint;
      joint.name = uj.name;
      joint.parent_link = link_id;
      joint.origin = to_isometry(uj.parent_to_joint_origin_transform);
      check_lengths(joint.origin.translation(), jwhere + ": <origin xyz>");
      switch (uj.type) {
        case urdf::Joint::REVOLUTE:
          joint.type = JointType::kRevolute;
          break;
        case urdf::Joint::CONTINUOUS:
          joint.type = JointType::kContinuous;
          break;
        case urdf::Joint::PRISMATIC:
          joint.type = JointType::kPrismatic;
          break;
        case urdf::Joint::FIXED:
          joint.type = JointType::kFixed;
          break;
        case urdf::Joint::FLOATING:
          throw InputError(jwhere +
                           ": floating joints are not supported (model the free "
                           "body as a separate robot or environment object)");
        case urdf::Joint::PLANAR:
          throw InputError(jwhere + ": planar joints are not supported");
        default:
          throw InputError(jwhere + ": unknown joint type");
      }
      if (joint.type != JointType::kFixed) {
        const Eigen::Vector3d axis(uj.axis.x, uj.axis.y, uj.axis.z);
        if (!axis.allFinite() || axis.norm() < 1e-12) {
          throw InputError(jwhere + ": <axis> must be a finite non-zero vector");
        }
        joint.axis = axis.normalized();
      }
      if (joint.type == JointType::kRevolute || joint.type == JointType::kPrismatic) {
        if (!uj.limits)
          throw InputError(jwhere + ": needs <limit lower upper> (revolute/prismatic)");
        joint.lower = uj.limits->lower;
        joint.upper = uj.limits->upper;
        if (!std::isfinite(joint.lower) || !std::isfinite(joint.upper) ||
            joint.lower > joint.upper) {
          throw InputError(jwhere + ": <limit> lower must be <= upper, both finite");
        }
        const char* unit = joint.type == JointType::kRevolute ? "rad" : "m";
        check_joint_value(joint.lower, jwhere + ": <limit lower>", unit);
        check_joint_value(joint.upper, jwhere + ": <limit upper>", unit);
      }
      if (uj.limits && uj.limits->velocity > 0.0) joint.max_velocity = uj.limits->velocity;
      if (uj.mimic && joint.type != JointType::kFixed) {
        check_joint_value(uj.mimic->multiplier, jwhere + ": <mimic multiplier>", "");
        check_joint_value(uj.mimic->offset, jwhere + ": <mimic offset>",
                          joint.type == JointType::kPrismatic ? "m" : "rad");
        mimics[joint.name] = {uj.mimic->joint_name, uj.mimic};
      }
      const int joint_id = static_cast<int>(model.joints_.size());
      model.joint_by_name_[joint.name] = joint_id;
      model.joints_.push_back(std::move(joint));
      model.links_[static_cast<std::size_t>(link_id)].child_joints.push_back(joint_id);
      const urdf::LinkConstSharedPtr child = urdf->getLink(uj.child_link_name);
      if (!child) throw InputError(jwhere + ": child link '" + uj.child_link_name + "' not found");
      stack.emplace_back(child, joint_id);
    }
  }
  // Child joint lists were filled in reverse push order; restore file order.
  for (Link& link : model.links_) {
    std::sort(link.child_joints.begin(), link.child_joints.end(), [&](int a, int b) {
      return file_rank[model.joints_[static_cast<std::size_t>(a)].name] <
             file_rank[model.joints_[static_cast<std::size_t>(b)].name];
    });
  }

  // Active joints in depth-first order of their child links (links_ is in that order).
  for (std::size_t l = 1; l < model.links_.size(); ++l) {
    const int j = model.links_[l].parent_joint;
    Joint& joint = model.joints_[static_cast<std::size_t>(j)];
    if (joint.type == JointType::kFixed || mimics.count(joint.name) != 0) continue;
    joint.variable = static_cast<int>(model.variable_joints_.size());
    model.variable_joints_.push_back(j);
  }
  // Mimic joints: resolve chains to an active joint.
  for (const auto& [name, leader] : mimics) {
    Joint& joint = model.joints_[static_cast<std::size_t>(model.joint_by_name_.at(name))];
    double multiplier = 1.0;
    double offset = 0.0;
    std::string current = name;
    for (std::size_t hops = 0;; ++hops) {
      const auto m = mimics.find(current);
      if (m == mimics.end()) break;
      if (hops > mimics.size()) {
        throw InputError(where + ": joint '" + name + "': <mimic> chain forms a cycle");
      }
      const std::string& target = m->second.first;
      const auto t = model.joint_by_name_.find(target);
      if (t == model.joint_by_name_.end()) {
        throw InputError(where + ": joint '" + current + "': <mimic joint='" + target +
                         "'> names no joint");
      }
      if (model.joints_[static_cast<std::size_t>(t->second)].type == JointType::kFixed) {
        throw InputError(where + ": joint '" + current + "': mimics fixed joint '" + target + "'");
      }
      // value(current) = mul * value(target) + off; compose with what we have so far.
      offset += multiplier * m->second.second->offset;
      multiplier *= m->second.second->multiplier;
      current = target;
    }
    const Joint& leader_joint =
        model.joints_[static_cast<std::size_t>(model.joint_by_name_.at(current))];
    joint.mimic_variable = leader_joint.variable;
    joint.mimic_multiplier = multiplier;
    joint.mimic_offset = offset;
    (void)leader;
  }

  for (const auto& [link_name, padding] : options.link_padding) {
    if (model.link_by_name_.count(link_name) == 0) {
      throw InputError(where + ": padding given for unknown link '" + link_name + "'");
    }
    check_padding(where + ": link '" + link_name + "'", padding);
    model.link_padding_[link_name] = padding;
  }
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
}

void RobotModel::set_default_padding(double padding) {
  check_padding("robot '" + name_ + "': default", padding);
  default_padding_ = padding;
  apply_padding();
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
