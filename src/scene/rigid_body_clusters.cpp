// CollisionChecker's self clusters: the self blocks that join the same two rigid bodies (links
// joined by fixed joints: a gripper's fingers, sensor and flange, say), tested first as one
// pair of convex hulls by check_motion. A body's hull depends on the model only, so the
// checkers of one model share it, like the self tables.
//
// The hull. Every robot shape of a body's links is a convex core grown by its margin (the
// link's padding). The hull of the cores' points, grown by the largest margin, contains each of
// them: a polytope core contributes its vertices (a box its corners); a round one (sphere,
// capsule, cylinder) a 12-sided prism circumscribing it (corners at r / cos(pi / 12) from its
// axis, ends at its half length, plus r for a capsule or sphere), which contains it.
#include <algorithm>
#include <cmath>
#include <hullcheck/core/convex_hull.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <map>
#include <mutex>
#include <utility>
#include <variant>

#include "collision_checker_internals.hpp"

namespace hullcheck {
namespace {

constexpr int kPrismSides = 12;

// Points (shape frame) whose hull contains `shape`'s core (the shape without its margin).
void add_core_points(const Shape& shape, const Eigen::Isometry3d& to_root,
                     std::vector<Eigen::Vector3d>& out) {
  const auto add = [&](const Eigen::Vector3d& p) { out.push_back(to_root * p); };
  const auto prism = [&](double radius, double half_length) {
    const double r = radius / std::cos(M_PI / kPrismSides);
    for (int k = 0; k < kPrismSides; ++k) {
      const double a = 2.0 * M_PI * k / kPrismSides;
      add({r * std::cos(a), r * std::sin(a), -half_length});
      add({r * std::cos(a), r * std::sin(a), half_length});
    }
  };
  const Shape::Geometry& g = shape.geometry();
  if (const auto* hull = std::get_if<ConvexHull>(&g)) {
    for (const Eigen::Vector3d& v : hull->vertices()) add(v);
  } else if (const auto* box = std::get_if<Box>(&g)) {
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d& h = box->half_extents;
      add({(k & 1) ? h.x() : -h.x(), (k & 2) ? h.y() : -h.y(), (k & 4) ? h.z() : -h.z()});
    }
  } else if (const auto* cylinder = std::get_if<Cylinder>(&g)) {
    prism(cylinder->radius, cylinder->half_length);
  } else if (const auto* capsule = std::get_if<Capsule>(&g)) {
    prism(capsule->radius, capsule->half_length + capsule->radius);
  } else if (const auto* sphere = std::get_if<Sphere>(&g)) {
    prism(sphere->radius, sphere->radius);
  }
}

}  // namespace

int CollisionChecker::rigid_root(int link) const {
  for (;;) {
    const int j = model_->link(link).parent_joint;
    if (j < 0 || model_->joint(j).type != JointType::kFixed) return link;
    link = model_->joint(j).parent_link;
  }
}

void CollisionChecker::build_self_clusters() {
  // Self blocks by the rigid bodies of their links; a pair of bodies with two or more blocks
  // is a cluster.
  std::map<std::pair<int, int>, std::vector<int>> by_bodies;
  for (std::size_t k = 0; k < self_blocks_.size(); ++k) {
    const int ra = rigid_root(link_balls_[static_cast<std::size_t>(self_blocks_[k].link_a)].link);
    const int rb = rigid_root(link_balls_[static_cast<std::size_t>(self_blocks_[k].link_b)].link);
    if (ra == rb) continue;  // cannot happen (fixed neighbours are allowed), but never cluster
    by_bodies[{std::min(ra, rb), std::max(ra, rb)}].push_back(static_cast<int>(k));
  }
  cluster_of_block_.assign(self_blocks_.size(), -1);
  std::map<int, int> body_of_root;
  const auto body = [&](int root) {
    const auto [it, added] = body_of_root.emplace(root, static_cast<int>(bodies_.size()));
    if (added) bodies_.push_back(body_hull(root));
    return it->second;
  };
  for (const auto& [roots, blocks] : by_bodies) {
    if (blocks.size() < 2) continue;
    const int begin = static_cast<int>(cluster_blocks_.size());
    for (int k : blocks) {
      cluster_of_block_[static_cast<std::size_t>(k)] = static_cast<int>(self_clusters_.size());
      cluster_blocks_.push_back(k);
    }
    self_clusters_.push_back(
        {body(roots.first), body(roots.second), begin, static_cast<int>(cluster_blocks_.size())});
  }
}

CollisionChecker::RigidBodyHull CollisionChecker::body_hull(int root) const {
  ModelSelfTables& shared = *self_tables_->model;
  const std::lock_guard<std::mutex> lock(shared.mutex);
  std::shared_ptr<const Shape>& made = shared.body_hulls[root];
  if (!made) {
    // The body's links: those whose rigid root is `root`; their offsets from it at any
    // configuration (fixed joints only in between).
    const Eigen::VectorXd q = model_->default_configuration();
    std::vector<Eigen::Isometry3d> poses(model_->links().size());
    model_->compute_link_poses(q, poses);
    const Eigen::Isometry3d root_inverse = poses[static_cast<std::size_t>(root)].inverse();
    std::vector<Eigen::Vector3d> points;
    double margin = 0.0;
    for (int l = 0; l < static_cast<int>(model_->links().size()); ++l) {
      if (rigid_root(l) != root) continue;
      for (const CollisionShape& cs : model_->link(l).shapes) {
        add_core_points(cs.shape, root_inverse * poses[static_cast<std::size_t>(l)] * cs.origin,
                        points);
        margin = std::max(margin, cs.shape.margin());
      }
    }
    const Shape hull{ConvexHull(points)};
    made = std::make_shared<const Shape>(margin > 0.0 ? hull.inflated(margin) : hull);
  }
  RigidBodyHull out;
  out.root = root;
  out.hull = made;
  const ConvexHull& h = std::get<ConvexHull>(made->geometry());
  out.center = h.bounding_ball_center();
  out.radius = h.bounding_ball_radius() + made->margin();
  return out;
}

}  // namespace hullcheck
