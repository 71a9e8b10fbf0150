#include <algorithm>
#include <cmath>
#include <cstdint>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/queries.hpp>
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

// Robot shapes per group of the obstacle broad phase: a group's bounding ball is tested
// against an obstacle first, its shapes only when it is not clear (consecutive links follow
// the kinematic chain, so a group is a few neighbouring links, or one decomposed link).
constexpr int kGroupSize = 4;

// Bounds on the signed distance of A and B from their supporting planes normal to the unit
// vector n (from A towards B): every point of A is at most n.a_max along n, every point of
// B at least n.b_min, so distance >= n.(b_min - a_max) (and depth <= -that when overlapping:
// the difference A - B reaches no further than that along -n). The two support points are
// points of the shapes, so their distance bounds the signed distance from above.
void slab_bounds(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                 const Eigen::Isometry3d& pose_b, const Eigen::Vector3d& n, double* lower,
                 double* upper) {
  const Eigen::Vector3d a_max = pose_a * a.support(pose_a.linear().transpose() * n);
  const Eigen::Vector3d b_min = pose_b * b.support(-(pose_b.linear().transpose() * n));
  *lower = n.dot(b_min - a_max);
  *upper = (b_min - a_max).norm();
}

// Queue codes of nearest_pair's blocks (negative; pairs are 2 * pair + refined, >= 0): block
// `index` (self blocks first, then obstacle blocks), refined once its bounding shapes'
// distance is in.
int block_code(std::size_t index, bool refined) {
  return -1 - (2 * static_cast<int>(index) + (refined ? 1 : 0));
}
std::size_t block_index(int code) { return static_cast<std::size_t>((-1 - code) / 2); }
bool block_refined(int code) { return (-1 - code) % 2 == 1; }

}  // namespace

