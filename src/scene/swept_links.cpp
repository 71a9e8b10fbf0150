// CollisionChecker::sweep_link: one link's shapes swept through a whole turn about the joint
// next to it, so that a self block moved by three values gets a distance table over two.
//
// Why the sweep bounds the distance. Links A and B are moved relative to each other by the
// revolute joints on the path between them; let J be the one next to A (A's own parent joint,
// through fixed joints, or, when the path leaves A downwards, the first joint below A). J's axis
// is a line fixed in A's frame, and turning J by phi moves B relative to A as turning A by -phi
// about that line does. So at every value of J, B's pose relative to A is one the other values
// give it with A turned about the line: A lies in the solid S its turned copies fill, which is
// the same set at every value of J, and B's signed distance to A is at least its signed
// distance to any convex set containing S (penetration depth grows with the set). The tables
// measure against such a set, per shape of A: the hull of kCopies copies turned by multiples of
// 2 pi / kCopies, grown by the sag of a chord of the turn (a point at distance rho from the line
// stays within rho (1 - cos(pi / kCopies)) of the chord joining its neighbouring copies) and by
// the radius of the round parts left out of the copies (a sphere's centre, a capsule's segment).
//
// Why the lever arms still hold. A table cell's reach multiplies each remaining value's lever
// arm for the pair (motion_bounds.cpp) by the cell's half-width. A lever arm bounds the
// distance from that value's axis of every point of A's shape over every configuration of the
// joints in between, J included; the swept set's vertices are A's points turned about J's line,
// i.e. points of A at other values of J, and the distance from a line is convex (largest at a
// vertex) and grows by at most the growth of the set: the vertices' bound plus the growth is
// what farthest() already counts for round shapes (centre plus radius). So the same reach holds.
#include <algorithm>
#include <cmath>
#include <hullcheck/core/convex_hull.hpp>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <variant>
#include <vector>

#include "collision_checker_internals.hpp"

namespace hullcheck {

namespace {

// Copies per turn: the chord's sag is 1 - cos(pi / 16) = 1.9% of a point's distance from the
// line (1.9 mm at 10 cm, well below a UR5 cell's reach of about 10 mm). 32 copies proved the
// same share of the UR5's cells apart (0.904 against 0.906 for the forearm against wrist_3)
// with hulls of twice the vertices.
constexpr int kCopies = 16;

// Points (link frame) whose hull, grown by the returned radius, contains `shape` placed at
// `local`: a box's corners, a sphere's centre, a capsule's or cylinder's segment (a cylinder
// lies in the capsule of its radius), a hull's vertices; the shape's margin is added.
double outer_points(const Shape& shape, const Eigen::Isometry3d& local,
                    std::vector<Eigen::Vector3d>* points) {
  const Shape::Geometry& g = shape.geometry();
  double radius = shape.margin();
  if (const auto* box = std::get_if<Box>(&g)) {
    for (int c = 0; c < 8; ++c) {
      points->push_back(local * Eigen::Vector3d((c & 1 ? 1 : -1) * box->half_extents.x(),
                                                (c & 2 ? 1 : -1) * box->half_extents.y(),
                                                (c & 4 ? 1 : -1) * box->half_extents.z()));
    }
  } else if (const auto* sphere = std::get_if<Sphere>(&g)) {
    points->push_back(local.translation());
    radius += sphere->radius;
  } else if (const auto* capsule = std::get_if<Capsule>(&g)) {
    points->push_back(local * Eigen::Vector3d(0, 0, capsule->half_length));
    points->push_back(local * Eigen::Vector3d(0, 0, -capsule->half_length));
    radius += capsule->radius;
  } else if (const auto* cylinder = std::get_if<Cylinder>(&g)) {
    points->push_back(local * Eigen::Vector3d(0, 0, cylinder->half_length));
    points->push_back(local * Eigen::Vector3d(0, 0, -cylinder->half_length));
    radius += cylinder->radius;
  } else {
    for (const Eigen::Vector3d& v : std::get<ConvexHull>(g).vertices()) {
      points->push_back(local * v);
    }
  }
  return radius;
}

// `points` turned about the line through `origin` along unit `axis` by multiples of 2 pi /
// `copies`.
std::vector<Eigen::Vector3d> turned_copies(const std::vector<Eigen::Vector3d>& points,
                                           const Eigen::Vector3d& origin,
                                           const Eigen::Vector3d& axis, int copies) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size() * static_cast<std::size_t>(copies));
  for (int k = 0; k < copies; ++k) {
    const Eigen::AngleAxisd turn(2.0 * M_PI * k / copies, axis);
    for (const Eigen::Vector3d& p : points) out.push_back(origin + turn * (p - origin));
  }
  return out;
}

