#include "fcl_checker.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/utility.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

namespace hullcheck::test {
namespace {

using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;

// The same geometry in FCL's types, in the shape's own frame.
Geometry to_fcl(const Shape& shape, const std::string& what) {
  if (shape.margin() != 0.0) {
    throw std::invalid_argument("FclChecker: " + what + " is padded; FCL comparisons need 0");
  }
  const Shape::Geometry& g = shape.geometry();
  Geometry out;
  if (const auto* box = std::get_if<Box>(&g)) {
    out = std::make_shared<fcl::Boxd>(2.0 * box->half_extents);
  } else if (const auto* sphere = std::get_if<Sphere>(&g)) {
    out = std::make_shared<fcl::Sphered>(sphere->radius);
  } else if (const auto* cylinder = std::get_if<Cylinder>(&g)) {
    out = std::make_shared<fcl::Cylinderd>(cylinder->radius, 2.0 * cylinder->half_length);
  } else if (const auto* capsule = std::get_if<Capsule>(&g)) {
    out = std::make_shared<fcl::Capsuled>(capsule->radius, 2.0 * capsule->half_length);
  } else {
    const auto& hull = std::get<ConvexHull>(g);
    if (hull.dimension() < 2) {
      throw std::invalid_argument("FclChecker: " + what + " is a hull of dimension " +
                                  std::to_string(hull.dimension()));
    }
    auto vertices = std::make_shared<std::vector<Eigen::Vector3d>>(hull.vertices());
    auto faces = std::make_shared<std::vector<int>>();
    faces->reserve(hull.triangles().size() * 8);
    for (const auto& t : hull.triangles()) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
    const bool flat = hull.dimension() == 2;
    if (flat) {  // a polygon: its fan from both sides (FCL's solvers use only the vertices)
      for (const auto& t : hull.triangles()) faces->insert(faces->end(), {3, t[0], t[2], t[1]});
    }
    // throw_if_invalid: a triangulation FCL cannot use (not watertight) must not go unnoticed;
    // a polygon is not a closed surface, so the check is off for it.
    auto convex = std::make_shared<fcl::Convexd>(vertices, static_cast<int>(faces->size() / 4),
                                                 faces, /*throw_if_invalid=*/!flat);
    out = convex;
  }
  out->computeLocalAABB();
  return out;
}

fcl::AABBd world_aabb(const fcl::CollisionGeometryd& g, const Eigen::Isometry3d& pose) {
  // Translate the local AABB's 8 corners: conservative for every geometry type.
  const fcl::AABBd& local = g.aabb_local;
  fcl::AABBd out;
  bool first = true;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner((c & 1) ? local.max_.x() : local.min_.x(),
                                 (c & 2) ? local.max_.y() : local.min_.y(),
                                 (c & 4) ? local.max_.z() : local.min_.z());
    const Eigen::Vector3d w = pose * corner;
    if (first) {
      out = fcl::AABBd(w);
      first = false;
    } else {
      out += w;
    }
  }
  return out;
}

}  // namespace

struct FclChecker::Impl {
  FclSolver solver = FclSolver::kLibccd;
  std::vector<FclPair> pairs;
  // Robot shapes, flattened: (link, shape) -> index via first_shape[link] + shape.
  std::vector<int> first_shape;
  std::vector<Geometry> robot_geometry;
  std::vector<Eigen::Isometry3d> robot_origin;  // link frame <- shape frame
  std::vector<Eigen::Isometry3d> robot_pose;    // model frame <- shape frame, current
  std::vector<fcl::AABBd> robot_aabb;
  std::vector<Geometry> obstacle_geometry;
  std::vector<Eigen::Isometry3d> obstacle_pose;
  std::vector<fcl::AABBd> obstacle_aabb;

