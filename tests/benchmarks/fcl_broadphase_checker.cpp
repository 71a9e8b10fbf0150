#include "fcl_broadphase_checker.hpp"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace hullcheck::bench {
namespace {

std::shared_ptr<fcl::CollisionGeometryd> to_fcl(const Shape& shape) {
  if (shape.margin() != 0.0) {
    throw std::runtime_error("FclBroadphaseChecker: padded shapes have no FCL counterpart");
  }
  const Shape::Geometry& g = shape.geometry();
  if (const auto* box = std::get_if<Box>(&g)) {
    return std::make_shared<fcl::Boxd>(2.0 * box->half_extents);
  }
  if (const auto* sphere = std::get_if<Sphere>(&g)) {
    return std::make_shared<fcl::Sphered>(sphere->radius);
  }
  if (const auto* cylinder = std::get_if<Cylinder>(&g)) {
    return std::make_shared<fcl::Cylinderd>(cylinder->radius, 2.0 * cylinder->half_length);
  }
  if (const auto* capsule = std::get_if<Capsule>(&g)) {
    return std::make_shared<fcl::Capsuled>(capsule->radius, 2.0 * capsule->half_length);
  }
  const auto& hull = std::get<ConvexHull>(g);
  auto vertices = std::make_shared<std::vector<Eigen::Vector3d>>(hull.vertices());
  auto faces = std::make_shared<std::vector<int>>();
  faces->reserve(hull.triangles().size() * 4);
  for (const auto& t : hull.triangles()) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
  // throw_if_invalid: a hull that is not watertight would make FCL fall back silently to a
  // linear-scan support function, and the comparison would not be what it claims.
  auto convex = std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.triangles().size()),
                                               faces, /*throw_if_invalid=*/true);
  return convex;
}

}  // namespace

