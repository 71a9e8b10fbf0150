// A self-contained HTML page showing the robot's collision shapes and the obstacles in 3D and
// animating a path (three.js from Debian's libjs-three, inlined: no network needed).
#pragma once

#include <Eigen/Core>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <string>
#include <vector>

namespace hullcheck::cli {

/// Writes `file`: the link shapes (convex hulls as their triangles, primitives exactly as
/// three.js solids; padding not drawn) at every configuration of `configurations` (full
/// vectors, played as an animation with a slider), the scene's obstacles, and `title` (HTML-
/// escaped). z is up; the camera is fitted to the obstacles and the robot along the whole path
/// (double-click refits), the light follows the camera.
/// With `before` (a second path, e.g. the path before optimization), that path's robot is drawn
/// too, translucent grey, moving in step with the first (same fraction of its frames), and each
/// path's last link traces its line (grey before, green the path). Throws InputError when
/// three.js is not installed (package libjs-three) or the file cannot be written.
void write_html_viewer(const std::string& file, const std::string& title, const RobotModel& model,
                       const PlanningScene& scene,
                       const std::vector<Eigen::VectorXd>& configurations,
                       const std::vector<Eigen::VectorXd>& before = {});

}  // namespace hullcheck::cli