struct CollisionChecker::Scratch {
  std::vector<Eigen::Isometry3d> link_poses;
  std::vector<Eigen::Isometry3d> shape_poses;
  std::vector<Eigen::Vector3d> centers;
  std::vector<double> lower_bounds;
  std::vector<double> motions;
  Eigen::VectorXd abs_dq;
  Eigen::VectorXd q_end;
  // Shape poses are computed when a pair needs them: posed[i] == stamp when shape_poses[i]
  // belongs to the current query (stamp grows with every place(), so no stale pose is used,
  // whichever checker ran before on this thread).
  std::vector<std::uint64_t> posed;
  std::vector<std::uint64_t> centered;  // centers[i] is current when centered[i] == stamp
  std::uint64_t stamp = 0;
  const std::vector<Eigen::Isometry3d>* link_poses_in = nullptr;  // of the current query
  const double* q = nullptr;  // configuration of the current query, when it has one
  std::vector<Eigen::Vector3d> group_centers;
  std::vector<double> group_radii;
  std::vector<Eigen::Vector3d> link_centers;  // per link_balls_ entry, model frame
  // is_valid: per shape, the stamp of the query and self block for which it was found to meet
  // the other link's hull (pieces that do not cannot meet any of that link's pieces).
  std::vector<std::uint64_t> meets_other;
  std::vector<std::pair<double, int>> candidates;  // clearance: queue of (lower bound, code)
  std::vector<std::pair<double, int>> nearest;     // clearance: (ball bound, code)
  std::vector<std::pair<double, int>> expanded;    // clearance: a block's pairs
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
    s.posed.resize(shapes_.size(), 0);
    s.centered.resize(shapes_.size(), 0);
    s.meets_other.resize(shapes_.size(), 0);
  }
  if (s.group_centers.size() < groups_.size()) {
    s.group_centers.resize(groups_.size());
    s.group_radii.resize(groups_.size());
  }
  if (s.link_centers.size() < link_balls_.size()) s.link_centers.resize(link_balls_.size());
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
      shapes_.push_back({l, s, cs.origin * cs.bounding_center, cs.bounding_radius, link.name,
                         cs.origin.matrix() == Eigen::Matrix4d::Identity()});
    }
  }
  first_shape[static_cast<std::size_t>(n)] = static_cast<int>(shapes_.size());
  shape_begin_ = first_shape;
  // The ball enclosing the balls of shapes_[begin, end) (one link's: their centres share its
  // frame), about the middle of their centres' bounding box.
  const auto enclosing_ball = [&](int begin, int end, Eigen::Vector3d* center, double* radius) {
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
  };
  // Pairs of links with geometry only: quadratic in those, not in all links. A link's ball
  // encloses its shapes' balls (about the middle of their centres' bounding box): a link pair
  // whose balls are apart needs none of its shape pairs (decomposed links have many).
  const std::vector<int> solid = model_->links_with_geometry();
  for (int l : solid) {
    LinkBall ball{l, Eigen::Vector3d::Zero(), 0.0};
    enclosing_ball(first_shape[static_cast<std::size_t>(l)],
                   first_shape[static_cast<std::size_t>(l) + 1], &ball.center, &ball.radius);
    link_balls_.push_back(ball);
  }
  for (std::size_t i = 0; i < solid.size(); ++i) {
    for (std::size_t k = i + 1; k < solid.size(); ++k) {
      const int a = solid[i];
      const int b = solid[k];
      if (matrix_.allowed(a, b)) continue;
      const int begin = static_cast<int>(self_pairs_.size());
      for (int sa = first_shape[static_cast<std::size_t>(a)];
           sa < first_shape[static_cast<std::size_t>(a) + 1]; ++sa) {
        for (int sb = first_shape[static_cast<std::size_t>(b)];
             sb < first_shape[static_cast<std::size_t>(b) + 1]; ++sb) {
          self_pairs_.push_back({sa, sb});
        }
      }
      self_blocks_.push_back(
          {static_cast<int>(i), static_cast<int>(k), begin, static_cast<int>(self_pairs_.size())});
    }
  }
  has_self_pairs_ = !self_pairs_.empty();
  for (const Obstacle& o : scene_.obstacles) {
    Eigen::Vector3d center, half;
    local_box(o.shape, &center, &half);
    boxes_.push_back({o.pose.linear().transpose(), o.pose * center, half});
  }
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
      const int link_end = first_shape[static_cast<std::size_t>(link) + 1];
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
  for (LinkBall& ball : link_balls_) {
    const int begin = first_shape[static_cast<std::size_t>(ball.link)];
    const int end = first_shape[static_cast<std::size_t>(ball.link) + 1];
    const CollisionShape& first = model_->link(ball.link).shapes.front();
    if (end - begin == 1 || (first.element_hull && first.piece_count == end - begin)) {
      ball.bound = begin;
    }
  }
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
  }

  // Lever arms. For each movable joint, the largest distance from its origin to any point of
  // each shape it moves: reach[l] bounds the distance from the joint's origin to the frame
  // origin of link l below it (accumulated along the chain, prismatic travel included).
  const int variables = model_->variable_count();
  lever_ = Eigen::VectorXd::Zero(variables);
  shape_levers_ = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(shapes_.size()), variables);
  self_pair_levers_ =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(self_pairs_.size()), variables);
  const int joint_count = static_cast<int>(model_->joints().size());
  // arm(j, s): motion of shape s per unit of joint j's own value (0 when j does not move s).
  Eigen::MatrixXd arm =
      Eigen::MatrixXd::Zero(joint_count, static_cast<Eigen::Index>(shapes_.size()));
  std::vector<double> reach(static_cast<std::size_t>(n));
  for (int ji = 0; ji < joint_count; ++ji) {
    const Joint& joint = model_->joint(ji);
    if (joint.type == JointType::kFixed) continue;
    std::vector<int> stack{joint.child_link};
    reach[static_cast<std::size_t>(joint.child_link)] = 0.0;
    while (!stack.empty()) {
      const int l = stack.back();
      stack.pop_back();
      for (int sh = first_shape[static_cast<std::size_t>(l)];
           sh < first_shape[static_cast<std::size_t>(l) + 1]; ++sh) {
        const RobotShape& rs = shapes_[static_cast<std::size_t>(sh)];
        arm(ji, sh) = joint.type == JointType::kPrismatic
                          ? 1.0
                          : reach[static_cast<std::size_t>(l)] + rs.center.norm() + rs.radius;
      }
      for (int k : model_->link(l).child_joints) {
        const Joint& child = model_->joint(k);
        const double travel = child.type == JointType::kPrismatic ? child.limit_reach() : 0.0;
        reach[static_cast<std::size_t>(child.child_link)] =
            reach[static_cast<std::size_t>(l)] + child.origin.translation().norm() + travel;
        stack.push_back(child.child_link);
      }
    }
  }
  // Joints above each link.
  std::vector<std::vector<bool>> above(static_cast<std::size_t>(n),
                                       std::vector<bool>(static_cast<std::size_t>(joint_count)));
  for (int l = 0; l < n; ++l) {
    for (int x = l; model_->link(x).parent_joint >= 0;) {
      const int j = model_->link(x).parent_joint;
      above[static_cast<std::size_t>(l)][static_cast<std::size_t>(j)] = true;
      x = model_->joint(j).parent_link;
    }
  }
  for (int ji = 0; ji < joint_count; ++ji) {
    const Joint& joint = model_->joint(ji);
    if (joint.type == JointType::kFixed) continue;
    const int v = joint.driver();
    const double m = std::abs(joint.driver_multiplier());
    lever_[v] += m * arm.row(ji).maxCoeff();
    shape_levers_.col(v) += m * arm.row(ji).transpose();
    for (std::size_t p = 0; p < self_pairs_.size(); ++p) {
      const int a = self_pairs_[p].a, b = self_pairs_[p].b;
      const bool above_a =
          above[static_cast<std::size_t>(shapes_[static_cast<std::size_t>(a)].link)]
               [static_cast<std::size_t>(ji)];
      const bool above_b =
          above[static_cast<std::size_t>(shapes_[static_cast<std::size_t>(b)].link)]
               [static_cast<std::size_t>(ji)];
      if (above_a == above_b) continue;  // moves both rigidly, or neither
      self_pair_levers_(static_cast<Eigen::Index>(p), v) += m * arm(ji, above_a ? a : b);
    }
  }
  build_warm_start_grids(above);
}

