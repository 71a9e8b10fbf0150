// CollisionChecker: construction (shapes, pairs, groups and the broad phase's bounding volumes)
// and the placement of shapes at a query's link poses. The queries live in
// collision_verdict.cpp (is_valid), clearance_search.cpp (clearance) and motion_bounds.cpp
// (motion_bound, safe_advance); the warm-start grids in self_pair_warm_start.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>
#include <map>
#include <stdexcept>

#include "collision_checker_internals.hpp"
#include "sphere_box_rows.hpp"

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

Eigen::Vector3d point_inside(const Shape& shape) {
  if (shape.kind() != ShapeKind::kConvexHull) return Eigen::Vector3d::Zero();
  const std::vector<Eigen::Vector3d>& v = std::get<ConvexHull>(shape.geometry()).vertices();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : v) sum += p;
  return v.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(v.size()));
}

CollisionChecker::Scratch& CollisionChecker::scratch() const {
  // One per thread, shared by every checker: a query uses it from start to end and never
  // calls another query meanwhile. Grows to the largest robot seen, then stays.
  thread_local Scratch s;
  const std::size_t links = model_->links().size();
  if (s.link_poses.size() != links) s.link_poses.resize(links);
  if (s.shape_poses.size() < shapes_.size()) {
    s.shape_poses.resize(shapes_.size());
    s.centers.resize(shapes_.size());
    s.posed.resize(shapes_.size(), 0);
    s.centered.resize(shapes_.size(), 0);
    s.meets_other.resize(shapes_.size(), 0);
  }
  if (s.group_centers.size() < groups_.size()) {
    s.group_centers.resize(groups_.size());
    s.group_radii.resize(groups_.size());
  }
  if (s.link_centers.size() < link_balls_.size()) s.link_centers.resize(link_balls_.size());
  const std::size_t box_columns = detail::box_rows_padded(boxes_.size());
  if (s.box_gaps.size() < box_columns) {
    s.box_gaps.resize(box_columns);
    s.boxes_clear.resize((box_columns + 63) / 64);
  }
  const std::size_t pairs = self_pairs_.size() + environment_pairs_.size();
  if (s.lower_bounds.size() < pairs) {
    s.lower_bounds.resize(pairs);
    s.candidates.reserve(pairs);
    s.nearest.reserve(pairs);
    s.expanded.reserve(pairs);
  }
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
  const std::vector<std::vector<bool>> link_object_allowed = apply_scene_allowed_pairs();
  padding_revision_ = model_->padding_revision();
  self_tables_ = std::make_shared<SelfTables>();
  self_tables_->model = model_self_tables();  // the model's shared tables, grids and spheres
  index_shapes();
  build_covering_spheres();
  build_self_pairs();
  build_self_clusters();
  build_groups();
  build_environment_pairs(link_object_allowed);
  // Link depths, from the root down the tree.
  link_depth_.assign(model_->links().size(), 0);
  std::vector<int> stack;
  for (int l = 0; l < static_cast<int>(model_->links().size()); ++l) {
    if (model_->link(l).parent_joint < 0) stack.push_back(l);
  }
  while (!stack.empty()) {
    const int l = stack.back();
    stack.pop_back();
    for (int j : model_->link(l).child_joints) {
      const int child = model_->joint(j).child_link;
      link_depth_[static_cast<std::size_t>(child)] = link_depth_[static_cast<std::size_t>(l)] + 1;
      stack.push_back(child);
    }
  }
  motion_levers_ = std::make_shared<MotionLevers>();
  build_warm_start_grids();
}

// The scene's allowed pairs: link/link into the matrix; link/object returned, per link, per
// obstacle (true: the pair is not checked).
std::vector<std::vector<bool>> CollisionChecker::apply_scene_allowed_pairs() {
  const auto n = model_->links().size();
  std::map<std::string, std::vector<int>> obstacles_of;
  for (std::size_t o = 0; o < scene_.obstacles.size(); ++o) {
    obstacles_of[scene_.obstacles[o].object].push_back(static_cast<int>(o));
  }
  std::vector<std::vector<bool>> link_object_allowed(
      n, std::vector<bool>(scene_.obstacles.size(), false));
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
  return link_object_allowed;
}

