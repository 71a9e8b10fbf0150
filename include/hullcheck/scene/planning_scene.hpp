// PlanningScene: static obstacles around a robot, from MoveIt PlanningScene YAML or a URDF.
#pragma once

#include <Eigen/Geometry>
#include <hullcheck/core/shape.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <string>
#include <utility>
#include <vector>

namespace hullcheck {

/// One static obstacle: a convex shape at a fixed pose in the robot's model frame.
struct Obstacle {
  std::string name;    ///< Object id; "id/2" for the third primitive of a multi-primitive object.
  std::string object;  ///< The collision object's id (shared by its primitives).
  Shape shape;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< Model frame <- shape frame.
  std::string source;  ///< "box", "sphere", "cylinder", "cone", "mesh", or a URDF link name.
};

/// Static obstacles and the scene's allowed collisions, in the robot's model frame (the frame
/// of the URDF's root link; MoveIt's planning frame for the data sets we read).
struct PlanningScene {
  std::string name;
  std::vector<Obstacle> obstacles;
  /// Pairs allowed to touch by the scene: (robot link, object id) or (link, link) names, both
  /// orders meaning the same. Object ids apply to every primitive of the object.
  std::vector<std::pair<std::string, std::string>> allowed_pairs;
  /// The scene's robot state (all joints it names), when it gives one: joint name -> value.
  std::vector<std::pair<std::string, double>> robot_joint_values;
};

/// Reads a MoveIt PlanningScene in YAML (moveit_msgs/PlanningScene as MoveIt and
/// MotionBenchMaker write it): `world.collision_objects[]` with `primitives` (box [x y z] full
/// sizes; sphere [r]; cylinder and cone [height, radius], axis z, centred) and
/// `primitive_poses`, `meshes` (vertices + triangles, hulled) and `mesh_poses`, an optional
/// object `pose` composed with each primitive pose, `header.frame_id` empty, "world", the
/// model's root link or any robot link (posed by forward kinematics at the scene's
/// `robot_state`, else the default configuration); `allowed_collision_matrix` entries that are
/// true; `robot_state.joint_state`. Positions and orientations as lists [x y z], [x y z w] or
/// maps {x: .., y: .., ...}. A cone is represented by the hull of a circumscribed 64-gon
/// pyramid (conservative by at most 0.13% of its radius). Units: metres.
/// Throws InputError naming the file, the object and the problem: unknown primitive type, wrong
/// dimension count, negative size, a quaternion whose norm is not 1 within 1e-3 (those within
/// are normalised), a frame that is neither the world nor a robot link, YAML syntax errors.
PlanningScene read_planning_scene(const std::string& path, const RobotModel& model);
/// The same from YAML text; `source_name` names it in errors.
PlanningScene parse_planning_scene(const std::string& yaml, const RobotModel& model,
                                   const std::string& source_name = "<scene string>");

/// A URDF as a static environment: every collision shape of every link, posed by forward
/// kinematics at the URDF's default configuration (RobotModel::default_configuration),
/// then placed by `environment_pose` (model frame <- environment root frame). Obstacle names
/// are "link" or "link/i" for a link's i-th shape; `object` is the link name.
PlanningScene planning_scene_from_urdf(const std::string& path,
                                       const Eigen::Isometry3d& environment_pose,
                                       const RobotLoadOptions& options = {});

}  // namespace hullcheck