void CollisionChecker::place(const std::vector<Eigen::Isometry3d>& link_poses, Scratch& s) const {
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

const Shape& CollisionChecker::shape_of(int shape) const {
  const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
  return model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].shape;
}

const Shape& CollisionChecker::bounding_shape(int shape) const {
  const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
  const CollisionShape& cs = model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)];
  return cs.element_hull ? *cs.element_hull : cs.shape;
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
  // Balls against oriented boxes: a shape group's ball first, then its shapes' balls. A ball
  // is clear of a box when its centre is further than its radius from the box.
  const auto clear = [](const ObstacleBox& box, const Eigen::Vector3d& c, double radius) {
    const Eigen::Vector3d local = box.rotation_t * (c - box.center);
    return (local.cwiseAbs() - box.half_extents).cwiseMax(0.0).squaredNorm() > radius * radius;
  };
  for (const EnvironmentBlock& block : blocks_) {
    const ObstacleBox& box = boxes_[static_cast<std::size_t>(block.obstacle)];
    const auto g = static_cast<std::size_t>(block.group);
    if (block.end - block.begin > 1 && clear(box, s.group_centers[g], s.group_radii[g])) continue;
    const int bound = groups_[g].bound;
    if (bound >= 0 && block.end - block.begin > 1) {
      // A decomposed mesh: its hull first (it contains every piece; one query, not one each).
      const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(block.obstacle)];
      if (!intersect(bounding_shape(bound), shape_pose(bound, s), o.shape, o.pose)) continue;
    }
    for (int i = block.begin; i < block.end; ++i) {
      const int shape = environment_pairs_[static_cast<std::size_t>(i)].shape;
      const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
      if (clear(box, center(shape, s), rs.radius)) continue;
      const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(block.obstacle)];
      if (intersect(model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].shape,
                    shape_pose(shape, s), o.shape, o.pose)) {
        return false;
      }
    }
  }
  for (const SelfBlock& block : self_blocks_) {
    // Non-zero when the pieces meeting the other link's hull are marked with it (below).
    std::uint64_t mark = 0;
    if (block.end - block.begin > 1) {
      const double reach = link_balls_[static_cast<std::size_t>(block.link_a)].radius +
                           link_balls_[static_cast<std::size_t>(block.link_b)].radius;
      if ((s.link_centers[static_cast<std::size_t>(block.link_a)] -
           s.link_centers[static_cast<std::size_t>(block.link_b)])
              .squaredNorm() > reach * reach) {
        continue;
      }
      // Links that are one shape or one decomposed mesh: their hulls first.
      const int bound_a = link_balls_[static_cast<std::size_t>(block.link_a)].bound;
      const int bound_b = link_balls_[static_cast<std::size_t>(block.link_b)].bound;
      if (bound_a >= 0 && bound_b >= 0) {
        const Shape& hull_a = bounding_shape(bound_a);
        const Shape& hull_b = bounding_shape(bound_b);
        const Eigen::Isometry3d& pose_a = shape_pose(bound_a, s);
        const Eigen::Isometry3d& pose_b = shape_pose(bound_b, s);
        if (!intersect(hull_a, pose_a, hull_b, pose_b)) continue;
        if (block.end - block.begin > kGroupSize) {
          // Many piece pairs: each piece against the other link's hull first; only pieces
          // meeting it can meet a piece of that link. A mark is this query and block's stamp.
          mark = (s.stamp << 20) + static_cast<std::uint64_t>(&block - self_blocks_.data()) + 1;
          bool any_a = false, any_b = false;
          const auto mark_pieces = [&](int link_ball, const Shape& other,
                                       const Eigen::Isometry3d& other_pose, bool* any) {
            const int l = link_balls_[static_cast<std::size_t>(link_ball)].link;
            for (int sh = shape_begin_[static_cast<std::size_t>(l)];
                 sh < shape_begin_[static_cast<std::size_t>(l) + 1]; ++sh) {
              if (intersect(shape_of(sh), shape_pose(sh, s), other, other_pose)) {
                s.meets_other[static_cast<std::size_t>(sh)] = mark;
                *any = true;
              }
            }
          };
          mark_pieces(block.link_a, hull_b, pose_b, &any_a);
          if (!any_a) continue;
          mark_pieces(block.link_b, hull_a, pose_a, &any_b);
          if (!any_b) continue;
        }
      }
    }
    for (int k = block.begin; k < block.end; ++k) {
      const SelfPair& p = self_pairs_[static_cast<std::size_t>(k)];
      if (mark != 0 && (s.meets_other[static_cast<std::size_t>(p.a)] != mark ||
                        s.meets_other[static_cast<std::size_t>(p.b)] != mark)) {
        continue;  // one of the two pieces is clear of the other link's hull
      }
      const double reach = shapes_[static_cast<std::size_t>(p.a)].radius +
                           shapes_[static_cast<std::size_t>(p.b)].radius;
      if ((center(p.a, s) - center(p.b, s)).squaredNorm() > reach * reach) continue;
      if (intersect(shape_of(p.a), shape_pose(p.a, s), shape_of(p.b), shape_pose(p.b, s))) {
        return false;
      }
    }
  }
  return true;
}