  int robot_index(int link, int shape) const {
    return first_shape[static_cast<std::size_t>(link)] + shape;
  }
  const fcl::CollisionGeometryd& geometry_b(const FclPair& p) const {
    return p.self() ? *robot_geometry[static_cast<std::size_t>(robot_index(p.link_b, p.shape_b))]
                    : *obstacle_geometry[static_cast<std::size_t>(p.obstacle)];
  }
  const Eigen::Isometry3d& pose_b(const FclPair& p) const {
    return p.self() ? robot_pose[static_cast<std::size_t>(robot_index(p.link_b, p.shape_b))]
                    : obstacle_pose[static_cast<std::size_t>(p.obstacle)];
  }
  const fcl::AABBd& aabb_b(const FclPair& p) const {
    return p.self() ? robot_aabb[static_cast<std::size_t>(robot_index(p.link_b, p.shape_b))]
                    : obstacle_aabb[static_cast<std::size_t>(p.obstacle)];
  }
  fcl::GJKSolverType type() const {
    return solver == FclSolver::kLibccd ? fcl::GST_LIBCCD : fcl::GST_INDEP;
  }
};

FclChecker::FclChecker(const RobotModel& model, const AllowedCollisionMatrix& matrix,
                       const PlanningScene& scene, FclSolver solver)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.solver = solver;
  const int n = static_cast<int>(model.links().size());
  if (matrix.link_count() != n) throw std::invalid_argument("FclChecker: matrix size");
  for (int l = 0; l < n; ++l) {
    m.first_shape.push_back(static_cast<int>(m.robot_geometry.size()));
    const Link& link = model.link(l);
    for (std::size_t s = 0; s < link.shapes.size(); ++s) {
      m.robot_geometry.push_back(
          to_fcl(link.shapes[s].shape, "link " + link.name + " shape " + std::to_string(s)));
      m.robot_origin.push_back(link.shapes[s].origin);
    }
  }
  m.robot_pose.assign(m.robot_geometry.size(), Eigen::Isometry3d::Identity());
  m.robot_aabb.resize(m.robot_geometry.size());
  for (const Obstacle& o : scene.obstacles) {
    m.obstacle_geometry.push_back(to_fcl(o.shape, "obstacle " + o.name));
    m.obstacle_pose.push_back(o.pose);
    m.obstacle_aabb.push_back(world_aabb(*m.obstacle_geometry.back(), o.pose));
  }

  // Allowed names from the scene, both orders.
  std::set<std::pair<std::string, std::string>> allowed;
  for (const auto& [a, b] : scene.allowed_pairs) {
    allowed.insert({a, b});
    allowed.insert({b, a});
  }
  for (int l = 0; l < n; ++l) {
    const Link& link = model.link(l);
    for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
      if (allowed.count({link.name, scene.obstacles[o].object})) continue;
      for (std::size_t s = 0; s < link.shapes.size(); ++s) {
        FclPair p;
        p.link_a = l;
        p.shape_a = static_cast<int>(s);
        p.obstacle = static_cast<int>(o);
        m.pairs.push_back(p);
      }
    }
  }
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (matrix.allowed(a, b) || allowed.count({model.link(a).name, model.link(b).name})) {
        continue;
      }
      for (std::size_t sa = 0; sa < model.link(a).shapes.size(); ++sa) {
        for (std::size_t sb = 0; sb < model.link(b).shapes.size(); ++sb) {
          FclPair p;
          p.link_a = a;
          p.shape_a = static_cast<int>(sa);
          p.link_b = b;
          p.shape_b = static_cast<int>(sb);
          m.pairs.push_back(p);
        }
      }
    }
  }
}

FclChecker::~FclChecker() = default;

const std::vector<FclPair>& FclChecker::pairs() const { return impl_->pairs; }

