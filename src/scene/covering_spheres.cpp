// CollisionChecker's covering spheres: for each robot shape, a few balls whose union contains
// it, tighter than its one bounding ball (is_valid_batch's broad phase tests them for a whole
// block of configurations).
//
// A convex hull is cut into slabs across its longest bounding-box axis; the part of the hull in
// a slab is the convex hull of its vertices in the slab and of the points where its edges cross
// the slab's planes, and the slab's ball is centred on those points' bounding box and reaches
// the farthest of them (so it contains their hull). The slabs cover the hull, so the balls do;
// each grows by the shape's margin. A primitive keeps its bounding ball.
//
// Also one inner ball per shape (inside it, so a ball reaching into an obstacle proves a
// collision): a primitive's largest centred one; for a hull, the ball about its vertices' mean
// reaching the nearest face plane.
#include <algorithm>
#include <array>
#include <cmath>
#include <hullcheck/scene/collision_checker.hpp>
#include <mutex>
#include <vector>

#include "collision_checker_internals.hpp"

namespace hullcheck {
namespace {

constexpr int kMaxSlabs = 6;

// Balls (x, y, z, radius; the hull's frame) covering a solid `hull`, one per slab, appended to
// `out`; false (nothing appended) for a flat hull or when a slab holds no part of it: the
// caller keeps the shape's bounding ball then.
bool hull_cover(const ConvexHull& hull, double margin, std::vector<Eigen::Vector4d>& out) {
  if (hull.dimension() != 3) return false;
  const std::vector<Eigen::Vector3d>& v = hull.vertices();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const Eigen::Vector3d& p : v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Eigen::Index axis = 0;
  const Eigen::Vector3d size = hi - lo;
  size.maxCoeff(&axis);
  const double shortest = std::max(size.minCoeff(), 1e-3 * size[axis]);
  const int slabs = std::clamp(
      static_cast<int>(std::lround(size[axis] / std::max(shortest, 1e-12))), 1, kMaxSlabs);
  // Every edge, once (two triangles share it).
  std::vector<std::array<int, 2>> edges;
  for (const auto& t : hull.triangles()) {
    for (int e = 0; e < 3; ++e) {
      const int a = t[static_cast<std::size_t>(e)], b = t[static_cast<std::size_t>((e + 1) % 3)];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const std::size_t first = out.size();
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < slabs; ++k) {
    const double a = lo[axis] + size[axis] * k / slabs;
    const double b = k + 1 == slabs ? hi[axis] : lo[axis] + size[axis] * (k + 1) / slabs;
    points.clear();
    for (const Eigen::Vector3d& p : v) {
      if (p[axis] >= a && p[axis] <= b) points.push_back(p);
    }
    for (const auto& e : edges) {
      const Eigen::Vector3d& p = v[static_cast<std::size_t>(e[0])];
      const Eigen::Vector3d& q = v[static_cast<std::size_t>(e[1])];
      for (const double plane : {a, b}) {
        if ((p[axis] - plane) * (q[axis] - plane) < 0.0) {
          const double s = (plane - p[axis]) / (q[axis] - p[axis]);
          Eigen::Vector3d x = p + s * (q - p);
          x[axis] = plane;
          points.push_back(x);
        }
      }
    }
    if (points.empty()) {  // cannot happen for a solid; not covered otherwise
      out.resize(first);
      return false;
    }
    Eigen::Vector3d plo = points.front(), phi = points.front();
    for (const Eigen::Vector3d& p : points) {
      plo = plo.cwiseMin(p);
      phi = phi.cwiseMax(p);
    }
    const Eigen::Vector3d c = 0.5 * (plo + phi);
    double r = 0.0;
    for (const Eigen::Vector3d& p : points) r = std::max(r, (p - c).norm());
    // A relative hair for the rounding of the crossing points.
    out.emplace_back(c[0], c[1], c[2], r * (1.0 + 1e-12) + 1e-12 + margin);
  }
  return true;
}

// A ball inside `shape` (x, y, z, radius; its frame); radius 0 when none is found.
Eigen::Vector4d inner_ball(const Shape& shape) {
  const double margin = shape.margin();
  const Shape::Geometry& g = shape.geometry();
  double r = 0.0;
  const Eigen::Vector3d c = point_inside(shape);  // inside a flat hull too
  if (const auto* sphere = std::get_if<Sphere>(&g)) {
    r = sphere->radius;
  } else if (const auto* box = std::get_if<Box>(&g)) {
    r = box->half_extents.minCoeff();
  } else if (const auto* cylinder = std::get_if<Cylinder>(&g)) {
    r = std::min(cylinder->radius, cylinder->half_length);
  } else if (const auto* capsule = std::get_if<Capsule>(&g)) {
    r = capsule->radius;
  } else if (const auto* hull = std::get_if<ConvexHull>(&g)) {
    // About the vertices' mean: the distance to the nearest face plane (a flat hull has no
    // inside but its margin's).
    if (hull->dimension() == 3) {
      r = INFINITY;
      for (const auto& t : hull->triangles()) {
        const Eigen::Vector3d& a = hull->vertices()[static_cast<std::size_t>(t[0])];
        const Eigen::Vector3d n = (hull->vertices()[static_cast<std::size_t>(t[1])] - a)
                                      .cross(hull->vertices()[static_cast<std::size_t>(t[2])] - a);
        if (n.squaredNorm() == 0.0) continue;
        r = std::min(r, std::abs(n.normalized().dot(a - c)));
      }
      if (!std::isfinite(r)) r = 0.0;
      r *= 1.0 - 1e-9;  // rounding of the planes
    }
  }
  return Eigen::Vector4d(c[0], c[1], c[2], r > 0.0 ? r + margin : margin);
}

}  // namespace

void CollisionChecker::build_covering_spheres() {
  // They depend on the model's shapes only: built once per model (and padding revision).
  ModelSelfTables& shared = *self_tables_->model;
  const std::lock_guard<std::mutex> lock(shared.mutex);
  if (shared.spheres_built) {
    cover_ = shared.cover;
    inner_ = shared.inner;
    cover_begin_ = shared.cover_begin;
    return;
  }
  inner_.clear();
  cover_begin_.assign(shapes_.size() + 1, 0);
  std::vector<Eigen::Vector4d> local;
  for (std::size_t i = 0; i < shapes_.size(); ++i) {
    const RobotShape& rs = shapes_[i];
    const CollisionShape& cs = model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)];
    const Eigen::Vector4d inner = inner_ball(cs.shape);
    const Eigen::Vector3d inner_center = cs.origin * inner.head<3>();  // into the link's frame
    inner_.emplace_back(inner_center[0], inner_center[1], inner_center[2], inner[3]);
    cover_begin_[i] = static_cast<int>(cover_.size());
    local.clear();
    if (cs.shape.kind() != ShapeKind::kConvexHull ||
        !hull_cover(std::get<ConvexHull>(cs.shape.geometry()), cs.shape.margin(), local)) {
      cover_.emplace_back(rs.center[0], rs.center[1], rs.center[2], rs.radius);  // its ball
      continue;
    }
    for (const Eigen::Vector4d& ball : local) {
      const Eigen::Vector3d c = cs.origin * ball.head<3>();
      cover_.emplace_back(c[0], c[1], c[2], ball[3]);
    }
  }
  cover_begin_[shapes_.size()] = static_cast<int>(cover_.size());
  shared.cover = cover_;
  shared.inner = inner_;
  shared.cover_begin = cover_begin_;
  shared.spheres_built = true;
}

}  // namespace hullcheck
