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

// Throws when the header names a joint twice (or names an empty one), or a held joint is named
// twice or also in the header.
void check_unique_names(const std::string& file, const JointPath& path) {
  std::set<std::string> seen;
  for (std::size_t i = 0; i < path.joint_names.size(); ++i) {
    if (path.joint_names[i].empty()) {
      throw InputError("path '" + file + "': joint name " + std::to_string(i + 1) +
                       " of the header is empty");
    }
    if (!seen.insert(path.joint_names[i]).second) {
      throw InputError("path '" + file + "': joint '" + path.joint_names[i] +
                       "' is named twice in the header");
    }
  }
  for (const auto& [name, value] : path.held) {
    if (!seen.insert(name).second) {
      throw InputError("path '" + file + "': held joint '" + name +
                       "' is named twice (among the header and the held joints)");
    }
  }
}

// True when `text` (trimmed) is a finite number, which is stored in *value.
bool parse_finite(const std::string& text, double* value) {
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return !text.empty() && end != text.c_str() && *end == '\0' && std::isfinite(*value);
}

// The items "name=value" of a CSV "# held:" line (after the colon).
void parse_held(const std::string& file, int line_number, const std::string& items,
                JointPath* path) {
  for (const std::string& item : split(items)) {
    const std::size_t eq = item.find('=');
    double value = 0.0;
    if (eq == std::string::npos || eq == 0 || !parse_finite(item.substr(eq + 1), &value)) {
      throw InputError("path '" + file + "': line " + std::to_string(line_number) +
                       ": held joint '" + item + "': expected NAME=VALUE with a finite value");
    }
    path->held.emplace_back(item.substr(0, eq), value);
  }
}

constexpr const char* kHeldPrefix = "# held:";

}  // namespace

void write_joint_path(const std::string& file, const JointPath& path) {
  std::ofstream out(file);
  if (!out) throw InputError("path '" + file + "': cannot write");
  if (is_json(file)) {
    // JSON through yaml-cpp's emitter: flow style with double-quoted keys and names is JSON.
    YAML::Emitter e;
    e.SetDoublePrecision(17);
    e << YAML::Flow << YAML::BeginMap;
    if (!path.held.empty()) {
      e << YAML::Key << YAML::DoubleQuoted << "held" << YAML::Value << YAML::BeginMap;
      for (const auto& [name, value] : path.held) {
        e << YAML::Key << YAML::DoubleQuoted << name << YAML::Value << value;
      }
      e << YAML::EndMap;
    }
    e << YAML::Key << YAML::DoubleQuoted << "joint_names" << YAML::Value << YAML::BeginSeq;
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
    if (!path.held.empty()) {
      out << kHeldPrefix << ' ';
      for (std::size_t i = 0; i < path.held.size(); ++i) {
        out << (i ? "," : "") << path.held[i].first << '=' << number(path.held[i].second);
      }
      out << "\n";
    }
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
      for (const auto& entry : root["held"]) {
        const std::string name = entry.first.as<std::string>();
        double value = 0.0;
        if (!parse_finite(entry.second.Scalar(), &value)) {
          throw InputError("path '" + file + "': held joint '" + name + "': '" +
                           entry.second.Scalar() + "' is not a finite number");
        }
        path.held.emplace_back(name, value);
      }
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
      if (line.rfind(kHeldPrefix, 0) == 0) {
        if (!path.joint_names.empty()) {
          throw InputError("path '" + file + "': line " + std::to_string(line_number) +
                           ": the held joints must come before the header");
        }
        parse_held(file, line_number, line.substr(std::string(kHeldPrefix).size()), &path);
        continue;
      }
      if (line[0] == '#') continue;  // a comment
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
        if (!parse_finite(items[i], &q[static_cast<Eigen::Index>(i)])) {
          throw InputError("path '" + file + "': line " + std::to_string(line_number) +
                           ", joint '" + path.joint_names[i] + "': '" + items[i] +
                           "' is not a finite number");
        }
      }
      path.waypoints.push_back(q);
    }
  }
  if (path.joint_names.empty()) throw InputError("path '" + file + "': no joint-name header");
  check_unique_names(file, path);
  if (path.waypoints.empty()) throw InputError("path '" + file + "': no waypoints");
  return path;
}

}  // namespace hullcheck::cli
