// Options shared by the subcommands that load a robot: --robot, --package, --srdf, --padding,
// and how meshes become convex shapes (--mesh-geometry, --tolerance, --cache-dir).
#pragma once

#include <CLI/CLI.hpp>
#include <hullcheck/robot.hpp>
#include <memory>
#include <string>
#include <vector>

namespace hullcheck::cli {

/// What the user said about the robot to load.
struct RobotOptions {
  std::string urdf;
  std::vector<std::string> packages;  // NAME=DIR
  std::string srdf;
  double padding = 0.0;
  std::string mesh_geometry = "decompose";  // "hull" or "decompose"
  double tolerance = DecompositionOptions{}.tolerance;
  int max_pieces = DecompositionOptions{}.max_pieces;
  std::string cache_dir;  // empty: the default folder
  bool no_cache = false;

  /// Adds --robot (required), --package (repeatable), --padding, --mesh-geometry,
  /// --tolerance, --max-pieces, --cache-dir, --no-cache; --srdf when `with_srdf`.
  void add_to(CLI::App& command, bool with_srdf);
  /// Loads the URDF; throws InputError for a malformed --package or a bad robot.
  std::shared_ptr<RobotModel> load() const;
  /// The RobotLoadOptions these options describe (load() uses them).
  RobotLoadOptions load_options() const;
  /// The SRDF given with --srdf (parsed), or an empty Srdf when none was given.
  Srdf load_srdf() const;
};

/// Parses "v1, v2,..." (comma-separated numbers, blanks after a number allowed) into `values`;
/// on the first item that is not a number returns false with it in `bad_item` (`values` then
/// holds the items before it).
bool parse_number_list(const std::string& text, std::vector<double>* values, std::string* bad_item);

/// Parses "v1,v2,..." into a configuration for `model` (checked: count and finiteness); names
/// the bad item when one is not a number.
Eigen::VectorXd parse_configuration(const std::string& text, const RobotModel& model);

}  // namespace hullcheck::cli
