#include <algorithm>
#include <cmath>
#include <hullcheck/errors.hpp>
#include <hullcheck/queries.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <map>

namespace hullcheck {
namespace {

// Half extents of `shape`'s axis-aligned box in its own frame, and that box's centre.
void local_box(const Shape& shape, Eigen::Vector3d* center, Eigen::Vector3d* half) {
  center->setZero();
  const Shape::Geometry& g = shape.geometry();
  if (const auto* box = std::get_if<Box>(&g)) {
    *half = box->half_extents;
  } else if (const auto* sphere = std::get_if<Sphere>(&g)) {
    half->setConstant(sphere->radius);
  } else if (const auto* cylinder = std::get_if<Cylinder>(&g)) {
    *half = Eigen::Vector3d(cylinder->radius, cylinder->radius, cylinder->half_length);
  } else if (const auto* capsule = std::get_if<Capsule>(&g)) {
    *half =
        Eigen::Vector3d(capsule->radius, capsule->radius, capsule->half_length + capsule->radius);
  } else {
    const auto& hull = std::get<ConvexHull>(g);
    Eigen::Vector3d lo = hull.vertices().front(), hi = lo;
    for (const Eigen::Vector3d& v : hull.vertices()) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    *center = 0.5 * (lo + hi);
    *half = 0.5 * (hi - lo);
  }
  half->array() += shape.margin();
}

}  // namespace

struct CollisionChecker::Scratch {
  std::vector<Eigen::Isometry3d> link_poses;
  std::vector<Eigen::Isometry3d> shape_poses;
  std::vector<Eigen::Vector3d> centers;
  std::vector<double> lower_bounds;
};

CollisionChecker::Scratch& CollisionChecker::scratch() const {
  // One per thread, shared by every checker: a query uses it from start to end and never
  // calls another query meanwhile. Grows to the largest robot seen, then stays.
  thread_local Scratch s;
  const std::size_t links = model_->links().size();
  if (s.link_poses.size() != links) s.link_poses.resize(links);
  if (s.shape_poses.size() < shapes_.size()) {
    s.shape_poses.resize(shapes_.size());
    s.centers.resize(shapes_.size());
  }
  const std::size_t pairs = self_pairs_.size() + environment_pairs_.size();
  if (s.lower_bounds.size() < pairs) s.lower_bounds.resize(pairs);
  return s;
}

CollisionChecker::CollisionChecker(std::shared_ptr<const RobotModel> model,
                                   AllowedCollisionMatrix matrix, PlanningScene scene)
    : model_(std::move(model)), matrix_(std::move(matrix)), scene_(std::move(scene)) {
  if (!model_) throw InputError("CollisionChecker: model is null");
  const int n = static_cast<int>(model_->links().size());
  if (matrix_.link_count() != n) {
    throw InputError("CollisionChecker: collision matrix has " +
                     std::to_string(matrix_.link_count()) + " links, robot '" + model_->name() +
                     "' has " + std::to_string(n));
  }
  // Scene-allowed pairs: link/link into the matrix, link/object into a set.
  std::map<std::string, std::vector<int>> obstacles_of;
  for (std::size_t o = 0; o < scene_.obstacles.size(); ++o) {
    obstacles_of[scene_.obstacles[o].object].push_back(static_cast<int>(o));
  }
  std::vector<std::vector<bool>> link_object_allowed(
      static_cast<std::size_t>(n), std::vector<bool>(scene_.obstacles.size(), false));
  for (const auto& [first, second] : scene_.allowed_pairs) {
    const int la = model_->link_index(first);
    const int lb = model_->link_index(second);
    if (la >= 0 && lb >= 0) {
      if (la != lb) matrix_.allow(la, lb, CollisionAllowance::kUser);
      continue;
    }
    const int link = la >= 0 ? la : lb;
    const std::string& object = la >= 0 ? second : first;
    const auto it = obstacles_of.find(object);
    if (link < 0 || it == obstacles_of.end()) {
      // Entries for objects not in this scene (or links of another robot) change nothing;
      // MoveIt keeps such names in the matrix too.
      continue;
    }
    for (int o : it->second) {
      link_object_allowed[static_cast<std::size_t>(link)][static_cast<std::size_t>(o)] = true;
    }
  }

  std::vector<int> first_shape(static_cast<std::size_t>(n) + 1, 0);
  for (int l = 0; l < n; ++l) {
    first_shape[static_cast<std::size_t>(l)] = static_cast<int>(shapes_.size());
    const Link& link = model_->link(l);
    for (int s = 0; s < static_cast<int>(link.shapes.size()); ++s) {
      const CollisionShape& cs = link.shapes[static_cast<std::size_t>(s)];
      shapes_.push_back({l, s, cs.origin * cs.bounding_center, cs.bounding_radius, link.name});
    }
  }
  first_shape[static_cast<std::size_t>(n)] = static_cast<int>(shapes_.size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (matrix_.allowed(a, b)) continue;
      for (int sa = first_shape[static_cast<std::size_t>(a)];
           sa < first_shape[static_cast<std::size_t>(a) + 1]; ++sa) {
        for (int sb = first_shape[static_cast<std::size_t>(b)];
             sb < first_shape[static_cast<std::size_t>(b) + 1]; ++sb) {
          self_pairs_.push_back({sa, sb});
        }
      }
    }
  }
  has_self_pairs_ = !self_pairs_.empty();
  for (const Obstacle& o : scene_.obstacles) {
    Eigen::Vector3d center, half;
    local_box(o.shape, &center, &half);
    boxes_.push_back({o.pose.linear().transpose(), o.pose * center, half});
  }
  for (int s = 0; s < static_cast<int>(shapes_.size()); ++s) {
    const auto link = static_cast<std::size_t>(shapes_[static_cast<std::size_t>(s)].link);
    for (int o = 0; o < static_cast<int>(scene_.obstacles.size()); ++o) {
      if (!link_object_allowed[link][static_cast<std::size_t>(o)]) {
        environment_pairs_.push_back({s, o});
      }
    }
  }

