// SelfCollisionChecker: self-collision test and minimum signed distance between a robot's links.
#pragma once

#include <Eigen/Geometry>
#include <hullcheck/core/query_result.hpp>
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <limits>
#include <memory>
#include <string_view>
#include <vector>

namespace hullcheck {

/// The closest (or deepest) pair of shapes between two links.
struct LinkPairProximity {
  /// Signed distance, m: > 0 apart, < 0 overlapping (minus the penetration depth, by EPA).
  /// +inf when no pair is checked.
  double distance = std::numeric_limits<double>::infinity();
  int link_a = -1;  ///< Link indices into RobotModel::links(); -1 when no pair is checked.
  int link_b = -1;
  std::string_view link_a_name;  ///< Names, valid while the model lives.
  std::string_view link_b_name;
  int shape_a = -1;  ///< Index into the link's shapes.
  int shape_b = -1;
  Eigen::Vector3d point_a{0, 0, 0};  ///< Witness points, model frame, m.
  Eigen::Vector3d point_b{0, 0, 0};
  Eigen::Vector3d normal{0, 0, 0};  ///< Unit, from A to B; point_b - point_a = distance*normal.
  Status status = Status::kConverged;
  int exact_queries = 0;  ///< Shape pairs that needed GJK (the rest were culled by balls).
};

/// Self-collision queries for one robot and one allowed-collision matrix.
///
/// Checks every shape pair of every link pair the matrix does not allow, with the shapes'
/// padding. A bounding-ball test culls far pairs before exact GJK/EPA. Tolerances are the
/// core queries' (query_options.hpp). Holds scratch storage, so one instance must not be used
/// by two threads at once; copies are cheap and independent. Queries do not allocate.
class SelfCollisionChecker {
 public:
  /// Throws InputError when the matrix is not sized for the model's links.
  SelfCollisionChecker(std::shared_ptr<const RobotModel> model, const AllowedCollisionMatrix& acm);

  const RobotModel& model() const { return *model_; }
  /// Checked link pairs (a < b) in the order they are tested.
  const std::vector<std::pair<int, int>>& checked_link_pairs() const { return link_pairs_; }

  /// True when any checked pair overlaps at configuration q (checked, see
  /// RobotModel::check_configuration).
  bool in_collision(const Eigen::Ref<const Eigen::VectorXd>& q);
  /// The checked pair with the smallest signed distance at q, with witnesses.
  LinkPairProximity min_distance(const Eigen::Ref<const Eigen::VectorXd>& q);

  /// The same for link poses already computed (RobotModel::compute_link_poses).
  bool in_collision_at(const std::vector<Eigen::Isometry3d>& link_poses);
  LinkPairProximity min_distance_at(const std::vector<Eigen::Isometry3d>& link_poses);
  /// Every checked link pair that overlaps, as (a, b) with a < b, appended to `out`.
  void colliding_link_pairs_at(const std::vector<Eigen::Isometry3d>& link_poses,
                               std::vector<std::pair<int, int>>& out);

 private:
  struct ShapeRef {
    int link;
    int shape;
  };
  struct ShapePair {
    int a;  // indices into shapes_
    int b;
    int link_pair;  // index into link_pairs_
  };
  void place_shapes(const std::vector<Eigen::Isometry3d>& link_poses);
  bool pair_overlaps(const ShapePair& p) const;

  std::shared_ptr<const RobotModel> model_;
  std::vector<std::pair<int, int>> link_pairs_;
  std::vector<ShapeRef> shapes_;
  std::vector<ShapePair> shape_pairs_;
  // Scratch, sized at construction.
  std::vector<Eigen::Isometry3d> link_poses_;
  std::vector<Eigen::Isometry3d> shape_poses_;
  std::vector<Eigen::Vector3d> shape_centers_;
  std::vector<double> lower_bounds_;
};

}  // namespace hullcheck
