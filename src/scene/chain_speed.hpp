// Speed bounds of a link's points at one configuration of a straight joint motion, and of how
// fast that speed can change: check_motion's rates from the configuration at an interval's
// middle instead of the lever arms alone (chain_speed.cpp derives them).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <hullcheck/robot/robot_model.hpp>
#include <vector>

namespace hullcheck {

/// For a set of points of one link along q(t) = q0 + t dq, relative to the frame that the
/// joints chain[0, from) move (the world when from = 0): `speed` bounds |dp/dt| at the placed
/// configuration (m per unit t), `accel` bounds |d^2p/dt^2| at every configuration (m per unit
/// t^2). Within t in [m - h, m + h] every such point then stays within
///   |t - m| (speed + h accel / 2)
/// of where it is at q(m). `usable` is false when a prismatic joint of the chain moves (the
/// derivation covers turning joints only): use the lever arms' rate then.
/// Along a unit direction n (fixed in that frame) the points' component changes at most at
/// |n . velocity| + |n x turn| radius + slack at the configuration (velocity: the centre's,
/// turn: the link's angular velocity, both world vectors), and that rate itself by at most
/// accel per unit t (along()).
struct ChainSpeed {
  double speed = 0.0;
  double accel = 0.0;
  bool usable = true;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d turn = Eigen::Vector3d::Zero();
  double radius = 0.0;
  double slack = 0.0;  // rounding, m per unit t

  /// The rate at the configuration along unit vector n (see above).
  double along(const Eigen::Vector3d& n) const;
};

/// How fast, at the configuration, the points of `a` and those of `b` (bounds relative to the
/// same frame) can change their components along unit vector n relative to each other: at most
/// |n . (a.velocity - b.velocity)| + |n x a.turn| a.radius + |n x b.turn| b.radius + slacks.
inline double relative_along(const ChainSpeed& a, const ChainSpeed& b, const Eigen::Vector3d& n) {
  return std::abs(n.dot(a.velocity - b.velocity)) + n.cross(a.turn).norm() * a.radius +
         n.cross(b.turn).norm() * b.radius + a.slack + b.slack;
}

inline double ChainSpeed::along(const Eigen::Vector3d& n) const {
  return relative_along(*this, ChainSpeed{}, n);
}

/// The bound for the points within `radius` of `centre` (world, m), points of shapes carried by
/// the joints `chain` (movable joints from the root down, MotionLevers::link_chains) beyond
/// chain[from]; `arms[j]` bounds their distance from joint j's axis over every configuration
/// (a column of CollisionChecker::joint_arms, or the largest of several). `poses`: the model's
/// link poses at the configuration (world). Allocation-free; a pure function of its inputs.
ChainSpeed chain_speed(const RobotModel& model, const std::vector<Eigen::Isometry3d>& poses,
                       const std::vector<int>& chain, std::size_t from, const Eigen::VectorXd& dq,
                       const double* arms, const Eigen::Vector3d& centre, double radius);

}  // namespace hullcheck
