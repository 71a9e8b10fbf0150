#include <yaml-cpp/yaml.h>

#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/length_checks.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <map>
#include <sstream>

namespace hullcheck {
namespace {

class SceneReader {
 public:
  SceneReader(const RobotModel& model, std::string source)
      : model_(model), source_(std::move(source)) {}

  PlanningScene read(const YAML::Node& root) {
    PlanningScene scene;
    if (!root.IsMap()) fail("", "the document is not a YAML map (a moveit_msgs/PlanningScene)");
    if (root["name"] && root["name"].IsScalar()) scene.name = root["name"].as<std::string>();
    read_robot_state(root["robot_state"], &scene);
    const YAML::Node world = root["world"];
    if (world && world["collision_objects"]) {
      const YAML::Node objects = world["collision_objects"];
      if (!objects.IsSequence()) fail("", "world.collision_objects is not a list");
      for (std::size_t i = 0; i < objects.size(); ++i) read_object(objects[i], i, &scene);
    }
    read_matrix(root["allowed_collision_matrix"], &scene);
    return scene;
  }

 private:
  [[noreturn]] void fail(const std::string& object, const std::string& problem) const {
    std::string msg = "scene '" + source_ + "'";
    if (!object.empty()) msg += ": object '" + object + "'";
    throw InputError(msg + ": " + problem);
  }

  double number(const YAML::Node& n, const std::string& object, const std::string& what) const {
    try {
      const double v = n.as<double>();
      if (!std::isfinite(v)) fail(object, what + " is not finite");
      return v;
    } catch (const YAML::Exception&) {
      fail(object, what + " is not a number");
    }
  }

  // A length, m: finite and at most kMaxLoadedLength in magnitude.
  double length(const YAML::Node& n, const std::string& object, const std::string& what) const {
    const double v = number(n, object, what);
    if (std::abs(v) > kMaxLoadedLength) {
      std::ostringstream msg;
      msg << what << " is " << v << ", above the " << kMaxLoadedLength
          << " m accepted for a length";
      fail(object, msg.str());
    }
    return v;
  }

  // Runs a Shape constructor; its InputError gets this scene's prefix once (the scene's own
  // errors, from fail(), already carry it and are not caught here).
  template <typename Make>
  Shape construct(const std::string& object, const std::string& what, Make make) const {
    try {
      return make();
    } catch (const InputError& e) {
      fail(object, what + ": " + e.what());
    }
  }

  // [x, y, z] or {x:, y:, z:} (missing map keys read as 0, as ROS messages default them), m.
  Eigen::Vector3d vector3(const YAML::Node& n, const std::string& object,
                          const std::string& what) const {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    if (!n) return v;
    if (n.IsSequence()) {
      if (n.size() != 3) fail(object, what + " needs 3 values, has " + std::to_string(n.size()));
      for (int i = 0; i < 3; ++i) v[i] = length(n[static_cast<std::size_t>(i)], object, what);
    } else if (n.IsMap()) {
      const char* keys[] = {"x", "y", "z"};
      for (int i = 0; i < 3; ++i) {
        if (n[keys[i]]) v[i] = length(n[keys[i]], object, what + "." + keys[i]);
      }
    } else {
      fail(object, what + " is neither a list nor a map");
    }
    return v;
  }

  Eigen::Quaterniond quaternion(const YAML::Node& n, const std::string& object,
                                const std::string& what) const {
    if (!n) return Eigen::Quaterniond::Identity();
    double c[4] = {0, 0, 0, 1};  // x y z w
    if (n.IsSequence()) {
      if (n.size() != 4) {
        fail(object, what + " needs 4 values [x, y, z, w], has " + std::to_string(n.size()));
      }
      for (int i = 0; i < 4; ++i) c[i] = number(n[static_cast<std::size_t>(i)], object, what);
    } else if (n.IsMap()) {
      const char* keys[] = {"x", "y", "z", "w"};
      c[3] = 0.0;
      for (int i = 0; i < 4; ++i) {
        if (n[keys[i]]) c[i] = number(n[keys[i]], object, what + "." + keys[i]);
      }
    } else {
      fail(object, what + " is neither a list nor a map");
    }
    Eigen::Quaterniond q(c[3], c[0], c[1], c[2]);
    const double norm = q.norm();
    if (std::abs(norm - 1.0) > 1e-3) {
      std::ostringstream msg;
      msg << what << " is not a unit quaternion (norm " << norm << ")";
      fail(object, msg.str());
    }
    q.coeffs() /= norm;
    return q;
  }

  Eigen::Isometry3d pose(const YAML::Node& n, const std::string& object,
                         const std::string& what) const {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    if (!n) return p;
    if (!n.IsMap()) fail(object, what + " is not a map with position and orientation");
    p.linear() = quaternion(n["orientation"], object, what + ".orientation").toRotationMatrix();
    p.translation() = vector3(n["position"], object, what + ".position");
    return p;
  }