// shapes_ (every link's shapes, in link order) and shape_begin_.
void CollisionChecker::index_shapes() {
  const int n = static_cast<int>(model_->links().size());
  std::vector<int> first_shape(static_cast<std::size_t>(n) + 1, 0);
  for (int l = 0; l < n; ++l) {
    first_shape[static_cast<std::size_t>(l)] = static_cast<int>(shapes_.size());
    const Link& link = model_->link(l);
    for (int s = 0; s < static_cast<int>(link.shapes.size()); ++s) {
      const CollisionShape& cs = link.shapes[static_cast<std::size_t>(s)];
      shapes_.push_back({l, s, cs.origin * cs.bounding_center, cs.bounding_radius, link.name,
                         cs.origin.matrix() == Eigen::Matrix4d::Identity(),
                         cs.origin * point_inside(cs.shape)});
    }
  }
  first_shape[static_cast<std::size_t>(n)] = static_cast<int>(shapes_.size());
  shape_begin_ = first_shape;
}

// The ball enclosing the balls of shapes_[begin, end) (one link's: their centres share its
// frame), about the middle of their centres' bounding box.
void CollisionChecker::enclosing_ball(int begin, int end, Eigen::Vector3d* center,
                                      double* radius) const {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int sh = begin; sh < end; ++sh) {
    lo = lo.cwiseMin(shapes_[static_cast<std::size_t>(sh)].center);
    hi = hi.cwiseMax(shapes_[static_cast<std::size_t>(sh)].center);
  }
  *center = 0.5 * (lo + hi);
  *radius = 0.0;
  for (int sh = begin; sh < end; ++sh) {
    const RobotShape& rs = shapes_[static_cast<std::size_t>(sh)];
    *radius = std::max(*radius, (rs.center - *center).norm() + rs.radius);
  }
}

// link_balls_, and self_pairs_ in self_blocks_ (one per checked link pair).
void CollisionChecker::build_self_pairs() {
  // Pairs of links with geometry only: quadratic in those, not in all links. A link's ball
  // encloses its shapes' balls (about the middle of their centres' bounding box): a link pair
  // whose balls are apart needs none of its shape pairs (decomposed links have many).
  const std::vector<int> solid = model_->links_with_geometry();
  link_ball_of_link_.assign(model_->links().size(), -1);
  for (int l : solid) {
    link_ball_of_link_[static_cast<std::size_t>(l)] = static_cast<int>(link_balls_.size());
    LinkBall ball{l, Eigen::Vector3d::Zero(), 0.0};
    enclosing_ball(shape_begin_[static_cast<std::size_t>(l)],
                   shape_begin_[static_cast<std::size_t>(l) + 1], &ball.center, &ball.radius);
    link_balls_.push_back(ball);
  }
  for (std::size_t i = 0; i < solid.size(); ++i) {
    for (std::size_t k = i + 1; k < solid.size(); ++k) {
      const int a = solid[i];
      const int b = solid[k];
      if (matrix_.allowed(a, b)) continue;
      const int begin = static_cast<int>(self_pairs_.size());
      for (int sa = shape_begin_[static_cast<std::size_t>(a)];
           sa < shape_begin_[static_cast<std::size_t>(a) + 1]; ++sa) {
        for (int sb = shape_begin_[static_cast<std::size_t>(b)];
             sb < shape_begin_[static_cast<std::size_t>(b) + 1]; ++sb) {
          self_pairs_.push_back({sa, sb});
        }
      }
      self_blocks_.push_back(
          {static_cast<int>(i), static_cast<int>(k), begin, static_cast<int>(self_pairs_.size())});
      self_block_balls_.push_back(static_cast<int>(i));
      self_block_balls_.push_back(static_cast<int>(k));
    }
  }
  has_self_pairs_ = !self_pairs_.empty();
}