SignedDistanceResult CollisionChecker::pair_distance_below(std::size_t i, double cutoff,
                                                           Scratch& s) const {
  const std::size_t n_env = environment_pairs_.size();
  if (i < n_env) {
    const EnvironmentPair& p = environment_pairs_[i];
    const RobotShape& rs = shapes_[static_cast<std::size_t>(p.shape)];
    const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(p.obstacle)];
    return signed_distance_below(
        model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].shape,
        shape_pose(p.shape, s), o.shape, o.pose, cutoff);
  }
  const SelfPair& p = self_pairs_[i - n_env];
  const RobotShape& a = shapes_[static_cast<std::size_t>(p.a)];
  const RobotShape& b = shapes_[static_cast<std::size_t>(p.b)];
  const WarmStartGrid& grid = warm_grids_[i - n_env];
  if (grid.dims >= 0 && s.q != nullptr) {
    WarmStart warm = grid.at(s.q);
    return signed_distance_below(
        model_->link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape, shape_pose(p.a, s),
        model_->link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape, shape_pose(p.b, s),
        cutoff, warm);
  }
  return signed_distance_below(model_->link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape,
                               shape_pose(p.a, s),
                               model_->link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape,
                               shape_pose(p.b, s), cutoff);
}

ClearanceResult CollisionChecker::clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  model_->check_configuration(q);
  Scratch& s = scratch();
  model_->compute_link_poses_unchecked(q.data(), s.link_poses.data());
  place(s.link_poses, s);
  s.q = q.data();
  return nearest_pair(s);
}

ClearanceResult CollisionChecker::clearance_at(
    const std::vector<Eigen::Isometry3d>& link_poses) const {
  Scratch& s = scratch();
  place(link_poses, s);
  return nearest_pair(s);
}

