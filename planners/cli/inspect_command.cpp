#include "inspect_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <hullcheck/scene/collision_checker.hpp>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "robot_options.hpp"

namespace hullcheck::cli {
namespace {

const char* type_name(JointType type) {
  switch (type) {
    case JointType::kRevolute:
      return "revolute";
    case JointType::kContinuous:
      return "continuous";
    case JointType::kPrismatic:
      return "prismatic";
    case JointType::kFixed:
      return "fixed";
  }
  return "?";
}

std::string format(const char* fmt, double a, double b = 0, double c = 0) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c);
  return buffer;
}

// URDF's roll-pitch-yaw (R = Rz(yaw) Ry(pitch) Rx(roll)) of a rotation, rad.
Eigen::Vector3d rpy_of(const Eigen::Matrix3d& r) {
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  // + 0.0 turns -0 into 0 for printing.
  return {std::atan2(r(2, 1), r(2, 2)) + 0.0, pitch + 0.0, std::atan2(r(1, 0), r(0, 0)) + 0.0};
}

std::string describe(const CollisionShape& s) {
  std::ostringstream out;
  const Shape::Geometry& g = s.unpadded.geometry();
  if (const auto* box = std::get_if<Box>(&g)) {
    const Eigen::Vector3d size = 2.0 * box->half_extents;
    out << "box " << format("%.4g x %.4g x %.4g", size.x(), size.y(), size.z());
  } else if (const auto* sphere = std::get_if<Sphere>(&g)) {
    out << "sphere r " << format("%.4g", sphere->radius);
  } else if (const auto* cylinder = std::get_if<Cylinder>(&g)) {
    out << "cylinder r " << format("%.4g", cylinder->radius) << " length "
        << format("%.4g", 2.0 * cylinder->half_length);
  } else if (const auto* capsule = std::get_if<Capsule>(&g)) {
    out << "capsule r " << format("%.4g", capsule->radius) << " length "
        << format("%.4g", 2.0 * capsule->half_length);
  } else if (const auto* hull = std::get_if<ConvexHull>(&g)) {
    if (s.piece_count > 1) {
      out << s.piece_count << " convex pieces";
    } else {
      out << "hull " << hull->vertex_count() << " vertices";
    }
    out << " (mesh " << s.mesh_vertex_count << " vertices, "
        << std::filesystem::path(s.source).filename().string();
    if (s.mesh_excess >= 0.0) out << format(", within %.2f mm of it", 1e3 * s.mesh_excess);
    out << ")";
  }
  const Eigen::Vector3d t = s.origin.translation();
  if (!t.isZero(0.0) || !s.origin.linear().isIdentity(0.0)) {
    const Eigen::Vector3d rpy = rpy_of(s.origin.linear());
    out << " at xyz " << format("%.4g %.4g %.4g", t.x(), t.y(), t.z()) << " rpy "
        << format("%.4g %.4g %.4g", rpy.x(), rpy.y(), rpy.z());
  }
  return out.str();
}