  void read_robot_state(const YAML::Node& state, PlanningScene* scene) {
    if (!state || !state["joint_state"]) return;
    const YAML::Node js = state["joint_state"];
    const YAML::Node names = js["name"];
    const YAML::Node positions = js["position"];
    if (!names || !positions) return;
    if (!names.IsSequence() || !positions.IsSequence() || names.size() != positions.size()) {
      fail("", "robot_state.joint_state: name and position must be lists of equal length");
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
      scene->robot_joint_values.emplace_back(names[i].as<std::string>(),
                                             number(positions[i], "", "robot_state position"));
    }
  }

  // Frame of an object: the model frame, or a robot link posed at the scene's robot state.
  Eigen::Isometry3d frame(const std::string& frame_id, const std::string& object,
                          const PlanningScene& scene) {
    std::string id = frame_id;
    if (!id.empty() && id[0] == '/') id = id.substr(1);
    if (id.empty() || id == "world" || id == model_.link(0).name) {
      return Eigen::Isometry3d::Identity();
    }
    const int link = model_.link_index(id);
    if (link < 0) {
      fail(object, "header.frame_id '" + frame_id + "' is neither the world nor a link of robot '" +
                       model_.name() + "'");
    }
    if (link_poses_.empty()) {
      Eigen::VectorXd q = model_.default_configuration();
      for (const auto& [name, value] : scene.robot_joint_values) {
        const int v = model_.variable_index(name);
        if (v >= 0) q[v] = value;
      }
      model_.compute_link_poses(q, link_poses_);
    }
    return link_poses_[static_cast<std::size_t>(link)];
  }

  // `type_name` receives the primitive's name ("box", ...; numeric types translated).
  Shape primitive(const YAML::Node& p, const std::string& object, std::string* type_name) const {
    if (!p.IsMap() || !p["type"]) fail(object, "primitive without a type");
    std::string type;
    const std::string raw = p["type"].as<std::string>();
    // moveit_msgs may give the numeric constant: 1 box, 2 sphere, 3 cylinder, 4 cone.
    static const std::map<std::string, std::string> kNumeric = {
        {"1", "box"}, {"2", "sphere"}, {"3", "cylinder"}, {"4", "cone"}};
    type = kNumeric.count(raw) ? kNumeric.at(raw) : raw;
    for (char& ch : type) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    *type_name = type;
    const YAML::Node dims = p["dimensions"];
    if (!dims || !dims.IsSequence()) fail(object, type + " without a dimensions list");
    std::vector<double> d;
    for (std::size_t i = 0; i < dims.size(); ++i) {
      d.push_back(length(dims[i], object, type + " dimension " + std::to_string(i)));
      if (d.back() < 0.0) fail(object, type + " has a negative dimension");
    }
    const auto need = [&](std::size_t n, const char* layout) {
      if (d.size() != n) {
        fail(object, type + " needs " + std::to_string(n) + " dimensions " + layout + ", has " +
                         std::to_string(d.size()));
      }
    };
    if (type == "box") {
      need(3, "[x, y, z]");
      return construct(object, type, [&] { return Shape(Box(d[0], d[1], d[2])); });
    }
    if (type == "sphere") {
      need(1, "[radius]");
      return construct(object, type, [&] { return Shape(Sphere(d[0])); });
    }
    if (type == "cylinder") {
      need(2, "[height, radius]");
      return construct(object, type, [&] { return Shape(Cylinder(d[1], d[0])); });
    }
    if (type == "cone") {
      need(2, "[height, radius]");
      return construct(object, type, [&] { return cone(d[0], d[1]); });
    }
    fail(object, "unknown primitive type '" + raw + "' (box, sphere, cylinder, cone)");
  }

  // Apex at +height/2, base circle at -height/2; the base polygon circumscribes the circle.
  static Shape cone(double height, double radius) {
    constexpr int kSides = 64;
    const double r = radius / std::cos(M_PI / kSides);
    std::vector<Eigen::Vector3d> points{{0, 0, height / 2}};
    for (int i = 0; i < kSides; ++i) {
      const double a = 2.0 * M_PI * i / kSides;
      points.emplace_back(r * std::cos(a), r * std::sin(a), -height / 2);
    }
    return ConvexHull(points);
  }

  Shape mesh(const YAML::Node& m, const std::string& object) const {
    const YAML::Node vertices = m["vertices"];
    if (!vertices || !vertices.IsSequence() || vertices.size() == 0) {
      fail(object, "mesh without vertices");
    }
    std::vector<Eigen::Vector3d> points;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      points.push_back(vector3(vertices[i], object, "mesh vertex " + std::to_string(i)));
    }
    return construct(object, "mesh", [&] { return Shape(ConvexHull(points)); });
  }

