#include "html_viewer.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "viewer_page.hpp"

namespace hullcheck::cli {
namespace {

const char* const kThreeDir = "/usr/share/javascript/three";

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError("viewer: cannot read '" + path +
                     "' (three.js: install Debian's libjs-three, scripts/install-deps.sh does)");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// JSON through yaml-cpp's emitter: flow style, keys double-quoted.
void key(YAML::Emitter& e, const char* name) { e << YAML::Key << YAML::DoubleQuoted << name; }

void emit_pose(YAML::Emitter& e, const Eigen::Isometry3d& pose) {
  e << YAML::BeginSeq;  // column-major 4x4, as THREE.Matrix4.fromArray expects
  for (int i = 0; i < 16; ++i) e << pose.matrix().data()[i];
  e << YAML::EndSeq;
}

void emit_shape(YAML::Emitter& e, const Shape& shape) {
  const Shape::Geometry& g = shape.geometry();
  e << YAML::BeginMap;
  if (const auto* box = std::get_if<Box>(&g)) {
    key(e, "type");
    e << YAML::DoubleQuoted << "box";
    key(e, "size");
    e << YAML::BeginSeq << 2 * box->half_extents.x() << 2 * box->half_extents.y()
      << 2 * box->half_extents.z() << YAML::EndSeq;
  } else if (const auto* sphere = std::get_if<Sphere>(&g)) {
    key(e, "type");
    e << YAML::DoubleQuoted << "sphere";
    key(e, "radius");
    e << sphere->radius;
  } else if (const auto* cylinder = std::get_if<Cylinder>(&g)) {
    key(e, "type");
    e << YAML::DoubleQuoted << "cylinder";
    key(e, "radius");
    e << cylinder->radius;
    key(e, "length");
    e << 2 * cylinder->half_length;
  } else if (const auto* capsule = std::get_if<Capsule>(&g)) {
    key(e, "type");
    e << YAML::DoubleQuoted << "capsule";
    key(e, "radius");
    e << capsule->radius;
    key(e, "length");
    e << 2 * capsule->half_length;
  } else {
    const auto& hull = std::get<ConvexHull>(g);
    key(e, "type");
    e << YAML::DoubleQuoted << "hull";
    key(e, "vertices");
    e << YAML::BeginSeq;
    for (const Eigen::Vector3d& v : hull.vertices()) e << v.x() << v.y() << v.z();
    e << YAML::EndSeq;
    key(e, "triangles");
    e << YAML::BeginSeq;
    for (const auto& t : hull.triangles()) e << t[0] << t[1] << t[2];
    e << YAML::EndSeq;
  }
  e << YAML::EndMap;
}

// Text for HTML element content.
std::string html_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// JSON made safe inside <script>: '<' occurs only in strings (names), where \u003c means the same.
std::string script_safe(const char* json) {
  std::string out;
  for (const char* c = json; *c; ++c) {
    if (*c == '<') {
      out += "\\u003c";
    } else {
      out += *c;
    }
  }
  return out;
}

// The page template with each {{name}} replaced by values.at(name); the values themselves are
// not searched for placeholders. Throws std::logic_error for a placeholder without a value.
std::string filled_page(std::string_view page,
                        const std::map<std::string_view, std::string_view>& values) {
  std::string out;
  std::size_t pos = 0;
  for (;;) {
    const std::size_t open = page.find("{{", pos);
    const std::size_t close = open == std::string_view::npos ? open : page.find("}}", open + 2);
    if (close == std::string_view::npos) break;
    const std::string_view name = page.substr(open + 2, close - open - 2);
    const auto value = values.find(name);
    if (value == values.end()) {
      throw std::logic_error("viewer page: no value for {{" + std::string(name) + "}}");
    }
    out.append(page.substr(pos, open - pos)).append(value->second);
    pos = close + 2;
  }
  return out.append(page.substr(pos));
}

}  // namespace

void write_html_viewer(const std::string& file, const std::string& title, const RobotModel& model,
                       const PlanningScene& scene,
                       const std::vector<Eigen::VectorXd>& configurations,
                       const std::vector<Eigen::VectorXd>& before) {
  const std::string three = read_file(std::string(kThreeDir) + "/three.min.js");
  const std::string orbit =
      read_file(std::string(kThreeDir) + "/examples/js/controls/OrbitControls.js");
  YAML::Emitter e;
  e.SetDoublePrecision(7);
  e << YAML::Flow << YAML::BeginMap;
  key(e, "links");
  e << YAML::BeginSeq;
  for (const Link& link : model.links()) {
    e << YAML::BeginMap;
    key(e, "name");
    e << YAML::DoubleQuoted << link.name;
    key(e, "shapes");
    e << YAML::BeginSeq;
    for (const CollisionShape& s : link.shapes) {
      e << YAML::BeginMap;
      key(e, "origin");
      emit_pose(e, s.origin);
      key(e, "shape");
      emit_shape(e, s.unpadded);
      e << YAML::EndMap;
    }
    e << YAML::EndSeq << YAML::EndMap;
  }
  e << YAML::EndSeq;
  key(e, "obstacles");
  e << YAML::BeginSeq;
  for (const Obstacle& o : scene.obstacles) {
    e << YAML::BeginMap;
    key(e, "name");
    e << YAML::DoubleQuoted << o.name;
    key(e, "pose");
    emit_pose(e, o.pose);
    key(e, "shape");
    emit_shape(e, o.shape);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq;
  std::vector<Eigen::Isometry3d> poses;
  for (const auto& [name, path] :
       {std::pair{"frames", &configurations}, std::pair{"before", &before}}) {
    key(e, name);
    e << YAML::BeginSeq;
    for (const Eigen::VectorXd& q : *path) {
      model.compute_link_poses(q, poses);
      e << YAML::BeginSeq;
      for (const Eigen::Isometry3d& p : poses) emit_pose(e, p);
      e << YAML::EndSeq;
    }
    e << YAML::EndSeq;
  }
  e << YAML::EndMap;

  const std::string heading = html_escaped(title);
  std::ofstream out(file);
  if (!out) throw InputError("viewer '" + file + "': cannot write");
  const std::string data = script_safe(e.c_str());
  const std::string page = filled_page(
      viewer_page(),
      {{"title", heading}, {"data", data}, {"three.js", three}, {"OrbitControls.js", orbit}});
  out << page;
  if (!out) throw InputError("viewer '" + file + "': write failed");
}

}  // namespace hullcheck::cli