void print_model(const RobotModel& model) {
  std::size_t shapes = 0;
  for (const Link& l : model.links()) shapes += l.shapes.size();
  std::cout << "robot " << model.name() << " (" << model.source() << ")\n  " << model.links().size()
            << " links, " << model.joints().size() << " joints, " << model.variable_count()
            << " configuration values, " << shapes << " collision shapes\n\n";
  std::cout << "configuration (in order):\n";
  std::printf("  %3s  %-28s %-11s %11s %11s %9s\n", "#", "joint", "type", "lower", "upper",
              "max vel");
  for (int i = 0; i < model.variable_count(); ++i) {
    const Joint& j = model.joint(model.variable_joint(i));
    std::printf("  %3d  %-28s %-11s %11.5g %11.5g %9.4g\n", i, j.name.c_str(), type_name(j.type),
                j.lower, j.upper, j.max_velocity);
  }
  bool header = false;
  for (const Joint& j : model.joints()) {
    if (j.variable >= 0) continue;
    if (!header) std::cout << "other joints:\n";
    header = true;
    std::printf("  %-33s %-11s", j.name.c_str(), type_name(j.type));
    if (j.mimic_variable >= 0) {
      std::printf(" mimics %s (x%g %+g)",
                  model.joint(model.variable_joint(j.mimic_variable)).name.c_str(),
                  j.mimic_multiplier, j.mimic_offset);
    }
    std::printf("\n");
  }
  std::cout << "\nlinks (collision shapes; padding in m):\n";
  for (const Link& l : model.links()) {
    std::printf("  %-28s parent %-24s padding %g\n", l.name.c_str(),
                l.parent_joint < 0 ? "-" : model.joint(l.parent_joint).name.c_str(), l.padding);
    for (std::size_t i = 0; i < l.shapes.size(); ++i) {
      const CollisionShape& s = l.shapes[i];
      if (s.piece > 0) continue;  // a decomposed mesh: described once, its pieces below
      std::cout << "      " << describe(s) << "\n";
      if (s.piece_count > 1) {
        std::cout << "        piece vertices:";
        for (int k = 0; k < s.piece_count; ++k) {
          const auto& piece =
              std::get<ConvexHull>(l.shapes[i + static_cast<std::size_t>(k)].unpadded.geometry());
          std::cout << ' ' << piece.vertex_count();
        }
        std::cout << "\n";
      }
    }
    if (l.shapes.empty()) std::cout << "      (no collision geometry)\n";
  }
}

void print_state(const RobotModel& model, const Eigen::VectorXd& q, const Srdf& srdf) {
  std::vector<Eigen::Isometry3d> poses;
  model.compute_link_poses(q, poses);
  std::cout << "\nlink poses at the given state (model frame; xyz in m, rpy in rad):\n";
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector3d t = poses[i].translation();
    const Eigen::Vector3d rpy = rpy_of(poses[i].linear());
    std::printf("  %-28s xyz %9.5f %9.5f %9.5f  rpy %8.4f %8.4f %8.4f\n",
                model.links()[i].name.c_str(), t.x(), t.y(), t.z(), rpy.x(), rpy.y(), rpy.z());
  }
  std::vector<std::string> warnings;
  const AllowedCollisionMatrix acm = AllowedCollisionMatrix::from_srdf(model, srdf, &warnings);
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  std::shared_ptr<const RobotModel> shared(&model, [](const RobotModel*) {});
  const CollisionChecker checker(shared, acm);  // no scene: the robot against itself
  std::vector<std::pair<int, int>> colliding;
  checker.colliding_link_pairs_at(poses, colliding);
  const ClearanceResult closest = checker.clearance_at(poses);
  std::cout << "\nself-collision (" << checker.checked_link_pairs().size()
            << " link pairs checked, " << acm.allowed_pair_count() << " allowed): ";
  if (colliding.empty()) {
    std::cout << "free\n";
  } else {
    std::cout << "IN COLLISION, " << colliding.size() << " pair(s):\n";
    for (const auto& [a, b] : colliding) {
      std::cout << "  " << model.link(a).name << " - " << model.link(b).name << "\n";
    }
  }
  if (closest.link_a >= 0) {
    std::printf("closest pair: %s - %s, signed distance %.9g m\n", closest.name_a.data(),
                closest.name_b.data(), closest.distance);
  }
}

}  // namespace

void add_inspect_command(CLI::App& app) {
  auto options = std::make_shared<RobotOptions>();
  auto state = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand(
      "inspect",
      "Joints with limits, links with their shapes; with --state, link poses and the "
      "self-collision verdict");
  options->add_to(*command, true);
  command->add_option("--state", *state, "Configuration q1,q2,... in the order printed (rad or m)");
  command->callback([options, state] {
    const std::shared_ptr<RobotModel> model = options->load();
    // Check everything before printing anything.
    const Srdf srdf = options->load_srdf();
    Eigen::VectorXd q;
    if (!state->empty()) q = parse_configuration(*state, *model);
    print_model(*model);
    if (!state->empty()) print_state(*model, q, srdf);
  });
}

}  // namespace hullcheck::cli
