#include "fcl_mesh_checker.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <utility>
#include <variant>

namespace hullcheck::test {
namespace {

using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;

// First cutoff of min_distance's passes, m.
constexpr double kFirstCutoff = 0.01;

// An obstacle's shape in FCL's types, in the obstacle's own frame.
Geometry obstacle_to_fcl(const Obstacle& o) {
  if (o.shape.margin() != 0.0) {
    throw std::invalid_argument("FclMeshChecker: obstacle " + o.name + " is padded");
  }
  const Shape::Geometry& g = o.shape.geometry();
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
    if (hull.dimension() != 3) {
      throw std::invalid_argument("FclMeshChecker: obstacle " + o.name + " is a flat hull");
    }
    auto vertices = std::make_shared<std::vector<Eigen::Vector3d>>(hull.vertices());
    auto faces = std::make_shared<std::vector<int>>();
    faces->reserve(hull.triangles().size() * 4);
    for (const auto& t : hull.triangles()) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
    out = std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.triangles().size()), faces,
                                         /*throw_if_invalid=*/true);
  }
  out->computeLocalAABB();
  return out;
}

// One posed geometry with its conservative world bounds.
struct Placed {
  const fcl::CollisionGeometryd* geometry = nullptr;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // link frame <- element frame
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();    // model frame <- element frame
  fcl::AABBd aabb;                                           // world box of the local box
  Eigen::Vector3d center = Eigen::Vector3d::Zero();          // world centre of the local box
  double radius = 0.0;                                       // its half diagonal

  // Moves the geometry to `p` and updates the bounds.
  void place(const Eigen::Isometry3d& p) {
    pose = p;
    const fcl::AABBd& local = geometry->aabb_local;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner((c & 1) ? local.max_.x() : local.min_.x(),
                                   (c & 2) ? local.max_.y() : local.min_.y(),
                                   (c & 4) ? local.max_.z() : local.min_.z());
      const Eigen::Vector3d w = pose * corner;
      if (c == 0) {
        aabb = fcl::AABBd(w);
      } else {
        aabb += w;
      }
    }
    center = pose * local.center();
    radius = local.radius();
  }
};

// A lower bound on the distance between two placed geometries (0 when the bounds overlap).
double lower_bound(const Placed& a, const Placed& b) {
  const double box_gap = a.aabb.overlap(b.aabb) ? 0.0 : a.aabb.distance(b.aabb);
  const double ball_gap = (a.center - b.center).norm() - a.radius - b.radius;
  return std::max({box_gap, ball_gap, 0.0});
}

}  // namespace

struct FclMeshChecker::Impl {
  std::shared_ptr<const FclMeshModel> meshes;
  std::vector<std::string> link_names;  // per model link
  std::vector<std::string> obstacle_names;
  std::vector<FclMeshPair> pairs;
  // Robot elements, flattened: (model link, element) -> first_element[link] + element.
  std::vector<int> first_element;
  std::vector<Placed> robot;
  std::vector<Geometry> obstacle_geometry;
  std::vector<Placed> obstacles;

  const Placed& side_a(const FclMeshPair& p) const {
    return robot[static_cast<std::size_t>(first_element[static_cast<std::size_t>(p.link_a)] +
                                          p.element_a)];
  }
  const Placed& side_b(const FclMeshPair& p) const {
    return p.self() ? robot[static_cast<std::size_t>(
                          first_element[static_cast<std::size_t>(p.link_b)] + p.element_b)]
                    : obstacles[static_cast<std::size_t>(p.obstacle)];
  }
  // fcl::collide on one pair.
  bool collides(const FclMeshPair& p) const {
    const Placed& a = side_a(p);
    const Placed& b = side_b(p);
    fcl::CollisionRequestd request(1, false);
    fcl::CollisionResultd result;
    return fcl::collide(a.geometry, fcl::Transform3d(a.pose.matrix()), b.geometry,
                        fcl::Transform3d(b.pose.matrix()), request, result) > 0;
  }
  // fcl::distance on one pair, seeded with `best`: the pair's distance when below it, else
  // `best` (FCL prunes every bounding-volume pair that cannot beat the seed).
  double distance_below(const FclMeshPair& p, double best) const {
    const Placed& a = side_a(p);
    const Placed& b = side_b(p);
    fcl::DistanceRequestd request;
    request.distance_tolerance = 1e-10;
    fcl::DistanceResultd result;
    result.min_distance = best;
    fcl::distance(a.geometry, fcl::Transform3d(a.pose.matrix()), b.geometry,
                  fcl::Transform3d(b.pose.matrix()), request, result);
    return std::min(result.min_distance, best);
  }
  // min_distance over the pairs of `order` (lower bound, pair index).
  FclMeshDistance min_distance(std::vector<std::pair<double, std::size_t>> order,
                               double cutoff) const;
};

