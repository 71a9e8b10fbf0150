#include <algorithm>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/robot/self_collision.hpp>

namespace hullcheck {

SelfCollisionChecker::SelfCollisionChecker(std::shared_ptr<const RobotModel> model,
                                           const AllowedCollisionMatrix& acm)
    : model_(std::move(model)) {
  if (!model_) throw InputError("SelfCollisionChecker: model is null");
  const int n = static_cast<int>(model_->links().size());
  if (acm.link_count() != n) {
    throw InputError("SelfCollisionChecker: collision matrix has " +
                     std::to_string(acm.link_count()) + " links, robot '" + model_->name() +
                     "' has " + std::to_string(n));
  }
  std::vector<int> first_shape(static_cast<std::size_t>(n) + 1, 0);
  for (int l = 0; l < n; ++l) {
    first_shape[static_cast<std::size_t>(l)] = static_cast<int>(shapes_.size());
    for (int s = 0; s < static_cast<int>(model_->link(l).shapes.size()); ++s) {
      shapes_.push_back({l, s});
    }
  }
  first_shape[static_cast<std::size_t>(n)] = static_cast<int>(shapes_.size());
  // Pairs of links with geometry only: quadratic in those, not in all links.
  const std::vector<int> solid = model_->links_with_geometry();
  for (std::size_t i = 0; i < solid.size(); ++i) {
    for (std::size_t k = i + 1; k < solid.size(); ++k) {
      const int a = solid[i];
      const int b = solid[k];
      if (acm.allowed(a, b)) continue;
      const int pair = static_cast<int>(link_pairs_.size());
      link_pairs_.emplace_back(a, b);
      for (int sa = first_shape[a]; sa < first_shape[a + 1]; ++sa) {
        for (int sb = first_shape[b]; sb < first_shape[b + 1]; ++sb) {
          shape_pairs_.push_back({sa, sb, pair});
        }
      }
    }
  }
  link_poses_.resize(static_cast<std::size_t>(n));
  shape_poses_.resize(shapes_.size());
  shape_centers_.resize(shapes_.size());
  lower_bounds_.resize(shape_pairs_.size());
}

void SelfCollisionChecker::place_shapes(const std::vector<Eigen::Isometry3d>& link_poses) {
  if (link_poses.size() != model_->links().size()) {
    throw InputError("SelfCollisionChecker: got " + std::to_string(link_poses.size()) +
                     " link poses, robot '" + model_->name() + "' has " +
                     std::to_string(model_->links().size()) + " links");
  }
  for (std::size_t i = 0; i < shapes_.size(); ++i) {
    const CollisionShape& s =
        model_->link(shapes_[i].link).shapes[static_cast<std::size_t>(shapes_[i].shape)];
    const Eigen::Isometry3d& link_pose = link_poses[static_cast<std::size_t>(shapes_[i].link)];
    shape_poses_[i] = link_pose * s.origin;
    shape_centers_[i] = shape_poses_[i] * s.bounding_center;
  }
}

bool SelfCollisionChecker::pair_overlaps(const ShapePair& p) const {
  const ShapeRef& ra = shapes_[static_cast<std::size_t>(p.a)];
  const ShapeRef& rb = shapes_[static_cast<std::size_t>(p.b)];
  const CollisionShape& a = model_->link(ra.link).shapes[static_cast<std::size_t>(ra.shape)];
  const CollisionShape& b = model_->link(rb.link).shapes[static_cast<std::size_t>(rb.shape)];
  const double reach = a.bounding_radius + b.bounding_radius;
  if ((shape_centers_[static_cast<std::size_t>(p.a)] -
       shape_centers_[static_cast<std::size_t>(p.b)])
          .squaredNorm() > reach * reach) {
    return false;
  }
  return intersect(a.shape, shape_poses_[static_cast<std::size_t>(p.a)], b.shape,
                   shape_poses_[static_cast<std::size_t>(p.b)]);
}

bool SelfCollisionChecker::in_collision(const Eigen::Ref<const Eigen::VectorXd>& q) {
  model_->compute_link_poses(q, link_poses_);
  return in_collision_at(link_poses_);
}

LinkPairProximity SelfCollisionChecker::min_distance(const Eigen::Ref<const Eigen::VectorXd>& q) {
  model_->compute_link_poses(q, link_poses_);
  return min_distance_at(link_poses_);
}

bool SelfCollisionChecker::in_collision_at(const std::vector<Eigen::Isometry3d>& link_poses) {
  place_shapes(link_poses);
  for (const ShapePair& p : shape_pairs_) {
    if (pair_overlaps(p)) return true;
  }
  return false;
}

void SelfCollisionChecker::colliding_link_pairs_at(const std::vector<Eigen::Isometry3d>& link_poses,
                                                   std::vector<std::pair<int, int>>& out) {
  place_shapes(link_poses);
  int last = -1;
  for (const ShapePair& p : shape_pairs_) {
    if (p.link_pair == last) continue;  // this link pair is already reported
    if (pair_overlaps(p)) {
      out.push_back(link_pairs_[static_cast<std::size_t>(p.link_pair)]);
      last = p.link_pair;
    }
  }
}

LinkPairProximity SelfCollisionChecker::min_distance_at(
    const std::vector<Eigen::Isometry3d>& link_poses) {
  place_shapes(link_poses);
  LinkPairProximity best;
  if (shape_pairs_.empty()) return best;
  // Lower bounds from the bounding balls; start with the most promising pair so that the
  // bound culls most of the rest.
  std::size_t first = 0;
  for (std::size_t i = 0; i < shape_pairs_.size(); ++i) {
    const ShapePair& p = shape_pairs_[i];
    const ShapeRef& ra = shapes_[static_cast<std::size_t>(p.a)];
    const ShapeRef& rb = shapes_[static_cast<std::size_t>(p.b)];
    const double ra_radius =
        model_->link(ra.link).shapes[static_cast<std::size_t>(ra.shape)].bounding_radius;
    const double rb_radius =
        model_->link(rb.link).shapes[static_cast<std::size_t>(rb.shape)].bounding_radius;
    lower_bounds_[i] = (shape_centers_[static_cast<std::size_t>(p.a)] -
                        shape_centers_[static_cast<std::size_t>(p.b)])
                           .norm() -
                       ra_radius - rb_radius;
    if (lower_bounds_[i] < lower_bounds_[first]) first = i;
  }
  const auto evaluate = [&](std::size_t i) {
    const ShapePair& p = shape_pairs_[i];
    const ShapeRef& ra = shapes_[static_cast<std::size_t>(p.a)];
    const ShapeRef& rb = shapes_[static_cast<std::size_t>(p.b)];
    const CollisionShape& a = model_->link(ra.link).shapes[static_cast<std::size_t>(ra.shape)];
    const CollisionShape& b = model_->link(rb.link).shapes[static_cast<std::size_t>(rb.shape)];
    const SignedDistanceResult r =
        signed_distance(a.shape, shape_poses_[static_cast<std::size_t>(p.a)], b.shape,
                        shape_poses_[static_cast<std::size_t>(p.b)]);
    ++best.exact_queries;
    if (r.signed_distance < best.distance) {
      best.distance = r.signed_distance;
      best.link_a = ra.link;
      best.link_b = rb.link;
      best.shape_a = ra.shape;
      best.shape_b = rb.shape;
      best.point_a = r.point_a;
      best.point_b = r.point_b;
      best.normal = r.normal;
      best.status = r.status;
    }
  };
  evaluate(first);
  for (std::size_t i = 0; i < shape_pairs_.size(); ++i) {
    if (i != first && lower_bounds_[i] < best.distance) evaluate(i);
  }
  if (best.link_a < 0) {
    // Only reachable with NaN distances, which the loaders' and shapes' range checks exclude.
    throw InputError("SelfCollisionChecker: robot '" + model_->name() +
                     "': no link pair has a defined distance (shapes or poses out of range)");
  }
  best.link_a_name = model_->link(best.link_a).name;
  best.link_b_name = model_->link(best.link_b).name;
  return best;
}

}  // namespace hullcheck