// `shape` at `local` (link frame) swept about the line through `origin` along unit `axis`.
detail::SweptShape sweep_shape(const Shape& shape, const Eigen::Isometry3d& local,
                               const Eigen::Vector3d& origin, const Eigen::Vector3d& axis) {
  std::vector<Eigen::Vector3d> points;
  const double grown = outer_points(shape, local, &points);
  double rho = 0.0;  // the farthest point from the line
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d r = p - origin;
    rho = std::max(rho, (r - r.dot(axis) * axis).norm());
  }
  const ConvexHull hull(turned_copies(points, origin, axis, kCopies));
  const double sag = rho * (1.0 - std::cos(M_PI / kCopies));
  detail::SweptShape out{Shape(hull).inflated(grown + sag), Eigen::Vector3d::Zero(), 0.0};
  // A ball about the vertices' centroid containing them, grown likewise.
  for (const Eigen::Vector3d& v : hull.vertices()) out.center += v;
  out.center /= static_cast<double>(hull.vertices().size());
  for (const Eigen::Vector3d& v : hull.vertices()) {
    out.radius = std::max(out.radius, (v - out.center).norm());
  }
  out.radius += grown + sag;
  return out;
}

}  // namespace

int CollisionChecker::sweep_joint(int link_ball, int other_ball, int drivers) const {
  const int x = link_balls_[static_cast<std::size_t>(link_ball)].link;
  const int y = link_balls_[static_cast<std::size_t>(other_ball)].link;
  // The moving joints on the path, per side, in climbing order (as relative_drivers climbs).
  std::vector<int> from_x, from_y, values;
  for (int lx = x, ly = y; lx != ly;) {
    const bool x_deeper =
        link_depth_[static_cast<std::size_t>(lx)] >= link_depth_[static_cast<std::size_t>(ly)];
    int& l = x_deeper ? lx : ly;
    const int j = model_->link(l).parent_joint;
    const Joint& joint = model_->joint(j);
    if (joint.type != JointType::kFixed) {
      if (joint.type == JointType::kPrismatic) return -1;
      (x_deeper ? from_x : from_y).push_back(j);
      values.push_back(joint.driver());
    }
    l = joint.parent_link;
  }
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  // Each value moves one joint there (no mimic pair): dropping J's value drops only J.
  if (static_cast<int>(values.size()) != drivers ||
      static_cast<int>(from_x.size() + from_y.size()) != drivers) {
    return -1;
  }
  return !from_x.empty() ? from_x.front() : from_y.back();
}

void CollisionChecker::sweep_axis(int link_ball, int joint_index, Eigen::Vector3d* origin,
                                  Eigen::Vector3d* axis) const {
  const int x = link_balls_[static_cast<std::size_t>(link_ball)].link;
  const Joint& joint = model_->joint(joint_index);
  // The joint's line is fixed in x's frame: any configuration shows it.
  std::vector<Eigen::Isometry3d> poses;
  model_->compute_link_poses(model_->default_configuration(), poses);
  const Eigen::Isometry3d to_x = poses[static_cast<std::size_t>(x)].inverse() *
                                 poses[static_cast<std::size_t>(joint.child_link)];
  *origin = to_x.translation();
  *axis = (to_x.linear() * joint.axis).normalized();
}

double CollisionChecker::sweep_growth(int link_ball, int joint_index) const {
  Eigen::Vector3d origin, axis;
  sweep_axis(link_ball, joint_index, &origin, &axis);
  double growth = 0.0;
  const int x = link_balls_[static_cast<std::size_t>(link_ball)].link;
  for (const CollisionShape& cs : model_->link(x).shapes) {
    std::vector<Eigen::Vector3d> points;
    const double radius = outer_points(cs.shape, cs.origin, &points);
    // Round parts as the octahedra their balls hold (a ball's centre alone has no volume).
    for (std::size_t i = 0, n = points.size(); i < n && radius > 0.0; ++i) {
      for (int d = 0; d < 6; ++d) {
        points.push_back(points[i] + (d < 3 ? radius : -radius) * Eigen::Vector3d::Unit(d % 3));
      }
    }
    growth += std::max(0.0, convex_hull_volume(turned_copies(points, origin, axis, 8)) -
                                convex_hull_volume(points));
  }
  return growth;
}

std::unique_ptr<CollisionChecker::SweptLink> CollisionChecker::sweep_link(int link_ball,
                                                                          int joint_index) const {
  Eigen::Vector3d origin, axis;
  sweep_axis(link_ball, joint_index, &origin, &axis);
  const int x = link_balls_[static_cast<std::size_t>(link_ball)].link;
  auto out = std::make_unique<SweptLink>();
  out->link = x;
  out->driver = model_->joint(joint_index).driver();
  try {
    for (const CollisionShape& cs : model_->link(x).shapes) {
      out->shapes.push_back(sweep_shape(cs.shape, cs.origin, origin, axis));
    }
    const int bound = link_balls_[static_cast<std::size_t>(link_ball)].bound;
    if (bound >= 0) {
      const RobotShape& rs = shapes_[static_cast<std::size_t>(bound)];
      out->bound = std::make_unique<detail::SweptShape>(sweep_shape(
          bounding_shape(bound), model_->link(x).shapes[static_cast<std::size_t>(rs.shape)].origin,
          origin, axis));
    }
  } catch (const InputError&) {
    return nullptr;  // a hull qhull cannot build (degenerate beyond what it handles)
  }
  return out;
}

}  // namespace hullcheck