ClearanceResult CollisionChecker::nearest_pair(Scratch& s) const {
  ClearanceResult best;
  const std::size_t n_env = environment_pairs_.size();
  if (n_env + self_pairs_.size() == 0) return best;
  // Best-first search over the pairs by lower bounds on their signed distance, refined lazily:
  // bounding balls (and, for a group of shapes, the group's ball) for every pair, the slab
  // between the shapes' supporting planes (along the balls' direction, or a self pair's
  // warm-start direction) only for a pair that comes first with its ball bound, and the exact
  // signed distance only for a pair that comes first with its slab bound. `cut` is an upper
  // bound on the minimum (the distance between two points of some pair's shapes, from the
  // slabs): a pair whose bound exceeds it cannot be the closest. The search ends when the
  // smallest bound left reaches the best exact value. Queue entries: (lower bound, 2 * pair + 1
  // once the slab bound is in).
  double cut = std::numeric_limits<double>::infinity();
  // Slab bound of pair i whose ball bound is `ball`: the refined lower bound; tightens the cut.
  const auto refine = [&](std::size_t i, double ball) {
    double slab, upper;
    if (i < n_env) {
      const EnvironmentPair& p = environment_pairs_[i];
      const RobotShape& rs = shapes_[static_cast<std::size_t>(p.shape)];
      const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(p.obstacle)];
      Eigen::Vector3d towards_shape;
      box_gap(boxes_[static_cast<std::size_t>(p.obstacle)], center(p.shape, s), rs.radius,
              &towards_shape);
      slab_bounds(model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].shape,
                  shape_pose(p.shape, s), o.shape, o.pose, -towards_shape, &slab, &upper);
    } else {
      const SelfPair& p = self_pairs_[i - n_env];
      const RobotShape& a = shapes_[static_cast<std::size_t>(p.a)];
      const RobotShape& b = shapes_[static_cast<std::size_t>(p.b)];
      const Eigen::Isometry3d& pose_a = shape_pose(p.a, s);
      Eigen::Vector3d n;
      const WarmStartGrid& grid = warm_grids_[i - n_env];
      const Eigen::Vector3d* direction =
          grid.dims >= 0 && s.q != nullptr ? &grid.at(s.q).direction : nullptr;
      if (direction != nullptr && direction->squaredNorm() > 0.0) {
        // The closest pair's direction at the grid cell's centre: a near-optimal slab.
        n = -(pose_a.linear() * *direction).normalized();
      } else {  // the balls' direction
        const Eigen::Vector3d ab = center(p.b, s) - center(p.a, s);
        const double centres = ab.norm();
        if (!(centres > 0.0)) return ball;  // concentric balls: no direction, no slab
        n = ab / centres;
      }
      slab_bounds(model_->link(a.link).shapes[static_cast<std::size_t>(a.shape)].shape, pose_a,
                  model_->link(b.link).shapes[static_cast<std::size_t>(b.shape)].shape,
                  shape_pose(p.b, s), n, &slab, &upper);
    }
    cut = std::min(cut, upper);
    return std::max(ball, slab);
  };
  // Ball bounds of the self pairs, a link pair with several shape pairs (decomposed meshes) as
  // one entry bounded by the links' balls (a block code, negative), expanded into its pairs
  // when it comes first. A block of an obstacle and a decomposed mesh's pieces likewise. Block
  // entries come first with their ball bound, then (when both sides have one bounding shape)
  // with the distance between the bounding shapes, a lower bound for every pair inside. The nearest
  // pair is refined at once: its slab sets a first cut that culls most obstacle pairs (on arms the
  // closest pair is often a self pair).
  s.nearest.clear();
  const auto pair_ball = [&](std::size_t k) {
    const SelfPair& p = self_pairs_[k];
    return (center(p.b, s) - center(p.a, s)).norm() -
           shapes_[static_cast<std::size_t>(p.a)].radius -
           shapes_[static_cast<std::size_t>(p.b)].radius;
  };
  const auto push_pairs = [&](const SelfBlock& block, std::vector<std::pair<double, int>>* to) {
    for (int k = block.begin; k < block.end; ++k) {
      to->emplace_back(pair_ball(static_cast<std::size_t>(k)), 2 * static_cast<int>(n_env) + 2 * k);
    }
  };
  for (std::size_t b = 0; b < self_blocks_.size(); ++b) {
    const SelfBlock& block = self_blocks_[b];
    if (block.end - block.begin <= kGroupSize) {
      push_pairs(block, &s.nearest);
      continue;
    }
    const LinkBall& la = link_balls_[static_cast<std::size_t>(block.link_a)];
    const LinkBall& lb = link_balls_[static_cast<std::size_t>(block.link_b)];
    s.nearest.emplace_back((s.link_centers[static_cast<std::size_t>(block.link_a)] -
                            s.link_centers[static_cast<std::size_t>(block.link_b)])
                                   .norm() -
                               la.radius - lb.radius,
                           block_code(b, false));
  }
  if (!s.nearest.empty()) {  // the nearest entry a block: its pairs instead
    const auto it = std::min_element(s.nearest.begin(), s.nearest.end());
    if (it->second < 0) {
      const SelfBlock& block = self_blocks_[block_index(it->second)];
      *it = s.nearest.back();
      s.nearest.pop_back();
      push_pairs(block, &s.nearest);
    }
  }
  const auto refine_nearest = [&](std::size_t from) {
    if (s.nearest.size() <= from) return;
    const auto it = std::min_element(
        s.nearest.begin() + static_cast<std::ptrdiff_t>(from), s.nearest.end(),
        [](const auto& x, const auto& y) {  // pairs only (blocks have negative codes)
          return (x.second >= 0) != (y.second >= 0) ? x.second >= 0 : x < y;
        });
    if (it->second < 0) return;
    it->first = refine(static_cast<std::size_t>(it->second / 2), it->first);
    it->second |= 1;
  };
  refine_nearest(0);
  // box_gap(box, c, radius) when it is below the cut; the square root only then.
  const auto ball_below_cut = [](const ObstacleBox& box, const Eigen::Vector3d& c, double radius,
                                 double cut_now, double* gap) {
    const Eigen::Vector3d local = box.rotation_t * (c - box.center);
    const Eigen::Vector3d excess = local.cwiseAbs() - box.half_extents;
    const double outside_squared = excess.cwiseMax(0.0).squaredNorm();
    if (outside_squared == 0.0) {
      *gap = excess.maxCoeff() - radius;
    } else {
      const double reach = cut_now + radius;  // gap < cut <=> outside < reach
      if (!(reach > 0.0) || outside_squared >= reach * reach) return false;
      *gap = std::sqrt(outside_squared) - radius;
    }
    return *gap < cut_now;
  };
  // The pairs of an obstacle block with their ball bounds below the cut.
  const auto push_environment_pairs = [&](const EnvironmentBlock& block,
                                          std::vector<std::pair<double, int>>* to) {
    const ObstacleBox& box = boxes_[static_cast<std::size_t>(block.obstacle)];
    double ball = 0.0;
    for (int i = block.begin; i < block.end; ++i) {
      const int shape = environment_pairs_[static_cast<std::size_t>(i)].shape;
      if (ball_below_cut(box, center(shape, s), shapes_[static_cast<std::size_t>(shape)].radius,
                         cut, &ball)) {
        to->emplace_back(ball, 2 * i);
      }
    }
  };
  const std::size_t environment_begin = s.nearest.size();
  for (const EnvironmentBlock& block : blocks_) {
    const ObstacleBox& box = boxes_[static_cast<std::size_t>(block.obstacle)];
    const auto g = static_cast<std::size_t>(block.group);
    double ball = 0.0;
    if (block.end - block.begin > 1 &&
        !ball_below_cut(box, s.group_centers[g], s.group_radii[g], cut, &ball)) {
      continue;
    }
    if (groups_[g].bound >= 0 && block.end - block.begin > kGroupSize) {
      s.nearest.emplace_back(
          ball, block_code(self_blocks_.size() + static_cast<std::size_t>(&block - blocks_.data()),
                           false));
      continue;
    }
    push_environment_pairs(block, &s.nearest);
  }
  refine_nearest(environment_begin);  // the nearest obstacle pair tightens the cut in turn
  // The queue: a binary heap, smallest bound on top (ties by pair: deterministic).
  auto& queue = s.candidates;
  queue.clear();
  for (const auto& entry : s.nearest) {
    if (entry.first <= cut) queue.push_back(entry);
  }
  const auto later = [](const std::pair<double, int>& x, const std::pair<double, int>& y) {
    return x > y;
  };
  std::make_heap(queue.begin(), queue.end(), later);
  const auto evaluate = [&](std::size_t i) {
    ++best.exact_queries;
    const SignedDistanceResult r = pair_distance_below(i, best.distance, s);
    best.iterations += r.iterations;
    if (r.status == Status::kAboveCutoff || !(r.signed_distance < best.distance)) return;
    best.distance = r.signed_distance;
    best.point_a = r.point_a;
    best.point_b = r.point_b;
    best.normal = r.normal;
    best.status = r.status;
    if (i < n_env) {
      const EnvironmentPair& p = environment_pairs_[i];
      const RobotShape& rs = shapes_[static_cast<std::size_t>(p.shape)];
      best.self = false;
      best.link_a = rs.link;
      best.shape_a = rs.shape;
      best.link_b = best.shape_b = -1;
      best.obstacle = p.obstacle;
      best.name_a = rs.link_name;
      best.name_b = scene_.obstacles[static_cast<std::size_t>(p.obstacle)].name;
    } else {
      const SelfPair& p = self_pairs_[i - n_env];
      const RobotShape& a = shapes_[static_cast<std::size_t>(p.a)];
      const RobotShape& b = shapes_[static_cast<std::size_t>(p.b)];
      best.self = true;
      best.link_a = a.link;
      best.shape_a = a.shape;
      best.link_b = b.link;
      best.shape_b = b.shape;
      best.obstacle = -1;
      best.name_a = a.link_name;
      best.name_b = b.link_name;
    }
  };

  // Each exact query stops as soon as it proves its pair no closer than the best so far (on a
  // colliding state, a separated pair costs a boolean test and a shallow one a few EPA steps).
  while (!queue.empty()) {
    std::pop_heap(queue.begin(), queue.end(), later);
    const auto [bound, code] = queue.back();
    queue.pop_back();
    // Strictly above the cut: the pair that set the cut has a bound at most the cut and is
    // still queued or evaluated.
    if (bound >= best.distance || bound > cut) break;
    if (code < 0) {
      const std::size_t index = block_index(code);
      const bool self_block = index < self_blocks_.size();
      if (!block_refined(code)) {
        // The bounding shapes' distance: a lower bound for every pair of the block (each
        // side's shapes lie in its bounding shape). Overlapping bounds bound nothing: expand.
        int bound_a = -1, bound_b = -1;
        const Shape* shape_b = nullptr;
        const Eigen::Isometry3d* pose_b = nullptr;
        if (self_block) {
          const SelfBlock& block = self_blocks_[index];
          bound_a = link_balls_[static_cast<std::size_t>(block.link_a)].bound;
          bound_b = link_balls_[static_cast<std::size_t>(block.link_b)].bound;
          if (bound_b >= 0) {
            shape_b = &bounding_shape(bound_b);
            pose_b = &shape_pose(bound_b, s);
          }
        } else {
          const EnvironmentBlock& block = blocks_[index - self_blocks_.size()];
          bound_a = groups_[static_cast<std::size_t>(block.group)].bound;
          const Obstacle& o = scene_.obstacles[static_cast<std::size_t>(block.obstacle)];
          shape_b = &o.shape;
          pose_b = &o.pose;
        }
        if (bound_a >= 0 && shape_b != nullptr) {
          ++best.exact_queries;
          const DistanceResult d =
              distance(bounding_shape(bound_a), shape_pose(bound_a, s), *shape_b, *pose_b);
          best.iterations += d.iterations;
          if (d.distance > 0.0) {
            const double refined = std::max(bound, d.distance);
            if (refined >= best.distance || refined > cut) continue;
            queue.emplace_back(refined, block_code(index, true));
            std::push_heap(queue.begin(), queue.end(), later);
            continue;
          }
        }
      }
      // The block's pairs with their own ball bounds.
      std::vector<std::pair<double, int>>& expanded = s.expanded;
      expanded.clear();
      if (self_block) {
        push_pairs(self_blocks_[index], &expanded);
      } else {
        push_environment_pairs(blocks_[index - self_blocks_.size()], &expanded);
      }
      for (const auto& entry : expanded) {
        if (entry.first >= best.distance || entry.first > cut) continue;
        queue.push_back(entry);
        std::push_heap(queue.begin(), queue.end(), later);
      }
      continue;
    }
    const auto i = static_cast<std::size_t>(code / 2);
    if (code % 2 == 1) {
      evaluate(i);
      continue;
    }
    const double refined = refine(i, bound);
    if (refined >= best.distance || refined > cut) continue;
    queue.emplace_back(refined, code | 1);
    std::push_heap(queue.begin(), queue.end(), later);
  }
  return best;
}