// groups_ of the obstacle broad phase, their balls, and the link balls' bounding shapes.
void CollisionChecker::build_groups() {
  // Groups of whole links, up to kGroupSize shapes; the pieces of a decomposed mesh are a group
  // of their own, bounded by the mesh's hull.
  {
    const auto piece_of = [&](int sh) -> const CollisionShape& {
      const RobotShape& rs = shapes_[static_cast<std::size_t>(sh)];
      return model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)];
    };
    int begin = 0;
    for (int sh = 0; sh < static_cast<int>(shapes_.size());) {
      const CollisionShape& cs = piece_of(sh);
      if (cs.element_hull) {  // a decomposed mesh's pieces, consecutive
        if (sh > begin) groups_.push_back({begin, sh});
        groups_.push_back({sh, sh + cs.piece_count, sh});
        sh += cs.piece_count;
        begin = sh;
        continue;
      }
      const int link = shapes_[static_cast<std::size_t>(sh)].link;
      const int link_end = shape_begin_[static_cast<std::size_t>(link) + 1];
      bool decomposed = false;  // does the rest of this link hold a decomposed mesh?
      for (int k = sh; k < link_end; ++k) decomposed = decomposed || piece_of(k).element_hull;
      const int stop = decomposed ? sh + 1 : link_end;  // whole links when possible
      if (sh > begin && stop - begin > kGroupSize) {
        groups_.push_back({begin, sh});
        begin = sh;
      }
      sh = stop;
    }
    if (static_cast<int>(shapes_.size()) > begin) {
      groups_.push_back({begin, static_cast<int>(shapes_.size())});
    }
  }
  for (ShapeGroup& group : groups_) {  // one link's group: a ball fixed in the link's frame
    const int link = shapes_[static_cast<std::size_t>(group.begin)].link;
    if (shapes_[static_cast<std::size_t>(group.end - 1)].link != link) continue;
    group.link = link;
    enclosing_ball(group.begin, group.end, &group.local_center, &group.radius);
  }
  group_ball_begin_.assign(1, 0);
  for (const ShapeGroup& group : groups_) {  // shapes are ordered by link
    for (int sh = group.begin; sh < group.end; ++sh) {
      const int ball =
          link_ball_of_link_[static_cast<std::size_t>(shapes_[static_cast<std::size_t>(sh)].link)];
      if (static_cast<int>(group_balls_.size()) == group_ball_begin_.back() ||
          group_balls_.back() != ball) {
        group_balls_.push_back(ball);
      }
    }
    group_ball_begin_.push_back(static_cast<int>(group_balls_.size()));
  }
  for (LinkBall& ball : link_balls_) {
    const int begin = shape_begin_[static_cast<std::size_t>(ball.link)];
    const int end = shape_begin_[static_cast<std::size_t>(ball.link) + 1];
    const CollisionShape& first = model_->link(ball.link).shapes.front();
    if (end - begin == 1 || (first.element_hull && first.piece_count == end - begin)) {
      ball.bound = begin;
    }
  }
}

// boxes_ (one per obstacle) and environment_pairs_ in blocks_ (one per group and obstacle).
void CollisionChecker::build_environment_pairs(
    const std::vector<std::vector<bool>>& link_object_allowed) {
  for (const Obstacle& o : scene_.obstacles) {
    Eigen::Vector3d center, half;
    local_box(o.shape, &center, &half);
    boxes_.push_back({o.pose.linear().transpose(), o.pose * center, half});
    obstacle_points_.push_back(o.pose * point_inside(o.shape));
    exact_box_.push_back(o.shape.kind() == ShapeKind::kBox && o.shape.margin() == 0.0);
    // Packed as ball_tests_block.hpp's kBoxValues: rotation row by row, centre, half extents.
    const ObstacleBox& box = boxes_.back();
    for (int i = 0; i < 9; ++i) box_values_.push_back(box.rotation_t(i / 3, i % 3));
    for (int i = 0; i < 3; ++i) box_values_.push_back(box.center[i]);
    for (int i = 0; i < 3; ++i) box_values_.push_back(box.half_extents[i]);
  }
  box_rows_ = detail::pack_box_rows(box_values_.data(), boxes_.size());
  group_block_begin_.assign(1, 0);
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    for (int o = 0; o < static_cast<int>(scene_.obstacles.size()); ++o) {
      const int begin = static_cast<int>(environment_pairs_.size());
      for (int s = groups_[static_cast<std::size_t>(g)].begin;
           s < groups_[static_cast<std::size_t>(g)].end; ++s) {
        const auto link = static_cast<std::size_t>(shapes_[static_cast<std::size_t>(s)].link);
        if (!link_object_allowed[link][static_cast<std::size_t>(o)]) {
          environment_pairs_.push_back({s, o});
        }
      }
      const int end = static_cast<int>(environment_pairs_.size());
      if (end > begin) blocks_.push_back({g, o, begin, end});
    }
    group_block_begin_.push_back(static_cast<int>(blocks_.size()));
  }
}

void CollisionChecker::require_current_padding() const {
  if (model_->padding_revision() != padding_revision_) {
    throw std::logic_error("CollisionChecker: robot '" + model_->name() +
                           "': its padding changed after the checker was built (the bounding "
                           "volumes hold the old one); build a new checker");
  }
}

