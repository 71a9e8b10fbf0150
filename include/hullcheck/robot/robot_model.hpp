// RobotModel: a URDF robot as links with convex collision shapes, and its forward kinematics.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <hullcheck/core/shape.hpp>
#include <hullcheck/robot/convex_decomposition.hpp>
#include <hullcheck/robot/link_pose_block.hpp>
#include <hullcheck/robot/mesh_file.hpp>
#include <hullcheck/robot/resource_path.hpp>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace hullcheck {

/// Joint types of URDF. Floating and planar joints are rejected at load time (InputError).
enum class JointType { kRevolute, kContinuous, kPrismatic, kFixed };

/// One joint of the kinematic tree, as the URDF gives it.
struct Joint {
  std::string name;
  JointType type = JointType::kFixed;
  int parent_link = -1;  // index into RobotModel::links()
  int child_link = -1;
  /// Parent link frame -> joint frame (URDF <origin>); the child link frame is the joint frame
  /// moved by the joint's position.
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  /// Unit axis in the joint frame (URDF <axis>, normalised; default x).
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  /// Position limits in rad (revolute) or m (prismatic); -inf..inf for continuous and fixed.
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  double max_velocity = std::numeric_limits<double>::infinity();  // rad/s or m/s; inf if unset
  /// Index into the configuration vector, or -1 for fixed and mimic joints.
  int variable = -1;
  /// Mimic joints: position = multiplier * position(variable `mimic_variable`) + offset, with
  /// chains of mimics resolved to the active joint at their end. -1 when not a mimic.
  int mimic_variable = -1;
  double mimic_multiplier = 1.0;
  double mimic_offset = 0.0;

  /// The configuration value that moves this joint (its own, or its mimic leader's); -1 for
  /// fixed joints. position = driver_multiplier() * q[driver()] + driver_offset().
  int driver() const { return mimic_variable >= 0 ? mimic_variable : variable; }
  double driver_multiplier() const { return mimic_variable >= 0 ? mimic_multiplier : 1.0; }
  double driver_offset() const { return mimic_variable >= 0 ? mimic_offset : 0.0; }
  /// Largest |position| within the limits (prismatic: the farthest travel, m).
  double limit_reach() const {
    return std::abs(driver_multiplier()) * std::max(std::abs(lower), std::abs(upper)) +
           std::abs(driver_offset());
  }
};

/// One convex shape of a link: a URDF <collision> element, or one convex piece of a mesh
/// element (RobotLoadOptions::mesh_geometry).
struct CollisionShape {
  /// The shape with its padding applied (what queries use).
  Shape shape;
  /// The shape without padding (box, sphere, cylinder exactly; a mesh as the convex hull of
  /// its vertices after URDF scale, or of one piece of its decomposition).
  Shape unpadded;
  /// Link frame -> shape frame (URDF <collision><origin>).
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  /// Ball bounding `shape` (padding included): centre in the shape frame and radius, m.
  Eigen::Vector3d bounding_center = Eigen::Vector3d::Zero();
  double bounding_radius = 0.0;
  /// "box", "sphere", "cylinder", or the resolved mesh file path.
  std::string source;
  /// Vertex count of the mesh file (0 for primitives); the hull's count is in `unpadded`.
  std::size_t mesh_vertex_count = 0;
  /// Which <collision> element of the link this shape comes from (0-based, file order).
  int element = 0;
  /// This shape is piece `piece` of `piece_count` of that element (0 of 1 unless decomposed).
  int piece = 0;
  int piece_count = 1;
  /// For a piece of a decomposed mesh (piece_count > 1): the convex hull of all the element's
  /// pieces (the mesh's hull), padded like `shape`; it contains every piece, so whatever is
  /// clear of it is clear of all of them (the checker's first test). Null otherwise.
  std::shared_ptr<const Shape> element_hull = nullptr;
  /// The same without padding, shared by the element's pieces.
  std::shared_ptr<const ConvexHull> element_hull_unpadded = nullptr;
  /// For a mesh: proven bound, m, on how far the element's shapes' surfaces reach beyond the
  /// mesh's solid (the decomposition's bound; for a hull, the hull's own, when measured). 0
  /// for primitives; -1 when not measured (MeshGeometry::kHull).
  double mesh_excess = 0.0;
};

/// How a mesh <collision> element becomes convex shapes.
enum class MeshGeometry {
  /// One convex hull per mesh: exact for convex meshes, covers concave ones by their hull
  /// (which can report collisions the mesh does not have).
  kHull,
  /// Convex pieces covering the mesh's solid, within RobotLoadOptions::decomposition.tolerance
  /// of it (decompose_mesh); a mesh within tolerance of its hull stays one piece.
  kDecompose,
};

