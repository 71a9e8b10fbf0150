#include <hullcheck/core/errors.hpp>
#include <hullcheck/scene/clearance_gradient.hpp>

namespace hullcheck {
namespace {

// Adds sign * n . dp/dq for the point p fixed on `link`, over the joints above it.
void add_chain(const RobotModel& model, const std::vector<Eigen::Isometry3d>& poses, int link,
               const Eigen::Vector3d& p, const Eigen::Vector3d& n, double sign,
               Eigen::VectorXd* gradient) {
  for (int l = link; model.link(l).parent_joint >= 0;) {
    const Joint& joint = model.joint(model.link(l).parent_joint);
    if (joint.type != JointType::kFixed) {
      const int variable = joint.driver();
      const double multiplier = joint.driver_multiplier();
      // The joint's axis in the model frame: the child frame's orientation times the axis
      // (rotation about the axis leaves it unchanged); its origin: the child frame's origin.
      const Eigen::Isometry3d& child = poses[static_cast<std::size_t>(joint.child_link)];
      const Eigen::Vector3d axis = child.linear() * joint.axis;
      const Eigen::Vector3d velocity = joint.type == JointType::kPrismatic
                                           ? axis
                                           : Eigen::Vector3d(axis.cross(p - child.translation()));
      (*gradient)[variable] += sign * multiplier * n.dot(velocity);
    }
    l = joint.parent_link;
  }
}

}  // namespace

Eigen::VectorXd clearance_gradient(const RobotModel& model,
                                   const std::vector<Eigen::Isometry3d>& link_poses,
                                   const ClearanceResult& pair) {
  if (link_poses.size() != model.links().size()) {
    throw InputError("clearance_gradient: link_poses does not match robot '" + model.name() + "'");
  }
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(model.variable_count());
  if (pair.link_a < 0) return gradient;
  // distance = n . (p_b - p_a): moving p_a along n shrinks it, moving p_b along n grows it.
  add_chain(model, link_poses, pair.link_a, pair.point_a, pair.normal, -1.0, &gradient);
  if (pair.self && pair.link_b >= 0) {
    add_chain(model, link_poses, pair.link_b, pair.point_b, pair.normal, +1.0, &gradient);
  }
  return gradient;
}

}  // namespace hullcheck