FclMeshChecker::FclMeshChecker(std::shared_ptr<const FclMeshModel> meshes, const RobotModel& model,
                               const AllowedCollisionMatrix& matrix, const PlanningScene& scene)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.meshes = std::move(meshes);
  const int n = static_cast<int>(model.links().size());
  if (matrix.link_count() != n) throw std::invalid_argument("FclMeshChecker: matrix size");
  std::vector<int> element_count(static_cast<std::size_t>(n), 0);
  for (int l = 0; l < n; ++l) {
    const Link& link = model.link(l);
    m.link_names.push_back(link.name);
    m.first_element.push_back(static_cast<int>(m.robot.size()));
    const int mesh_link = m.meshes->link_index(link.name);
    if (mesh_link < 0) {
      if (!link.shapes.empty()) {
        throw std::invalid_argument("FclMeshChecker: no mesh link " + link.name);
      }
      continue;
    }
    for (const FclMeshElement& e :
         m.meshes->links()[static_cast<std::size_t>(mesh_link)].elements) {
      Placed placed;
      placed.geometry = e.geometry.get();
      placed.origin = e.origin;
      placed.place(e.origin);
      m.robot.push_back(placed);
      ++element_count[static_cast<std::size_t>(l)];
    }
  }
  for (const Obstacle& o : scene.obstacles) {
    m.obstacle_geometry.push_back(obstacle_to_fcl(o));
    m.obstacle_names.push_back(o.name);
    Placed placed;
    placed.geometry = m.obstacle_geometry.back().get();
    placed.place(o.pose);
    m.obstacles.push_back(placed);
  }

  // The scene's allowed names, both orders.
  std::set<std::pair<std::string, std::string>> allowed;
  for (const auto& [a, b] : scene.allowed_pairs) {
    allowed.insert({a, b});
    allowed.insert({b, a});
  }
  for (int l = 0; l < n; ++l) {
    for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
      if (allowed.count({m.link_names[static_cast<std::size_t>(l)], scene.obstacles[o].object})) {
        continue;
      }
      for (int e = 0; e < element_count[static_cast<std::size_t>(l)]; ++e) {
        FclMeshPair p;
        p.link_a = l;
        p.element_a = e;
        p.obstacle = static_cast<int>(o);
        m.pairs.push_back(p);
      }
    }
  }
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (matrix.allowed(a, b) || allowed.count({m.link_names[static_cast<std::size_t>(a)],
                                                 m.link_names[static_cast<std::size_t>(b)]})) {
        continue;
      }
      for (int ea = 0; ea < element_count[static_cast<std::size_t>(a)]; ++ea) {
        for (int eb = 0; eb < element_count[static_cast<std::size_t>(b)]; ++eb) {
          FclMeshPair p;
          p.link_a = a;
          p.element_a = ea;
          p.link_b = b;
          p.element_b = eb;
          m.pairs.push_back(p);
        }
      }
    }
  }
}

FclMeshChecker::~FclMeshChecker() = default;

const std::vector<FclMeshPair>& FclMeshChecker::pairs() const { return impl_->pairs; }

std::string FclMeshChecker::pair_name(std::size_t i) const {
  const FclMeshPair& p = impl_->pairs.at(i);
  return impl_->link_names[static_cast<std::size_t>(p.link_a)] + " / " +
         (p.self() ? impl_->link_names[static_cast<std::size_t>(p.link_b)]
                   : impl_->obstacle_names[static_cast<std::size_t>(p.obstacle)]);
}