/// One link: a rigid body with zero or more collision shapes.
struct Link {
  std::string name;
  int parent_joint = -1;  // -1 for the root link
  std::vector<int> child_joints;
  std::vector<CollisionShape> shapes;
  double padding = 0.0;  // m, applied to every shape of the link
};

/// Options for loading a URDF.
struct RobotLoadOptions {
  /// Package folders for package:// URIs, searched before the environment (resource_path.hpp).
  /// Each must be an existing folder (InputError otherwise).
  PackageMap packages;
  /// Padding (inflation margin, m, >= 0) of links not named in `link_padding`.
  double default_padding = 0.0;
  /// Padding per link name (m, >= 0). Unknown link names are an error.
  std::map<std::string, double> link_padding;
  /// Size, count and memory limits for each collision mesh file (mesh_file.hpp).
  MeshLimits mesh_limits;
  /// Meshes as convex pieces (default) or as one hull each.
  MeshGeometry mesh_geometry = MeshGeometry::kDecompose;
  /// Tolerance (m) and piece budget of the decomposition (convex_decomposition.hpp).
  DecompositionOptions decomposition;
  /// Folder of cached decompositions (decomposition_cache.hpp); empty: the default folder
  /// default_decomposition_cache_dir(). Ignored when `use_decomposition_cache` is false.
  std::string decomposition_cache_dir;
  bool use_decomposition_cache = true;
};

/// A robot loaded from URDF: links, joints, collision shapes, and forward kinematics.
///
/// Frames: every pose is in the model frame, the frame of the URDF's root link. Units: metres
/// and radians. The configuration vector q holds one value per active joint (revolute,
/// continuous, prismatic; not fixed, not mimic), ordered depth-first from the root link, the
/// children of a link in the order their joints appear in the URDF file; `variable_names()`
/// gives that order and `variable_index()` looks names up. Limits are not enforced by
/// kinematics (data sets hold states slightly outside them).
///
/// Collision meshes become convex pieces within a tolerance of the mesh (default 3 mm), or one
/// convex hull each (RobotLoadOptions::mesh_geometry); decompositions are cached on disk
/// (decomposition_cache.hpp), so a robot's first load may take seconds and later ones do not.
/// Visual geometry is ignored (its meshes need not exist). Loading throws InputError naming
/// the file, element and problem: malformed XML, an unresolvable or unreadable collision
/// mesh or one beyond `RobotLoadOptions::mesh_limits`, joints that do not form one tree
/// (a cycle, a link with two parent joints, several roots, links unreachable from the root),
/// a shape dimension, mesh vertex or origin translation that is not finite or exceeds 1e6 m,
/// a revolute/prismatic joint without limits, a floating or planar joint, a mimic of an
/// unknown joint, bad padding. Immutable after loading except for padding; const methods are
/// thread-safe.
class RobotModel {
 public:
  /// Loads the URDF file at `path`; relative mesh paths resolve against its folder.
  static RobotModel from_urdf_file(const std::string& path, const RobotLoadOptions& options = {});
  /// Loads URDF text; `base_dir` is where relative paths resolve and package search starts;
  /// `source_name` names the text in error messages.
  static RobotModel from_urdf_string(const std::string& xml, const std::string& base_dir,
                                     const RobotLoadOptions& options = {},
                                     const std::string& source_name = "<urdf string>");

  const std::string& name() const { return name_; }
  const std::string& source() const { return source_; }
  const std::vector<Link>& links() const { return links_; }
  const std::vector<Joint>& joints() const { return joints_; }
  const Link& link(int i) const { return links_.at(static_cast<std::size_t>(i)); }
  const Joint& joint(int i) const { return joints_.at(static_cast<std::size_t>(i)); }
  /// Indices of the links with collision geometry (at least one shape), ascending: the only
  /// links that take part in collision pairs.
  std::vector<int> links_with_geometry() const;
  /// Index of the link / joint called `name`, or -1.
  int link_index(const std::string& name) const;
  int joint_index(const std::string& name) const;

  /// Number of configuration values (active joints).
  int variable_count() const { return static_cast<int>(variable_joints_.size()); }
  /// Joint index of configuration value i.
  int variable_joint(int i) const { return variable_joints_.at(static_cast<std::size_t>(i)); }
  /// Names of the active joints in configuration order.
  std::vector<std::string> variable_names() const;
  /// Configuration index of the active joint `name`; -1 when it is not an active joint.
  int variable_index(const std::string& name) const;
  /// Per-variable bounds (lower/upper, -inf/inf for continuous joints).
  Eigen::VectorXd lower_limits() const;
  Eigen::VectorXd upper_limits() const;
  /// A default configuration, MoveIt's convention: each value 0 when 0 is within the joint's
  /// limits, else the middle of its range.
  Eigen::VectorXd default_configuration() const;

