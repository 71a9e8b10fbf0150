// CollisionChecker's motion bounds: the lever arms of each joint over the shapes it moves, and
// the bounds built on them (motion_bound, safe_advance's conservative advancement).
#include <algorithm>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <variant>
#include <vector>

#include "collision_checker_internals.hpp"

namespace hullcheck {

namespace {

// The largest value of `bound` over the points of collision shape `cs` (padding included),
// where `bound(p)` is at least the distance of link-frame point p from a line (over every
// configuration of the joints in between): over a polyhedron's vertices (the distance from a
// line is convex, so largest at one), for round shapes at their centres plus their radius (the
// distance from a line changes by at most the distance moved).
template <typename Bound>
double farthest(const CollisionShape& cs, const Bound& bound) {
  const auto at = [&](const Eigen::Vector3d& local) { return bound(cs.origin * local); };
  const Shape::Geometry& g = cs.shape.geometry();
  double d = 0.0;
  if (const auto* box = std::get_if<Box>(&g)) {
    for (int c = 0; c < 8; ++c) {
      d = std::max(d, at(Eigen::Vector3d((c & 1 ? 1 : -1) * box->half_extents.x(),
                                         (c & 2 ? 1 : -1) * box->half_extents.y(),
                                         (c & 4 ? 1 : -1) * box->half_extents.z())));
    }
  } else if (const auto* sphere = std::get_if<Sphere>(&g)) {
    d = at(Eigen::Vector3d::Zero()) + sphere->radius;
  } else if (const auto* capsule = std::get_if<Capsule>(&g)) {  // axis z: its caps' centres
    d = std::max(at(Eigen::Vector3d(0, 0, capsule->half_length)),
                 at(Eigen::Vector3d(0, 0, -capsule->half_length))) +
        capsule->radius;
  } else if (const auto* cylinder = std::get_if<Cylinder>(&g)) {  // axis z: its discs' centres
    d = std::max(at(Eigen::Vector3d(0, 0, cylinder->half_length)),
                 at(Eigen::Vector3d(0, 0, -cylinder->half_length))) +
        cylinder->radius;
  } else {
    for (const Eigen::Vector3d& v : std::get<ConvexHull>(g).vertices()) d = std::max(d, at(v));
  }
  return d + cs.shape.margin();
}

// Where a link below a revolute joint J sits relative to J's axis (the line through J's child
// link frame's origin along J's unit axis, fixed in that frame): a point p of the link (its own
// frame) lies at most distance(p) from the axis, for every value of the joints in between.
// The moving joints K between J and the link, from J down, each with `pre` (K's joint frame
// into the frame of the moving joint above, J's child frame for the first; fixed joints folded
// in) and `tail` (the link's frame into the last K's child frame). Going up through K, a point
// z of K's child frame is turned about K's axis: its part along the axis stays, the rest keeps
// its length wherever it turns (or, for a prismatic K, z slides by at most its travel). The
// distance from J's axis changes by at most the distance a point moves, so it is at most the
// bound at the part that stays plus the length of the part that turns (or the travel).
struct AxisBound {
  struct Level {
    Eigen::Isometry3d pre;
    Eigen::Vector3d axis;  // K's, in K's joint frame
    double travel;         // prismatic K: its travel; revolute: < 0
  };
  std::vector<Level> levels;
  Eigen::Isometry3d tail = Eigen::Isometry3d::Identity();