void CollisionChecker::place(const std::vector<Eigen::Isometry3d>& link_poses, Scratch& s) const {
  require_current_padding();
  if (link_poses.size() != model_->links().size()) {
    throw InputError("CollisionChecker: got " + std::to_string(link_poses.size()) +
                     " link poses, robot '" + model_->name() + "' has " +
                     std::to_string(model_->links().size()) + " links");
  }
  s.link_poses_in = &link_poses;
  s.q = nullptr;
  ++s.stamp;
  // Shape ball centres are computed when a test needs them (center()); a decomposed mesh's
  // pieces are many, and most queries never look at them.
  for (std::size_t i = 0; i < link_balls_.size(); ++i) {
    s.link_centers[i] =
        link_poses[static_cast<std::size_t>(link_balls_[i].link)] * link_balls_[i].center;
  }
  // Group balls: one link's group has a fixed ball in that link's frame; a group of several
  // links gets one around the mean of its members' centres, enclosing every member's ball.
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    const ShapeGroup& group = groups_[g];
    if (group.link >= 0) {
      s.group_centers[g] = link_poses[static_cast<std::size_t>(group.link)] * group.local_center;
      s.group_radii[g] = group.radius;
      continue;
    }
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int i = group.begin; i < group.end; ++i) c += center(i, s);
    c /= static_cast<double>(group.end - group.begin);
    double radius = 0.0;
    for (int i = group.begin; i < group.end; ++i) {
      radius =
          std::max(radius, (center(i, s) - c).norm() + shapes_[static_cast<std::size_t>(i)].radius);
    }
    s.group_centers[g] = c;
    s.group_radii[g] = radius;
  }
}

const Eigen::Vector3d& CollisionChecker::center(int shape, Scratch& s) const {
  const auto i = static_cast<std::size_t>(shape);
  if (s.centered[i] != s.stamp) {
    s.centered[i] = s.stamp;
    s.centers[i] =
        (*s.link_poses_in)[static_cast<std::size_t>(shapes_[i].link)] * shapes_[i].center;
  }
  return s.centers[i];
}

const Eigen::Isometry3d& CollisionChecker::shape_pose(int shape, Scratch& s) const {
  const auto i = static_cast<std::size_t>(shape);
  const RobotShape& rs = shapes_[i];
  const Eigen::Isometry3d& link_pose = (*s.link_poses_in)[static_cast<std::size_t>(rs.link)];
  if (rs.at_link_frame) return link_pose;
  if (s.posed[i] != s.stamp) {
    s.shape_poses[i] =
        link_pose * model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].origin;
    s.posed[i] = s.stamp;
  }
  return s.shape_poses[i];
}

const Shape& CollisionChecker::shape_of(int shape) const {
  const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
  return model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].shape;
}

const Shape& CollisionChecker::bounding_shape(int shape) const {
  const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
  const CollisionShape& cs = model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)];
  return cs.element_hull ? *cs.element_hull : cs.shape;
}

double CollisionChecker::pair_ball_gap(std::size_t i, Scratch& s) const {
  const std::size_t n_env = environment_pairs_.size();
  if (i < n_env) {
    const EnvironmentPair& p = environment_pairs_[i];
    return box_gap(boxes_[static_cast<std::size_t>(p.obstacle)], center(p.shape, s),
                   shapes_[static_cast<std::size_t>(p.shape)].radius);
  }
  const SelfPair& p = self_pairs_[i - n_env];
  return (center(p.a, s) - center(p.b, s)).norm() - shapes_[static_cast<std::size_t>(p.a)].radius -
         shapes_[static_cast<std::size_t>(p.b)].radius;
}

double CollisionChecker::box_gap(const ObstacleBox& box, const Eigen::Vector3d& c, double radius,
                                 Eigen::Vector3d* direction) const {
  const Eigen::Vector3d local = box.rotation_t * (c - box.center);
  const Eigen::Vector3d excess = local.cwiseAbs() - box.half_extents;
  const Eigen::Vector3d beyond = excess.cwiseMax(0.0);
  const double outside = beyond.norm();
  if (direction != nullptr) {
    // World direction from the box towards the centre: from the nearest box point when the
    // centre is outside, else the normal of the nearest face.
    Eigen::Vector3d d;
    if (outside > 0.0) {
      d = beyond.cwiseProduct(local.cwiseSign()) / outside;
    } else {
      Eigen::Index k = 0;
      excess.maxCoeff(&k);
      d = Eigen::Vector3d::Unit(k) * (local[k] < 0.0 ? -1.0 : 1.0);
    }
    *direction = box.rotation_t.transpose() * d;
  }
  // A lower bound on the signed distance between anything in the ball and anything in the
  // box. Centre outside: the gap minus the radius. Centre inside: minus the ball's penetration
  // depth, the radius plus the centre's depth below the nearest face (-radius alone is no
  // bound: a deeper pair would be culled and clearance would report a shallower one).
  return (outside > 0.0 ? outside : excess.maxCoeff()) - radius;
}

}  // namespace hullcheck