  void read_object(const YAML::Node& o, std::size_t index, PlanningScene* scene) {
    if (!o.IsMap()) fail("#" + std::to_string(index), "collision object is not a map");
    const std::string id = o["id"] ? o["id"].as<std::string>() : "#" + std::to_string(index);
    if (o["operation"]) {
      const std::string op = o["operation"].as<std::string>();
      if (op == "remove" || op == "1" || op == "REMOVE") return;
    }
    std::string frame_id;
    if (o["header"] && o["header"]["frame_id"])
      frame_id = o["header"]["frame_id"].as<std::string>();
    const Eigen::Isometry3d base = frame(frame_id, id, *scene) * pose(o["pose"], id, "pose");
    std::vector<std::pair<Shape, std::string>> shapes;
    std::vector<Eigen::Isometry3d> poses;
    const auto collect = [&](const char* list, const char* pose_list, bool is_mesh) {
      const YAML::Node items = o[list];
      if (!items) return;
      if (!items.IsSequence()) fail(id, std::string(list) + " is not a list");
      const YAML::Node item_poses = o[pose_list];
      if (items.size() > 0 &&
          (!item_poses || !item_poses.IsSequence() || item_poses.size() != items.size())) {
        fail(id, std::string(pose_list) + " must list one pose per entry of " + list);
      }
      for (std::size_t i = 0; i < items.size(); ++i) {
        if (is_mesh) {
          shapes.emplace_back(mesh(items[i], id), "mesh");
        } else {
          std::string type;
          Shape s = primitive(items[i], id, &type);
          shapes.emplace_back(std::move(s), type);
        }
        poses.push_back(
            base * pose(item_poses[i], id, std::string(pose_list) + "[" + std::to_string(i) + "]"));
      }
    };
    collect("primitives", "primitive_poses", false);
    collect("meshes", "mesh_poses", true);
    if (o["planes"] && o["planes"].IsSequence() && o["planes"].size() > 0) {
      fail(id, "planes are not supported (infinite half-spaces); use a large box");
    }
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      const std::string name = shapes.size() == 1 ? id : id + "/" + std::to_string(i);
      scene->obstacles.push_back({name, id, shapes[i].first, poses[i], shapes[i].second});
    }
  }

  void read_matrix(const YAML::Node& acm, PlanningScene* scene) const {
    if (!acm || !acm["entry_names"]) return;
    const YAML::Node names = acm["entry_names"];
    const YAML::Node values = acm["entry_values"];
    if (!names.IsSequence() || !values || !values.IsSequence() || values.size() != names.size()) {
      fail("", "allowed_collision_matrix: entry_values must have one row per entry name");
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
      YAML::Node row = values[i];
      if (row.IsMap() && row["enabled"]) row = row["enabled"];  // moveit_msgs/AllowedCollisionEntry
      if (!row.IsSequence() || row.size() != names.size()) {
        fail("", "allowed_collision_matrix: row " + std::to_string(i) + " must have " +
                     std::to_string(names.size()) + " values");
      }
      for (std::size_t j = i + 1; j < names.size(); ++j) {
        if (row[j].as<bool>()) {
          scene->allowed_pairs.emplace_back(names[i].as<std::string>(), names[j].as<std::string>());
        }
      }
    }
  }

  const RobotModel& model_;
  std::string source_;
  std::vector<Eigen::Isometry3d> link_poses_;
};

}  // namespace

PlanningScene parse_planning_scene(const std::string& yaml, const RobotModel& model,
                                   const std::string& source_name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw InputError("scene '" + source_name + "': YAML error: " + e.what());
  }
  try {
    return SceneReader(model, source_name).read(root);
  } catch (const YAML::Exception& e) {
    throw InputError("scene '" + source_name + "': " + e.what());
  }
}

PlanningScene read_planning_scene(const std::string& path, const RobotModel& model) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError("scene '" + path + "': cannot open file");
  } catch (const YAML::Exception& e) {
    throw InputError("scene '" + path + "': YAML error: " + e.what());
  }
  try {
    return SceneReader(model, path).read(root);
  } catch (const YAML::Exception& e) {
    throw InputError("scene '" + path + "': " + e.what());
  }
}

PlanningScene planning_scene_from_urdf(const std::string& path,
                                       const Eigen::Isometry3d& environment_pose,
                                       const RobotLoadOptions& options) {
  const RobotModel env = RobotModel::from_urdf_file(path, options);
  std::vector<Eigen::Isometry3d> poses;
  env.compute_link_poses(env.default_configuration(), poses);
  PlanningScene scene;
  scene.name = env.name();
  for (std::size_t l = 0; l < env.links().size(); ++l) {
    const Link& link = env.links()[l];
    for (std::size_t s = 0; s < link.shapes.size(); ++s) {
      const std::string name =
          link.shapes.size() == 1 ? link.name : link.name + "/" + std::to_string(s);
      scene.obstacles.push_back({name, link.name, link.shapes[s].shape,
                                 environment_pose * poses[l] * link.shapes[s].origin, link.name});
    }
  }
  return scene;
}

}  // namespace hullcheck
