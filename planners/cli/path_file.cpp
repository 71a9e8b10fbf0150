#include "path_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <set>
#include <sstream>

namespace hullcheck::cli {
namespace {

bool is_json(const std::string& file) {
  return file.size() >= 5 && file.compare(file.size() - 5, 5, ".json") == 0;
}

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto b = item.find_first_not_of(" \t\r");
    const auto e = item.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : item.substr(b, e - b + 1));
  }
  return out;
}

// Throws when the header names a joint twice (or names an empty one).
void check_unique_names(const std::string& file, const std::vector<std::string>& names) {
  std::set<std::string> seen;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i].empty()) {
      throw InputError("path '" + file + "': joint name " + std::to_string(i + 1) +
                       " of the header is empty");
    }
    if (!seen.insert(names[i]).second) {
      throw InputError("path '" + file + "': joint '" + names[i] +
                       "' is named twice in the header");
    }
  }
}

}  // namespace

void write_joint_path(const std::string& file, const JointPath& path) {
  std::ofstream out(file);
  if (!out) throw InputError("path '" + file + "': cannot write");
  if (is_json(file)) {
    // JSON through yaml-cpp's emitter: flow style with double-quoted keys and names is JSON.
    YAML::Emitter e;
    e.SetDoublePrecision(17);
    e << YAML::Flow << YAML::BeginMap << YAML::Key << YAML::DoubleQuoted << "joint_names"
      << YAML::Value << YAML::BeginSeq;
    for (const std::string& n : path.joint_names) e << YAML::DoubleQuoted << n;
    e << YAML::EndSeq << YAML::Key << YAML::DoubleQuoted << "waypoints" << YAML::Value
      << YAML::BeginSeq;
    for (const Eigen::VectorXd& w : path.waypoints) {
      e << YAML::BeginSeq;
      for (int i = 0; i < w.size(); ++i) e << w[i];
      e << YAML::EndSeq;
    }
    e << YAML::EndSeq << YAML::EndMap;
    out << e.c_str() << "\n";
  } else {
    for (std::size_t i = 0; i < path.joint_names.size(); ++i) {
      out << (i ? "," : "") << path.joint_names[i];
    }
    out << "\n";
    for (const Eigen::VectorXd& w : path.waypoints) {
      for (int i = 0; i < w.size(); ++i) out << (i ? "," : "") << number(w[i]);
      out << "\n";
    }
  }
  if (!out) throw InputError("path '" + file + "': write failed");
}

JointPath read_joint_path(const std::string& file) {
  JointPath path;
  if (is_json(file)) {
    YAML::Node root;
    try {
      root = YAML::LoadFile(file);
      for (const YAML::Node& n : root["joint_names"])
        path.joint_names.push_back(n.as<std::string>());
      int row = 0;
      for (const YAML::Node& w : root["waypoints"]) {
        if (w.size() != path.joint_names.size()) {
          throw InputError("path '" + file + "': waypoint " + std::to_string(row) + " has " +
                           std::to_string(w.size()) + " values, expected " +
                           std::to_string(path.joint_names.size()));
        }
        Eigen::VectorXd q(static_cast<Eigen::Index>(w.size()));
        for (std::size_t i = 0; i < w.size(); ++i) {
          q[static_cast<Eigen::Index>(i)] = w[i].as<double>();
          if (!std::isfinite(q[static_cast<Eigen::Index>(i)])) {
            throw InputError("path '" + file + "': waypoint " + std::to_string(row) + ", joint '" +
                             path.joint_names[i] + "': '" + w[i].Scalar() +
                             "' is not a finite number");
          }
        }
        path.waypoints.push_back(q);
        ++row;
      }
    } catch (const YAML::BadFile&) {
      throw InputError("path '" + file + "': cannot open file");
    } catch (const YAML::Exception& e) {
      throw InputError("path '" + file + "': not a path JSON file: " + e.what());
    }
  } else {
    std::ifstream in(file);
    if (!in) throw InputError("path '" + file + "': cannot open file");
    std::string line;
    int line_number = 0;
    while (std::getline(in, line)) {
      ++line_number;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      const std::vector<std::string> items = split(line);
      if (path.joint_names.empty()) {
        path.joint_names = items;
        continue;
      }
      if (items.size() != path.joint_names.size()) {
        throw InputError("path '" + file + "': line " + std::to_string(line_number) + " has " +
                         std::to_string(items.size()) + " values, the header names " +
                         std::to_string(path.joint_names.size()) + " joints");
      }
      Eigen::VectorXd q(static_cast<Eigen::Index>(items.size()));
      for (std::size_t i = 0; i < items.size(); ++i) {
        char* end = nullptr;
        q[static_cast<Eigen::Index>(i)] = std::strtod(items[i].c_str(), &end);
        if (items[i].empty() || *end != '\0' || !std::isfinite(q[static_cast<Eigen::Index>(i)])) {
          throw InputError("path '" + file + "': line " + std::to_string(line_number) +
                           ", joint '" + path.joint_names[i] + "': '" + items[i] +
                           "' is not a finite number");
        }
      }
      path.waypoints.push_back(q);
    }
  }
  if (path.joint_names.empty()) throw InputError("path '" + file + "': no joint-name header");
  check_unique_names(file, path.joint_names);
  if (path.waypoints.empty()) throw InputError("path '" + file + "': no waypoints");
  return path;
}

}  // namespace hullcheck::cli