void FclChecker::set_link_poses(const std::vector<Eigen::Isometry3d>& link_poses) {
  Impl& m = *impl_;
  if (link_poses.size() != m.first_shape.size()) {
    throw std::invalid_argument("FclChecker: link pose count");
  }
  for (std::size_t l = 0; l < link_poses.size(); ++l) {
    const std::size_t begin = static_cast<std::size_t>(m.first_shape[l]);
    const std::size_t end = l + 1 < m.first_shape.size()
                                ? static_cast<std::size_t>(m.first_shape[l + 1])
                                : m.robot_geometry.size();
    for (std::size_t i = begin; i < end; ++i) {
      m.robot_pose[i] = link_poses[l] * m.robot_origin[i];
      m.robot_aabb[i] = world_aabb(*m.robot_geometry[i], m.robot_pose[i]);
    }
  }
}

Eigen::Isometry3d FclChecker::pose_a(std::size_t i) const {
  const FclPair& p = impl_->pairs.at(i);
  return impl_->robot_pose[static_cast<std::size_t>(impl_->robot_index(p.link_a, p.shape_a))];
}

Eigen::Isometry3d FclChecker::pose_b(std::size_t i) const {
  return impl_->pose_b(impl_->pairs.at(i));
}

bool FclChecker::pair_collides(std::size_t i) const {
  const Impl& m = *impl_;
  const FclPair& p = m.pairs.at(i);
  const auto a = static_cast<std::size_t>(m.robot_index(p.link_a, p.shape_a));
  fcl::CollisionRequestd request(1, false);
  request.gjk_solver_type = m.type();
  fcl::CollisionResultd result;
  return fcl::collide(m.robot_geometry[a].get(), fcl::Transform3d(m.robot_pose[a].matrix()),
                      &m.geometry_b(p), fcl::Transform3d(m.pose_b(p).matrix()), request,
                      result) > 0;
}

double FclChecker::pair_distance(std::size_t i) const {
  const Impl& m = *impl_;
  const FclPair& p = m.pairs.at(i);
  const auto a = static_cast<std::size_t>(m.robot_index(p.link_a, p.shape_a));
  fcl::DistanceRequestd request;
  request.gjk_solver_type = m.type();
  request.distance_tolerance = 1e-10;
  fcl::DistanceResultd result;
  return fcl::distance(m.robot_geometry[a].get(), fcl::Transform3d(m.robot_pose[a].matrix()),
                       &m.geometry_b(p), fcl::Transform3d(m.pose_b(p).matrix()), request, result);
}

bool FclChecker::in_collision() const {
  const Impl& m = *impl_;
  for (std::size_t i = 0; i < m.pairs.size(); ++i) {
    const FclPair& p = m.pairs[i];
    const auto a = static_cast<std::size_t>(m.robot_index(p.link_a, p.shape_a));
    if (!m.robot_aabb[a].overlap(m.aabb_b(p))) continue;
    if (pair_collides(i)) return true;
  }
  return false;
}

FclDistance FclChecker::min_distance() const {
  const Impl& m = *impl_;
  std::vector<std::pair<double, std::size_t>> order;
  order.reserve(m.pairs.size());
  for (std::size_t i = 0; i < m.pairs.size(); ++i) {
    const FclPair& p = m.pairs[i];
    const auto a = static_cast<std::size_t>(m.robot_index(p.link_a, p.shape_a));
    const fcl::AABBd& aabb_a = m.robot_aabb[a];
    const fcl::AABBd& aabb_b = m.aabb_b(p);
    order.emplace_back(aabb_a.overlap(aabb_b) ? 0.0 : aabb_a.distance(aabb_b), i);
  }
  std::sort(order.begin(), order.end());
  FclDistance out;
  for (const auto& [bound, i] : order) {
    if (bound >= out.distance) break;
    ++out.distance_calls;
    const double d = pair_distance(i);
    if (d < 0.0) {
      out.collision = true;
      out.pair = static_cast<std::ptrdiff_t>(i);
      return out;
    }
    if (d < out.distance) {
      out.distance = d;
      out.pair = static_cast<std::ptrdiff_t>(i);
    }
  }
  return out;
}

}  // namespace hullcheck::test