double CollisionChecker::safe_advance(const Eigen::Ref<const Eigen::VectorXd>& q,
                                      const Eigen::Ref<const Eigen::VectorXd>& dq,
                                      double min_clearance) const {
  model_->check_configuration(q);
  if (dq.size() != q.size() || !dq.allFinite()) {
    throw InputError("CollisionChecker::safe_advance: dq must have " + std::to_string(q.size()) +
                     " finite values");
  }
  Scratch& s = scratch();
  model_->compute_link_poses_unchecked(q.data(), s.link_poses.data());
  place(s.link_poses, s);
  s.q = q.data();
  const std::size_t n_env = environment_pairs_.size();
  const std::size_t n_all = n_env + self_pairs_.size();
  if (s.motions.size() < n_all) s.motions.resize(n_all);
  if (s.abs_dq.size() != dq.size()) {  // per-thread scratch: allocates on first use only
    s.abs_dq.resize(dq.size());
    s.q_end.resize(dq.size());
  }
  Eigen::VectorXd& abs_dq = s.abs_dq;
  abs_dq = dq.cwiseAbs();
  s.q_end = q + dq;
  // Lever arms assume prismatic joints within their limits; beyond them (RobotModel does not
  // clamp), shapes below sit further from the rotating joints above. Over t in [0, 1] a
  // prismatic value stays within max(|q|, |q + dq|): add that excess times the rotation of
  // every joint above, to every pair (conservative), and certify no further than t = 1.
  const double extra = prismatic_excess_motion(q, s.q_end);
  // Per pair: gap lower bound (bounding volumes) and motion per unit s.
  double best = std::numeric_limits<double>::infinity();
  std::size_t first = n_all;
  for (std::size_t i = 0; i < n_all; ++i) {
    double lb, motion;
    if (i < n_env) {
      const EnvironmentPair& p = environment_pairs_[i];
      lb = box_gap(boxes_[static_cast<std::size_t>(p.obstacle)], center(p.shape, s),
                   shapes_[static_cast<std::size_t>(p.shape)].radius);
      motion = shape_levers_.row(p.shape).dot(abs_dq) + extra;
    } else {
      const SelfPair& p = self_pairs_[i - n_env];
      lb = (center(p.a, s) - center(p.b, s)).norm() -
           shapes_[static_cast<std::size_t>(p.a)].radius -
           shapes_[static_cast<std::size_t>(p.b)].radius;
      motion =
          self_pair_levers_.row(static_cast<Eigen::Index>(i - n_env)).dot(abs_dq) + 2.0 * extra;
    }
    s.lower_bounds[i] = lb;
    s.motions[i] = motion;
    const double key = lb <= min_clearance ? -1.0 : lb / motion;  // inf when motion == 0
    if (key < best || first == n_all) {
      best = key;
      first = i;
    }
  }
  if (n_all == 0) return 1.0;
  // Signed distance of pair i when below `cutoff` (else a proven lower bound >= cutoff);
  // false when it is within min_clearance (touching or overlapping).
  const auto exact = [&](std::size_t i, double cutoff, double* d) {
    *d = pair_distance_below(i, cutoff, s).signed_distance;
    return *d > min_clearance;
  };

  double step = std::numeric_limits<double>::infinity();
  double d = 0.0;
  if (!exact(first, INFINITY, &d)) return -1.0;
  step = d / s.motions[first];
  for (std::size_t i = 0; i < n_all; ++i) {
    if (i == first) continue;
    const double lb = s.lower_bounds[i];
    // Distances from `limit` on cannot shorten the step (a pair that does not move cannot).
    const double limit = s.motions[i] > 0.0 ? step * s.motions[i] : 0.0;
    if (lb > min_clearance && lb >= limit) continue;
    // The query may stop at any proof that the distance reaches max(limit, min_clearance)
    // (a lower bound d >= limit changes nothing below; d <= min_clearance is exact).
    if (!exact(i, std::max(limit, min_clearance), &d)) return -1.0;
    step = std::min(step, d / s.motions[i]);
  }
  return std::min(step, 1.0);
}