  /// Throws InputError unless q has variable_count() finite values (the message names the
  /// robot, the expected count or the joint holding the bad value).
  void check_configuration(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  /// How far (rad or m) a revolute or prismatic joint value may lie outside its limits and still
  /// pass check_joint_ranges (data sets hold states slightly outside them).
  static constexpr double kLimitTolerance = 1e-3;
  /// Largest |value| (rad) check_joint_ranges accepts for a continuous joint.
  static constexpr double kMaxContinuousValue = 1e6;

  /// Throws InputError naming the robot, the joint, the value and the joint's range unless
  /// `value` (rad or m) of configuration value `variable` is within the joint's limits widened
  /// by `tolerance` (rad or m, >= 0) for a revolute/prismatic joint, or at most
  /// kMaxContinuousValue in magnitude for a continuous one. The check of values entering
  /// planning and motion validation (JointStateSpace::from_configuration for the group's
  /// values, the program's paths and start/goal states): a value far outside the range would
  /// make motion checks crawl. Does not allocate unless it throws.
  void check_joint_range(int variable, double value, double tolerance = kLimitTolerance) const;
  /// check_configuration, then check_joint_range for every value of q.
  void check_joint_ranges(const Eigen::Ref<const Eigen::VectorXd>& q,
                          double tolerance = kLimitTolerance) const;

  /// Forward kinematics: writes every link's pose (model frame <- link frame) into
  /// `link_poses`, indexed like links(). Checks q (check_configuration). Does not allocate
  /// when `link_poses` already has links().size() entries.
  void compute_link_poses(const Eigen::Ref<const Eigen::VectorXd>& q,
                          std::vector<Eigen::Isometry3d>& link_poses) const;
  /// The same without checks, for hot loops: q points to variable_count() finite values and
  /// link_poses to links().size() poses.
  void compute_link_poses_unchecked(const double* q, Eigen::Isometry3d* link_poses) const;
  /// Forward kinematics of `count` (1..kPoseBlockLanes) configurations at once, vectorised
  /// across them (SIMD, the widest the CPU supports, chosen at run time): configuration k's
  /// values start at q + k * stride (a column-major matrix's columns: stride = rows), each
  /// variable_count() finite values (unchecked, as above). Lanes from `count` on repeat the last
  /// configuration. Poses agree with compute_link_poses to rounding (about 1e-15 relative; sin
  /// and cos are SIMD approximations within a few ulp), not bit for bit: callers needing exact
  /// answers use them only with a tolerance (CollisionChecker::is_valid_batch's broad phase).
  /// Thread-safe; allocates only while `out` or this thread's scratch grows.
  void compute_link_poses_block(const double* q, std::ptrdiff_t stride, int count,
                                LinkPoseBlock& out) const;

  /// Sets the padding of one link / of every link not given its own; re-inflates the shapes.
  /// Not thread-safe with concurrent queries on this model.
  void set_link_padding(const std::string& link, double padding);
  void set_default_padding(double padding);
  /// How many times the padding was set since loading: objects built from the padded shapes
  /// (CollisionChecker's bounding volumes) compare it to detect a stale copy.
  int padding_revision() const { return padding_revision_; }

 private:
  // One step of forward kinematics, in link order (parents first):
  // pose[link] = pose[anchor] * offset * motion(value), where anchor is the nearest ancestor
  // reached through a movable joint (fixed joints are folded into `offset`).
  struct KinematicStep {
    int link = 0;
    int anchor = -1;  // -1: the model frame
    Eigen::Matrix3d offset_rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d offset_translation = Eigen::Vector3d::Zero();
    JointType type = JointType::kFixed;
    int axis_index = -1;  // 0/1/2 when the axis is +-x/y/z, else -1
    double axis_sign = 1.0;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
    int variable = -1;  // configuration value driving the joint (itself or its mimic leader)
    double multiplier = 1.0;
    double offset = 0.0;
  };

  void apply_padding();
  void build_kinematics();

  std::string name_;
  std::string source_;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<int> variable_joints_;
  std::vector<KinematicStep> steps_;
  // Unique per build_kinematics() (copies share it with their identical steps_): keys the
  // per-thread plain copy of steps_ that compute_link_poses_block keeps.
  std::uint64_t kinematics_id_ = 0;
  std::map<std::string, int> link_by_name_;
  std::map<std::string, int> joint_by_name_;
  std::map<std::string, double> link_padding_;
  double default_padding_ = 0.0;
  int padding_revision_ = 0;
};

}  // namespace hullcheck
