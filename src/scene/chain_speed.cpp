// chain_speed: how fast the points of a shape move at one configuration of a straight joint
// motion, and a bound on how fast that speed changes.
//
// The speed. Along q(t) = q0 + t dq every turning joint j of the chain turns at the constant
// rate w_j = multiplier_j dq[driver_j] about its axis: the unit vector u_j through the point o_j
// (its child link frame's origin), both at the placed configuration. Relative to the frame F
// that the joints before chain[from] move, a point p of the shape moves at
//   v(p) = sum_j w_j u_j x (p - o_j)                                   (j >= from)
// (the velocity of p minus that of F's point at p; a vector's length does not depend on the
// frame it is written in). v is affine in p: v(p) = v(c) + W x (p - c) with W = sum_j w_j u_j,
// so |v(p)| <= |v(c)| + |W| radius for every p within `radius` of c, and along a unit vector n
// (fixed in F), |n . v(p)| <= |n . v(c)| + |n x W| radius (n . (W x r) = (n x W) . r).
//
// The change of speed. With o_j taken as the foot of p on axis j (v, and the expression below,
// do not depend on which point of the axis is taken), |p - o_j| = the distance of p from axis j
// <= L_j = arms[j], at every configuration. Differentiating,
//   dv/dt = sum_j w_j [ du_j/dt x (p - o_j) + u_j x (dp/dt - do_j/dt) ].
// Axis j turns with the joints above it: du_j/dt = W_j x u_j, W_j = sum_{i<j} w_i u_i, so the
// first term is at most |W_j| L_j. The point o_j moves with the joints above j, so
//   dp/dt - do_j/dt = W_j x (p - o_j) + sum_{i>=j} w_i u_i x (p - o_i),
// at most |W_j| L_j + sum_{i>=j} |w_i| L_i. Hence, with S_j = sum_{i<j} |w_i| >= |W_j|,
//   |dv/dt| <= sum_j |w_j| (2 S_j L_j + sum_{i>=j} |w_i| L_i) =: accel
// over every configuration. Within [m - h, m + h], |p(t) - p(m)| <= |t - m| speed + (t - m)^2
// accel / 2 <= |t - m| (speed + h accel / 2), and its component along n changes by at most
// |t - m| (along(n) + h accel / 2).
//
// Rounding. The terms of v(c) may cancel; its computed length is within about 1e-16 of
// sum_j |w_j| |c - o_j| of the true one: speed adds 1e-12 of that sum plus the lever rate
// sum_j |w_j| L_j, accel 1e-12 of sum_j |w_j| times the lever rate (the running sums').
#include "chain_speed.hpp"

#include <cmath>

namespace hullcheck {

ChainSpeed chain_speed(const RobotModel& model, const std::vector<Eigen::Isometry3d>& poses,
                       const std::vector<int>& chain, std::size_t from, const Eigen::VectorXd& dq,
                       const double* arms, const Eigen::Vector3d& centre, double radius) {
  ChainSpeed out;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();     // v(centre)
  Eigen::Vector3d turn = Eigen::Vector3d::Zero();  // W
  double above = 0.0;                              // S_j: summed |w_i| of the joints passed
  double lever_rate = 0.0, spread = 0.0;
  // sum_{i>=j} |w_i| L_i for the first j: the lever rate, then less each joint passed.
  for (std::size_t k = from; k < chain.size(); ++k) {
    const Joint& joint = model.joint(chain[k]);
    lever_rate += std::abs(joint.driver_multiplier() * dq[joint.driver()]) * arms[chain[k]];
  }
  double below = lever_rate;
  for (std::size_t k = from; k < chain.size(); ++k) {
    const Joint& joint = model.joint(chain[k]);
    const double w = joint.driver_multiplier() * dq[joint.driver()];
    if (w == 0.0) continue;
    if (joint.type == JointType::kPrismatic) {
      out.usable = false;
      return out;
    }
    const double lever = arms[chain[k]];
    const Eigen::Isometry3d& frame = poses[static_cast<std::size_t>(joint.child_link)];
    const Eigen::Vector3d u = frame.linear() * joint.axis;
    const Eigen::Vector3d arm = centre - frame.translation();
    v += w * u.cross(arm);
    turn += w * u;
    spread += std::abs(w) * arm.norm();
    out.accel += std::abs(w) * (2.0 * above * lever + below);
    above += std::abs(w);
    below -= std::abs(w) * lever;
  }
  out.velocity = v;
  out.turn = turn;
  out.radius = radius;
  out.slack = 1e-12 * (lever_rate + spread);
  out.speed = v.norm() + turn.norm() * radius + out.slack;
  out.accel += 1e-12 * above * lever_rate;  // `below`'s rounding
  return out;
}

}  // namespace hullcheck
