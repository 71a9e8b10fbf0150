// Gradient of the clearance of a pair with respect to the joint values.
#pragma once

#include <Eigen/Geometry>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <vector>

namespace hullcheck {

/// d(pair.distance)/dq for the pair of `pair` (from CollisionChecker::clearance_at at these
/// `link_poses`), one entry per configuration value (m/rad or m/m), treating the witness points
/// as fixed on their links and the normal as fixed (exact for vertex-face contact, a
/// first-order direction otherwise). Moving q along the gradient increases the pair's
/// distance. Zero when the pair is undefined (link_a < 0). Mimic joints add to their leader's
/// entry. Allocates the returned vector.
Eigen::VectorXd clearance_gradient(const RobotModel& model,
                                   const std::vector<Eigen::Isometry3d>& link_poses,
                                   const ClearanceResult& pair);

}  // namespace hullcheck