  // Lever arms for motion_bound. reach[l]: bound on the distance from a joint's origin to the
  // frame origin of link l below it, accumulated along the chain.
  lever_ = Eigen::VectorXd::Zero(model_->variable_count());
  std::vector<double> reach(static_cast<std::size_t>(n));
  for (const Joint& joint : model_->joints()) {
    if (joint.type == JointType::kFixed) continue;
    const int variable = joint.mimic_variable >= 0 ? joint.mimic_variable : joint.variable;
    const double multiplier = joint.mimic_variable >= 0 ? std::abs(joint.mimic_multiplier) : 1.0;
    if (joint.type == JointType::kPrismatic) {
      lever_[variable] += multiplier;
      continue;
    }
    double arm = 0.0;
    std::vector<int> stack{joint.child_link};
    reach[static_cast<std::size_t>(joint.child_link)] = 0.0;
    while (!stack.empty()) {
      const int l = stack.back();
      stack.pop_back();
      for (const CollisionShape& cs : model_->link(l).shapes) {
        arm = std::max(arm, reach[static_cast<std::size_t>(l)] +
                                (cs.origin * cs.bounding_center).norm() + cs.bounding_radius);
      }
      for (int k : model_->link(l).child_joints) {
        const Joint& child = model_->joint(k);
        double travel = 0.0;
        if (child.type == JointType::kPrismatic) {
          travel = std::max(std::abs(child.lower), std::abs(child.upper)) *
                       (child.mimic_variable >= 0 ? std::abs(child.mimic_multiplier) : 1.0) +
                   (child.mimic_variable >= 0 ? std::abs(child.mimic_offset) : 0.0);
        }
        reach[static_cast<std::size_t>(child.child_link)] =
            reach[static_cast<std::size_t>(l)] + child.origin.translation().norm() + travel;
        stack.push_back(child.child_link);
      }
    }
    lever_[variable] += multiplier * arm;
  }
}

void CollisionChecker::place(const std::vector<Eigen::Isometry3d>& link_poses, Scratch& s) const {
  if (link_poses.size() != model_->links().size()) {
    throw InputError("CollisionChecker: got " + std::to_string(link_poses.size()) +
                     " link poses, robot '" + model_->name() + "' has " +
                     std::to_string(model_->links().size()) + " links");
  }
  for (std::size_t i = 0; i < shapes_.size(); ++i) {
    const RobotShape& rs = shapes_[i];
    const Eigen::Isometry3d& link_pose = link_poses[static_cast<std::size_t>(rs.link)];
    s.shape_poses[i] =
        link_pose * model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].origin;
    s.centers[i] = link_pose * rs.center;
  }
}

double CollisionChecker::box_gap(const ObstacleBox& box, const Eigen::Vector3d& c,
                                 double radius) const {
  const Eigen::Vector3d local = box.rotation_t * (c - box.center);
  const Eigen::Vector3d outside = (local.cwiseAbs() - box.half_extents).cwiseMax(0.0);
  return outside.norm() - radius;
}

bool CollisionChecker::is_valid(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  model_->check_configuration(q);
  Scratch& s = scratch();
  model_->compute_link_poses_unchecked(q.data(), s.link_poses.data());
  return is_valid_at(s.link_poses);
}