class FclBroadphaseChecker::Impl {
 public:
  // The robot, matrix (scene's link pairs included) and scene of `hc`; obstacle/link pairs the
  // scene allows are resolved here as CollisionChecker does.
  explicit Impl(const CollisionChecker& hc)
      : model_(&hc.model()), matrix_(hc.matrix()), link_poses_(hc.model().links().size()) {
    const PlanningScene& scene = hc.scene();
    const int n_links = static_cast<int>(model_->links().size());
    link_object_allowed_.assign(static_cast<std::size_t>(n_links),
                                std::vector<bool>(scene.obstacles.size(), false));
    for (const auto& [first, second] : scene.allowed_pairs) {
      const int la = model_->link_index(first);
      const int lb = model_->link_index(second);
      if ((la >= 0) == (lb >= 0)) continue;  // link/link pairs are in hc.matrix() already
      const int link = la >= 0 ? la : lb;
      const std::string& object = la >= 0 ? second : first;
      for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
        if (scene.obstacles[o].object == object) {
          link_object_allowed_[static_cast<std::size_t>(link)][o] = true;
        }
      }
    }
    // User data points into infos_, which is sized once and never reallocated.
    std::size_t robot_shapes = 0;
    for (const Link& link : model_->links()) robot_shapes += link.shapes.size();
    infos_.reserve(robot_shapes + scene.obstacles.size());
    for (int l = 0; l < n_links; ++l) {
      const Link& link = model_->link(l);
      first_object_.push_back(static_cast<int>(robot_.size()));
      for (const CollisionShape& cs : link.shapes) {
        robot_.push_back(std::make_unique<fcl::CollisionObjectd>(to_fcl(cs.shape)));
        origins_.push_back(cs.origin);
        infos_.push_back({l, -1});
        robot_.back()->setUserData(&infos_.back());
        robot_links_.push_back(l);
      }
    }
    for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
      const Obstacle& obstacle = scene.obstacles[o];
      obstacles_.push_back(
          std::make_unique<fcl::CollisionObjectd>(to_fcl(obstacle.shape), obstacle.pose));
      infos_.push_back({-1, static_cast<int>(o)});
      obstacles_.back()->setUserData(&infos_.back());
    }
    // Robot objects registered at the default configuration, then moved per state.
    place(model_->default_configuration());
    std::vector<fcl::CollisionObjectd*> robot, obstacles;
    for (auto& r : robot_) robot.push_back(r.get());
    for (auto& o : obstacles_) obstacles.push_back(o.get());
    robot_manager_.registerObjects(robot);
    robot_manager_.setup();
    obstacle_manager_.registerObjects(obstacles);
    obstacle_manager_.setup();
    for (int a = 0; a < n_links && !has_self_pairs_; ++a) {
      for (int b = a + 1; b < n_links; ++b) {
        if (!matrix_.allowed(a, b) && !model_->link(a).shapes.empty() &&
            !model_->link(b).shapes.empty()) {
          has_self_pairs_ = true;
          break;
        }
      }
    }
    collision_request_.num_max_contacts = 1;
    collision_request_.enable_contact = false;
    collision_request_.gjk_solver_type = fcl::GST_LIBCCD;
    distance_request_.enable_nearest_points = false;
    distance_request_.enable_signed_distance = true;
    distance_request_.gjk_solver_type = fcl::GST_LIBCCD;
  }

  bool is_valid(const Eigen::VectorXd& q) {
    place(q);
    robot_manager_.update();
    collision_ = false;
    robot_manager_.collide(&obstacle_manager_, this, &Impl::collide_callback);
    if (!collision_ && has_self_pairs_) {
      robot_manager_.collide(this, &Impl::collide_callback);
    }
    return !collision_;
  }

  double clearance(const Eigen::VectorXd& q) {
    place(q);
    robot_manager_.update();
    min_distance_ = std::numeric_limits<double>::max();
    robot_manager_.distance(&obstacle_manager_, this, &Impl::distance_callback);
    if (min_distance_ > 0.0 && has_self_pairs_) {
      robot_manager_.distance(this, &Impl::distance_callback);
    }
    return min_distance_;
  }

  // FCL's signed distance of the pair hullcheck reports as closest, at the poses of the last
  // query, the smaller over both argument orders (libccd's GJK distance depends on the order
  // and can stop early on large hulls; the broad phase passes the pair in either order).
  double pair_distance(const ClearanceResult& r) {
    fcl::CollisionObjectd* a =
        robot_[static_cast<std::size_t>(first_object_[static_cast<std::size_t>(r.link_a)] +
                                        r.shape_a)]
            .get();
    fcl::CollisionObjectd* b =
        r.self ? robot_[static_cast<std::size_t>(first_object_[static_cast<std::size_t>(r.link_b)] +
                                                 r.shape_b)]
                     .get()
               : obstacles_[static_cast<std::size_t>(r.obstacle)].get();
    fcl::DistanceResultd ab, ba;
    fcl::distance(a, b, distance_request_, ab);
    fcl::distance(b, a, distance_request_, ba);
    return std::min(ab.min_distance, ba.min_distance);
  }

 private:
  struct Info {
    int link;      // robot link, or -1 for an obstacle
    int obstacle;  // scene obstacle, or -1 for a robot shape
  };

  void place(const Eigen::VectorXd& q) {
    model_->compute_link_poses_unchecked(q.data(), link_poses_.data());
    for (std::size_t i = 0; i < robot_.size(); ++i) {
      robot_[i]->setTransform(link_poses_[static_cast<std::size_t>(robot_links_[i])] * origins_[i]);
      robot_[i]->computeAABB();
    }
  }

  bool allowed(const fcl::CollisionObjectd* o1, const fcl::CollisionObjectd* o2) const {
    const Info& a = *static_cast<const Info*>(o1->getUserData());
    const Info& b = *static_cast<const Info*>(o2->getUserData());
    if (a.link >= 0 && b.link >= 0) return matrix_.allowed(a.link, b.link);
    if (a.link >= 0 && b.obstacle >= 0) {
      return link_object_allowed_[static_cast<std::size_t>(a.link)]
                                 [static_cast<std::size_t>(b.obstacle)];
    }
    if (b.link >= 0 && a.obstacle >= 0) {
      return link_object_allowed_[static_cast<std::size_t>(b.link)]
                                 [static_cast<std::size_t>(a.obstacle)];
    }
    return true;  // obstacle/obstacle: never checked
  }

  static bool collide_callback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
    auto& self = *static_cast<Impl*>(data);
    if (self.collision_) return true;
    if (self.allowed(o1, o2)) return false;
    self.collision_result_.clear();
    fcl::collide(o1, o2, self.collision_request_, self.collision_result_);
    self.collision_ = self.collision_result_.isCollision();
    return self.collision_;
  }

  static bool distance_callback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data,
                                double& dist) {
    auto& self = *static_cast<Impl*>(data);
    if (self.min_distance_ <= 0.0) {
      dist = self.min_distance_;
      return true;
    }
    if (!self.allowed(o1, o2)) {
      self.distance_result_.clear();
      fcl::distance(o1, o2, self.distance_request_, self.distance_result_);
      self.min_distance_ = std::min(self.min_distance_, self.distance_result_.min_distance);
    }
    dist = self.min_distance_;
    return self.min_distance_ <= 0.0;
  }

  const RobotModel* model_;
  AllowedCollisionMatrix matrix_;
  std::vector<std::vector<bool>> link_object_allowed_;
  std::vector<Info> infos_;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> robot_, obstacles_;
  std::vector<Eigen::Isometry3d> origins_;
  std::vector<int> robot_links_;
  std::vector<int> first_object_;  // per link: index of its first shape in robot_
  std::vector<Eigen::Isometry3d> link_poses_;
  fcl::DynamicAABBTreeCollisionManagerd robot_manager_, obstacle_manager_;
  bool has_self_pairs_ = false;
  fcl::CollisionRequestd collision_request_;
  fcl::CollisionResultd collision_result_;
  fcl::DistanceRequestd distance_request_;
  fcl::DistanceResultd distance_result_;
  bool collision_ = false;
  double min_distance_ = 0.0;
};

FclBroadphaseChecker::FclBroadphaseChecker(const CollisionChecker& hc)
    : impl_(std::make_unique<Impl>(hc)) {}
FclBroadphaseChecker::~FclBroadphaseChecker() = default;
bool FclBroadphaseChecker::is_valid(const Eigen::VectorXd& q) { return impl_->is_valid(q); }
double FclBroadphaseChecker::clearance(const Eigen::VectorXd& q) { return impl_->clearance(q); }
double FclBroadphaseChecker::pair_distance(const ClearanceResult& r) {
  return impl_->pair_distance(r);
}

}  // namespace hullcheck::bench