void FclMeshChecker::set_link_poses(const std::vector<Eigen::Isometry3d>& link_poses) {
  Impl& m = *impl_;
  if (link_poses.size() != m.first_element.size()) {
    throw std::invalid_argument("FclMeshChecker: link pose count");
  }
  for (std::size_t l = 0; l < link_poses.size(); ++l) {
    const std::size_t end = l + 1 < m.first_element.size()
                                ? static_cast<std::size_t>(m.first_element[l + 1])
                                : m.robot.size();
    for (std::size_t i = static_cast<std::size_t>(m.first_element[l]); i < end; ++i) {
      m.robot[i].place(link_poses[l] * m.robot[i].origin);
    }
  }
}

std::ptrdiff_t FclMeshChecker::first_collision() const {
  const Impl& m = *impl_;
  for (std::size_t i = 0; i < m.pairs.size(); ++i) {
    const FclMeshPair& p = m.pairs[i];
    if (!m.side_a(p).aabb.overlap(m.side_b(p).aabb)) continue;
    if (m.collides(p)) return static_cast<std::ptrdiff_t>(i);
  }
  return -1;
}

FclMeshDistance FclMeshChecker::min_distance(double cutoff) const {
  const Impl& m = *impl_;
  std::vector<std::pair<double, std::size_t>> order;
  order.reserve(m.pairs.size());
  for (std::size_t i = 0; i < m.pairs.size(); ++i) {
    order.emplace_back(lower_bound(m.side_a(m.pairs[i]), m.side_b(m.pairs[i])), i);
  }
  return m.min_distance(std::move(order), cutoff);
}

double FclMeshChecker::pair_distance(std::size_t i) const {
  const FclMeshPair& p = impl_->pairs.at(i);
  if (impl_->collides(p)) return 0.0;
  return impl_->distance_below(p, std::numeric_limits<double>::max());
}

FclMeshDistance FclMeshChecker::named_pair_distance(const std::string& a,
                                                    const std::string& b) const {
  const Impl& m = *impl_;
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t i = 0; i < m.pairs.size(); ++i) {
    const FclMeshPair& p = m.pairs[i];
    const std::string& name_a = m.link_names[static_cast<std::size_t>(p.link_a)];
    const std::string& name_b = p.self() ? m.link_names[static_cast<std::size_t>(p.link_b)]
                                         : m.obstacle_names[static_cast<std::size_t>(p.obstacle)];
    if ((name_a == a && name_b == b) || (name_a == b && name_b == a)) {
      order.emplace_back(lower_bound(m.side_a(p), m.side_b(p)), i);
    }
  }
  return m.min_distance(std::move(order), std::numeric_limits<double>::infinity());
}

FclMeshDistance FclMeshChecker::Impl::min_distance(
    std::vector<std::pair<double, std::size_t>> order, double cutoff) const {
  std::sort(order.begin(), order.end());
  FclMeshDistance out;
  // Collision tests first: only pairs whose bounds overlap can touch.
  for (const auto& [bound, i] : order) {
    if (bound > 0.0) break;
    const FclMeshPair& p = pairs[i];
    if (!side_a(p).aabb.overlap(side_b(p).aabb)) continue;
    ++out.collide_calls;
    if (collides(p)) {
      out.collision = true;
      out.distance = 0.0;
      out.pair = static_cast<std::ptrdiff_t>(i);
      return out;
    }
  }
  out.distance = std::max(cutoff, 0.0);
  if (order.empty() || out.distance <= 0.0) return out;
  // Distances in passes under growing cutoffs, each exact below its cutoff: FCL prunes its
  // traversal against the seed, so a small one is cheap (most answers are millimetres, and a
  // first seed of metres costs several times more on 40k-triangle meshes).
  for (double c = std::min(cutoff, kFirstCutoff);;) {
    out.distance = c;
    bool all = true;  // every pair's bound was below c
    for (const auto& [bound, i] : order) {
      if (bound >= out.distance) {
        all = false;
        break;
      }
      ++out.distance_calls;
      const double d = distance_below(pairs[i], out.distance);
      if (d < out.distance) {
        out.distance = d;
        out.pair = static_cast<std::ptrdiff_t>(i);
      }
    }
    if (out.pair >= 0 || c >= cutoff) return out;
    c = all ? cutoff : std::min(cutoff, 8.0 * c);
  }
}

}  // namespace hullcheck::test