double CollisionChecker::prismatic_excess_motion(
    const Eigen::Ref<const Eigen::VectorXd>& q0,
    const Eigen::Ref<const Eigen::VectorXd>& q1) const {
  // The lever arms assume prismatic joints within their limits, which configurations need not
  // respect (RobotModel does not clamp; MBM's Panda start states hold the fingers beyond
  // them). A prismatic value beyond its limits puts the shapes below it up to `beyond` further
  // from every rotating joint above it.
  double extra = 0.0;
  for (const Joint& joint : model_->joints()) {
    if (joint.type != JointType::kPrismatic) continue;
    const int v = joint.driver();
    const double beyond =
        std::abs(joint.driver_multiplier()) * std::max(std::abs(q0[v]), std::abs(q1[v])) +
        std::abs(joint.driver_offset()) - joint.limit_reach();
    if (!(beyond > 0.0)) continue;
    for (int l = joint.parent_link; model_->link(l).parent_joint >= 0;) {
      const Joint& above = model_->joint(model_->link(l).parent_joint);
      if (above.type == JointType::kRevolute || above.type == JointType::kContinuous) {
        const int va = above.driver();
        extra += beyond * std::abs(above.driver_multiplier()) * std::abs(q1[va] - q0[va]);
      }
      l = above.parent_link;
    }
  }
  return extra;
}

double CollisionChecker::motion_bound(const Eigen::Ref<const Eigen::VectorXd>& q0,
                                      const Eigen::Ref<const Eigen::VectorXd>& q1) const {
  model_->check_configuration(q0);
  model_->check_configuration(q1);
  // prismatic_excess_motion: shapes below a prismatic joint beyond its limits.
  const double bound = (q1 - q0).cwiseAbs().dot(lever_) + prismatic_excess_motion(q0, q1);
  return has_self_pairs_ ? 2.0 * bound : bound;
}

}  // namespace hullcheck