  double distance(const Eigen::Vector3d& p, const Eigen::Vector3d& axis) const {
    Eigen::Vector3d z = tail * p;
    double moved = 0.0;  // how far the turning parts move the point, at most
    for (auto level = levels.rbegin(); level != levels.rend(); ++level) {
      if (level->travel >= 0.0) {
        moved += level->travel;
      } else {
        const Eigen::Vector3d along = z.dot(level->axis) * level->axis;
        moved += (z - along).norm();
        z = along;
      }
      z = level->pre * z;
    }
    return (z - z.dot(axis) * axis).norm() + moved;
  }
  // The bound of the link below `joint`, a child joint of this bound's link.
  AxisBound below(const Joint& joint) const {
    AxisBound out = *this;
    if (joint.type == JointType::kFixed) {
      out.tail = tail * joint.origin;
      return out;
    }
    out.levels.push_back({tail * joint.origin, joint.axis,
                          joint.type == JointType::kPrismatic ? joint.limit_reach() : -1.0});
    out.tail = Eigen::Isometry3d::Identity();
    return out;
  }
};

}  // namespace

// above[l][j]: joint j is on the path from the root to link l.
std::vector<std::vector<bool>> CollisionChecker::joints_above_links() const {
  const int n = static_cast<int>(model_->links().size());
  const int joint_count = static_cast<int>(model_->joints().size());
  std::vector<std::vector<bool>> above(static_cast<std::size_t>(n),
                                       std::vector<bool>(static_cast<std::size_t>(joint_count)));
  for (int l = 0; l < n; ++l) {
    for (int x = l; model_->link(x).parent_joint >= 0;) {
      const int j = model_->link(x).parent_joint;
      above[static_cast<std::size_t>(l)][static_cast<std::size_t>(j)] = true;
      x = model_->joint(j).parent_link;
    }
  }
  return above;
}

int CollisionChecker::relative_drivers(int link_a, int link_b, int at_most, int* keys,
                                       bool* revolute) const {
  // The joints above exactly one link are those between it and the two links' deepest common
  // ancestor: climb from the deeper link until both meet.
  int count = 0;
  if (revolute != nullptr) *revolute = true;
  const auto climb = [&](int* link) {
    const Joint& joint = model_->joint(model_->link(*link).parent_joint);
    *link = joint.parent_link;
    if (joint.type == JointType::kFixed) return true;
    if (revolute != nullptr && joint.type == JointType::kPrismatic) *revolute = false;
    const int v = joint.driver();
    if (std::find(keys, keys + std::min(count, at_most), v) != keys + std::min(count, at_most)) {
      return true;
    }
    if (count < at_most) keys[count] = v;
    return ++count <= at_most;
  };
  while (link_a != link_b) {
    int* deeper = link_depth_[static_cast<std::size_t>(link_a)] >=
                          link_depth_[static_cast<std::size_t>(link_b)]
                      ? &link_a
                      : &link_b;
    if (!climb(deeper)) return at_most + 1;
  }
  return count;
}

const Eigen::MatrixXd& CollisionChecker::joint_arms() const {
  // They depend on the model's shapes and kinematics only: built once per model (and padding
  // revision), shared by its checkers.
  ModelSelfTables& shared = *self_tables_->model;
  const std::lock_guard<std::mutex> lock(shared.mutex);
  if (shared.joint_arms_built) return shared.joint_arms;
  const int n = static_cast<int>(model_->links().size());
  const int joint_count = static_cast<int>(model_->joints().size());
  Eigen::MatrixXd& arm = shared.joint_arms;
  arm = Eigen::MatrixXd::Zero(joint_count, static_cast<Eigen::Index>(shapes_.size()));
  // reach[l]: distance from the joint's origin to link l's frame origin (the ball bound).
  std::vector<double> reach(static_cast<std::size_t>(n));
  std::vector<AxisBound> axis_bound(static_cast<std::size_t>(n));
  for (int ji = 0; ji < joint_count; ++ji) {
    const Joint& joint = model_->joint(ji);
    if (joint.type == JointType::kFixed) continue;
    const bool prismatic = joint.type == JointType::kPrismatic;
    std::vector<int> stack{joint.child_link};
    reach[static_cast<std::size_t>(joint.child_link)] = 0.0;
    axis_bound[static_cast<std::size_t>(joint.child_link)] = AxisBound{};
    while (!stack.empty()) {
      const int l = stack.back();
      stack.pop_back();
      const AxisBound& here = axis_bound[static_cast<std::size_t>(l)];
      for (int sh = shape_begin_[static_cast<std::size_t>(l)];
           sh < shape_begin_[static_cast<std::size_t>(l) + 1]; ++sh) {
        const RobotShape& rs = shapes_[static_cast<std::size_t>(sh)];
        const CollisionShape& cs = model_->link(l).shapes[static_cast<std::size_t>(rs.shape)];
        const double ball = reach[static_cast<std::size_t>(l)] + rs.center.norm() + rs.radius;
        arm(ji, sh) = prismatic ? 1.0 : std::min(ball, farthest(cs, [&](const Eigen::Vector3d& p) {
                                                   return here.distance(p, joint.axis);
                                                 }));
      }
      for (int k : model_->link(l).child_joints) {
        const Joint& child = model_->joint(k);
        const double travel = child.type == JointType::kPrismatic ? child.limit_reach() : 0.0;
        reach[static_cast<std::size_t>(child.child_link)] =
            reach[static_cast<std::size_t>(l)] + child.origin.translation().norm() + travel;
        axis_bound[static_cast<std::size_t>(child.child_link)] = here.below(child);
        stack.push_back(child.child_link);
      }
    }
  }
  shared.joint_arms_built = true;
  return arm;
}

const CollisionChecker::MotionLevers& CollisionChecker::motion_levers() const {
  std::call_once(motion_levers_->built, [this] { build_motion_levers(*motion_levers_); });
  return *motion_levers_;
}

void CollisionChecker::build_motion_levers(MotionLevers& out) const {
  const std::vector<std::vector<bool>> above = joints_above_links();
  // Lever arms: for each movable joint, a bound on how far any point of each shape it moves
  // travels per unit of the joint's own value. A prismatic joint moves them by one. A revolute
  // joint turns them on circles about its axis, a line fixed in its child link's frame: a
  // point's lever is its distance from that line, bounded over every configuration of the
  // joints in between (AxisBound: exact on the child link and rigidly attached ones); never
  // more than the bound through the shape's bounding ball.
  const int variables = model_->variable_count();
  out.lever = Eigen::VectorXd::Zero(variables);
  out.shape_levers = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(shapes_.size()), variables);
  out.self_pair_levers =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(self_pairs_.size()), variables);
  const int joint_count = static_cast<int>(model_->joints().size());
  // arm(j, s): motion of shape s per unit of joint j's own value (0 when j does not move s).
  const Eigen::MatrixXd& arm = joint_arms();
  for (int ji = 0; ji < joint_count; ++ji) {
    const Joint& joint = model_->joint(ji);
    if (joint.type == JointType::kFixed) continue;
    const int v = joint.driver();
    const double m = std::abs(joint.driver_multiplier());
    out.lever[v] += m * arm.row(ji).maxCoeff();
    out.shape_levers.col(v) += m * arm.row(ji).transpose();
  }
  // A self pair's: the joints above exactly one of its links move one shape relative to the
  // other (those above both move them rigidly together). Per block (one link pair), the joints
  // once, then its pairs: a column's entries are consecutive (decomposed links have thousands).
  for (const SelfBlock& block : self_blocks_) {
    const int link_a = link_balls_[static_cast<std::size_t>(block.link_a)].link;
    const int link_b = link_balls_[static_cast<std::size_t>(block.link_b)].link;
    for (int ji = 0; ji < joint_count; ++ji) {
      const Joint& joint = model_->joint(ji);
      if (joint.type == JointType::kFixed) continue;
      const bool above_a = above[static_cast<std::size_t>(link_a)][static_cast<std::size_t>(ji)];
      const bool above_b = above[static_cast<std::size_t>(link_b)][static_cast<std::size_t>(ji)];
      if (above_a == above_b) continue;
      const double m = std::abs(joint.driver_multiplier());
      double* column = out.self_pair_levers.col(joint.driver()).data();
      for (int p = block.begin; p < block.end; ++p) {
        const SelfPair& pair = self_pairs_[static_cast<std::size_t>(p)];
        column[p] += m * arm(ji, above_a ? pair.a : pair.b);
      }
    }
  }
  out.joint_arms = &arm;
  out.link_chains.assign(model_->links().size(), {});
  for (std::size_t link = 0; link < model_->links().size(); ++link) {
    std::vector<int>& chain = out.link_chains[link];
    for (int l = static_cast<int>(link); model_->link(l).parent_joint >= 0;) {
      const int j = model_->link(l).parent_joint;
      if (model_->joint(j).type != JointType::kFixed) chain.push_back(j);
      l = model_->joint(j).parent_link;
    }
    std::reverse(chain.begin(), chain.end());  // from the root down
  }
  // A bounding volume's levers: per value, the largest of its members'.
  const auto raise = [](Eigen::MatrixXd& levers, std::size_t row, const auto& member) {
    levers.row(static_cast<Eigen::Index>(row)) =
        levers.row(static_cast<Eigen::Index>(row)).cwiseMax(member);
  };
  out.group_levers = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(groups_.size()), variables);
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    for (int sh = groups_[g].begin; sh < groups_[g].end; ++sh) {
      raise(out.group_levers, g, out.shape_levers.row(sh));
    }
  }
  out.group_arms = Eigen::MatrixXd::Zero(joint_count, static_cast<Eigen::Index>(groups_.size()));
  out.group_link.assign(groups_.size(), -1);
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    const auto col = static_cast<Eigen::Index>(g);
    out.group_link[g] = shapes_[static_cast<std::size_t>(groups_[g].begin)].link;
    for (int sh = groups_[g].begin; sh < groups_[g].end; ++sh) {
      out.group_arms.col(col) = out.group_arms.col(col).cwiseMax(arm.col(sh));
      if (shapes_[static_cast<std::size_t>(sh)].link != out.group_link[g]) out.group_link[g] = -1;
    }
  }
  out.link_ball_arms =
      Eigen::MatrixXd::Zero(joint_count, static_cast<Eigen::Index>(link_balls_.size()));
  for (std::size_t b = 0; b < link_balls_.size(); ++b) {
    const auto link = static_cast<std::size_t>(link_balls_[b].link);
    for (int sh = shape_begin_[link]; sh < shape_begin_[link + 1]; ++sh) {
      out.link_ball_arms.col(static_cast<Eigen::Index>(b)) =
          out.link_ball_arms.col(static_cast<Eigen::Index>(b)).cwiseMax(arm.col(sh));
    }
  }
  out.self_block_levers =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(self_blocks_.size()), variables);
  for (std::size_t k = 0; k < self_blocks_.size(); ++k) {
    const SelfBlock& block = self_blocks_[k];
    out.self_block_levers.row(static_cast<Eigen::Index>(k)) =
        out.self_pair_levers.middleRows(block.begin, block.end - block.begin).colwise().maxCoeff();
  }
  out.many_drivers.assign(self_blocks_.size(), 0);
  for (std::size_t k = 0; k < self_blocks_.size(); ++k) {
    int keys[2];
    out.many_drivers[k] =
        relative_drivers(link_balls_[static_cast<std::size_t>(self_blocks_[k].link_a)].link,
                         link_balls_[static_cast<std::size_t>(self_blocks_[k].link_b)].link, 2,
                         keys) > 2;
  }
  out.cluster_levers =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(self_clusters_.size()), variables);
  for (std::size_t k = 0; k < self_clusters_.size(); ++k) {
    for (int i = self_clusters_[k].begin; i < self_clusters_[k].end; ++i) {
      raise(out.cluster_levers, k,
            out.self_block_levers.row(cluster_blocks_[static_cast<std::size_t>(i)]));
    }
  }
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
  // Per-thread scratch: allocates on first use only.
  if (s.abs_dq.size() != dq.size()) s.abs_dq.resize(dq.size());
  if (s.q_end.size() != dq.size()) s.q_end.resize(dq.size());
  Eigen::VectorXd& abs_dq = s.abs_dq;
  abs_dq = dq.cwiseAbs();
  s.q_end = q + dq;
  // Lever arms assume prismatic joints within their limits; beyond them (RobotModel does not
  // clamp), shapes below sit further from the rotating joints above. Over t in [0, 1] a
  // prismatic value stays within max(|q|, |q + dq|): add that excess times the rotation of
  // every joint above, to every pair (conservative), and certify no further than t = 1.
  const double extra = prismatic_excess_motion(q, s.q_end);
  const MotionLevers& levers = motion_levers();
  // Per pair: gap lower bound (bounding volumes) and motion per unit s.
  double best = std::numeric_limits<double>::infinity();
  std::size_t first = n_all;
  for (std::size_t i = 0; i < n_all; ++i) {
    const double lb = pair_ball_gap(i, s);
    const double motion =
        i < n_env ? levers.shape_levers.row(environment_pairs_[i].shape).dot(abs_dq) + extra
                  : levers.self_pair_levers.row(static_cast<Eigen::Index>(i - n_env)).dot(abs_dq) +
                        2.0 * extra;
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
  require_current_padding();
  const double bound =
      (q1 - q0).cwiseAbs().dot(motion_levers().lever) + prismatic_excess_motion(q0, q1);
  return has_self_pairs_ ? 2.0 * bound : bound;
}

}  // namespace hullcheck