bool CollisionChecker::is_valid_at(const std::vector<Eigen::Isometry3d>& link_poses) const {
  Scratch& s = scratch();
  place(link_poses, s);
  for (const EnvironmentPair& p : environment_pairs_) {
    const RobotShape& rs = shapes_[static_cast<std::size_t>(p.shape)];
    if (box_gap(boxes_[static_cast<std::size_t>(p.obstacle)],
                s.centers[static_cast<std::size_t>(p.shape)], rs.radius) > 0.0) {
      continue;
    }
    const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(p.obstacle)];
    if (intersect(model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].shape,
                  s.shape_poses[static_cast<std::size_t>(p.shape)], o.shape, o.pose)) {
      return false;
    }
  }
  for (const SelfPair& p : self_pairs_) {
    const RobotShape& a = shapes_[static_cast<std::size_t>(p.a)];
    const RobotShape& b = shapes_[static_cast<std::size_t>(p.b)];
    const double reach = a.radius + b.radius;
    if ((s.centers[static_cast<std::size_t>(p.a)] - s.centers[static_cast<std::size_t>(p.b)])
            .squaredNorm() > reach * reach) {
      continue;
    }
    if (intersect(model_->link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape,
                  s.shape_poses[static_cast<std::size_t>(p.a)],
                  model_->link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape,
                  s.shape_poses[static_cast<std::size_t>(p.b)])) {
      return false;
    }
  }
  return true;
}

ClearanceResult CollisionChecker::clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  model_->check_configuration(q);
  Scratch& s = scratch();
  model_->compute_link_poses_unchecked(q.data(), s.link_poses.data());
  return clearance_at(s.link_poses);
}

ClearanceResult CollisionChecker::clearance_at(
    const std::vector<Eigen::Isometry3d>& link_poses) const {
  Scratch& s = scratch();
  place(link_poses, s);
  ClearanceResult best;
  const std::size_t n_env = environment_pairs_.size();
  const std::size_t n_all = n_env + self_pairs_.size();
  if (n_all == 0) return best;
  // Lower bounds: ball against oriented box (environment), ball against ball (self).
  std::size_t first = 0;
  for (std::size_t i = 0; i < n_all; ++i) {
    double lb;
    if (i < n_env) {
      const EnvironmentPair& p = environment_pairs_[i];
      lb = box_gap(boxes_[static_cast<std::size_t>(p.obstacle)],
                   s.centers[static_cast<std::size_t>(p.shape)],
                   shapes_[static_cast<std::size_t>(p.shape)].radius);
    } else {
      const SelfPair& p = self_pairs_[i - n_env];
      lb = (s.centers[static_cast<std::size_t>(p.a)] - s.centers[static_cast<std::size_t>(p.b)])
               .norm() -
           shapes_[static_cast<std::size_t>(p.a)].radius -
           shapes_[static_cast<std::size_t>(p.b)].radius;
    }
    s.lower_bounds[i] = lb;
    if (lb < s.lower_bounds[first]) first = i;
  }
  const auto evaluate = [&](std::size_t i) {
    ++best.exact_queries;
    if (i < n_env) {
      const EnvironmentPair& p = environment_pairs_[i];
      const RobotShape& rs = shapes_[static_cast<std::size_t>(p.shape)];
      const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(p.obstacle)];
      const SignedDistanceResult r =
          signed_distance(model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].shape,
                          s.shape_poses[static_cast<std::size_t>(p.shape)], o.shape, o.pose);
      if (r.signed_distance < best.distance) {
        best.distance = r.signed_distance;
        best.self = false;
        best.link_a = rs.link;
        best.shape_a = rs.shape;
        best.link_b = best.shape_b = -1;
        best.obstacle = p.obstacle;
        best.name_a = rs.link_name;
        best.name_b = o.name;
        best.point_a = r.point_a;
        best.point_b = r.point_b;
        best.normal = r.normal;
        best.status = r.status;
      }
    } else {
      const SelfPair& p = self_pairs_[i - n_env];
      const RobotShape& a = shapes_[static_cast<std::size_t>(p.a)];
      const RobotShape& b = shapes_[static_cast<std::size_t>(p.b)];
      const SignedDistanceResult r =
          signed_distance(model_->link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape,
                          s.shape_poses[static_cast<std::size_t>(p.a)],
                          model_->link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape,
                          s.shape_poses[static_cast<std::size_t>(p.b)]);
      if (r.signed_distance < best.distance) {
        best.distance = r.signed_distance;
        best.self = true;
        best.link_a = a.link;
        best.shape_a = a.shape;
        best.link_b = b.link;
        best.shape_b = b.shape;
        best.obstacle = -1;
        best.name_a = a.link_name;
        best.name_b = b.link_name;
        best.point_a = r.point_a;
        best.point_b = r.point_b;
        best.normal = r.normal;
        best.status = r.status;
      }
    }
  };
  evaluate(first);
  for (std::size_t i = 0; i < n_all; ++i) {
    if (i != first && s.lower_bounds[i] < best.distance) evaluate(i);
  }
  return best;
}

double CollisionChecker::motion_bound(const Eigen::Ref<const Eigen::VectorXd>& q0,
                                      const Eigen::Ref<const Eigen::VectorXd>& q1) const {
  model_->check_configuration(q0);
  model_->check_configuration(q1);
  const double bound = (q1 - q0).cwiseAbs().dot(lever_);
  return has_self_pairs_ ? 2.0 * bound : bound;
}

}  // namespace hullcheck
