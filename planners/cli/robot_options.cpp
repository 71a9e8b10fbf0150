#include "robot_options.hpp"

#include <cstdlib>
#include <sstream>

#include "number_options.hpp"

namespace hullcheck::cli {

void RobotOptions::add_to(CLI::App& command, bool with_srdf) {
  command.add_option("--robot", urdf, "URDF file of the robot")->required();
  command.add_option("--package", packages,
                     "Folder of a ROS package for package:// URIs, as NAME=DIR (repeatable)");
  command.add_option("--padding", padding, "Padding added to every link, m (default 0)")
      ->check(finite_in(0.0, 1e6));
  if (with_srdf) {
    command.add_option("--srdf", srdf, "MoveIt SRDF: collision matrix, groups, named states");
  }
  command
      .add_option("--mesh-geometry", mesh_geometry,
                  "Meshes as convex pieces within --tolerance of the mesh (decompose, default) "
                  "or as one convex hull each (hull)")
      ->check(CLI::IsMember({"hull", "decompose"}));
  command
      .add_option("--tolerance", tolerance,
                  "Decomposition tolerance, m: how far the pieces may reach beyond a mesh "
                  "(default 0.003)")
      ->check(finite_in(1e-6, 1e6));
  command.add_option("--max-pieces", max_pieces, "Most convex pieces per mesh (default 32)")
      ->check(integer_in(1, 1024));
  command.add_option("--cache-dir", cache_dir,
                     "Folder of cached decompositions (default $HULLCHECK_CACHE_DIR, "
                     "$XDG_CACHE_HOME/hullcheck or ~/.cache/hullcheck)");
  command.add_flag("--no-cache", no_cache, "Decompose meshes without reading or writing the cache");
}

std::shared_ptr<RobotModel> RobotOptions::load() const {
  return std::make_shared<RobotModel>(RobotModel::from_urdf_file(urdf, load_options()));
}

RobotLoadOptions RobotOptions::load_options() const {
  RobotLoadOptions options;
  for (const std::string& p : packages) {
    const std::size_t eq = p.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == p.size()) {
      throw InputError("--package '" + p + "': expected NAME=DIR");
    }
    options.packages[p.substr(0, eq)] = p.substr(eq + 1);
  }
  options.default_padding = padding;
  options.mesh_geometry = mesh_geometry == "hull" ? MeshGeometry::kHull : MeshGeometry::kDecompose;
  options.decomposition.tolerance = tolerance;
  options.decomposition.max_pieces = max_pieces;
  options.decomposition_cache_dir = cache_dir;
  options.use_decomposition_cache = !no_cache;
  return options;
}

Srdf RobotOptions::load_srdf() const { return srdf.empty() ? Srdf{} : read_srdf_file(srdf); }

bool parse_number_list(const std::string& text, std::vector<double>* values,
                       std::string* bad_item) {
  values->clear();
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    // strtod also reads "nan" and "inf", which check_configuration then rejects by joint name.
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    while (end != nullptr && (*end == ' ' || *end == '\t')) ++end;
    if (item.empty() || end == item.c_str() || *end != '\0') {
      *bad_item = item;
      return false;
    }
    values->push_back(v);
  }
  return true;
}

Eigen::VectorXd parse_configuration(const std::string& text, const RobotModel& model) {
  std::vector<double> values;
  std::string bad;
  if (!parse_number_list(text, &values, &bad)) {
    throw InputError("--state: item " + std::to_string(values.size()) + " ('" + bad +
                     "') is not a number");
  }
  const Eigen::VectorXd q =
      Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  model.check_configuration(q);
  return q;
}

}  // namespace hullcheck::cli
