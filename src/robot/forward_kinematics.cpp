// Forward kinematics of RobotModel: the load-time plan (fixed joints folded into constant
// offsets) and the allocation-free evaluation.
#include <atomic>
#include <cmath>
#include <cstdint>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <sstream>

namespace hullcheck {

void RobotModel::build_kinematics() {
  static std::atomic<std::uint64_t> next_id{1};
  kinematics_id_ = next_id++;
  // anchor[l]: the link whose frame l is rigidly attached to (-1: model frame), and the
  // constant transform anchor -> l.
  std::vector<int> anchor(links_.size(), -1);
  std::vector<Eigen::Isometry3d> to_anchor(links_.size(), Eigen::Isometry3d::Identity());
  steps_.clear();
  steps_.reserve(links_.size());
  for (std::size_t l = 0; l < links_.size(); ++l) {
    KinematicStep step;
    step.link = static_cast<int>(l);
    const int j = links_[l].parent_joint;
    if (j < 0) {  // root: the model frame itself
      steps_.push_back(step);
      continue;
    }
    const Joint& joint = joints_[static_cast<std::size_t>(j)];
    const auto parent = static_cast<std::size_t>(joint.parent_link);
    const Eigen::Isometry3d offset = to_anchor[parent] * joint.origin;
    step.anchor = anchor[parent];
    step.offset_rotation = offset.linear();
    step.offset_translation = offset.translation();
    step.type = joint.type;
    if (joint.type == JointType::kFixed) {
      anchor[l] = anchor[parent];
      to_anchor[l] = offset;
      steps_.push_back(step);
      continue;
    }
    anchor[l] = static_cast<int>(l);
    step.axis = joint.axis;
    for (int k = 0; k < 3; ++k) {
      // Exactly +-e_k (after normalisation): rotate two columns instead of a matrix product.
      if (std::abs(joint.axis[k]) == 1.0 && joint.axis[(k + 1) % 3] == 0.0 &&
          joint.axis[(k + 2) % 3] == 0.0) {
        step.axis_index = k;
        step.axis_sign = joint.axis[k] > 0.0 ? 1.0 : -1.0;
      }
    }
    step.variable = joint.driver();
    step.multiplier = joint.driver_multiplier();
    step.offset = joint.driver_offset();
    steps_.push_back(step);
  }
}

void RobotModel::check_configuration(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  if (q.size() != variable_count()) {
    std::ostringstream msg;
    msg << "robot '" << name_ << "': configuration has " << q.size() << " values, expected "
        << variable_count() << " (";
    for (int i = 0; i < variable_count(); ++i) {
      msg << (i ? ", " : "") << joint(variable_joint(i)).name;
    }
    msg << ")";
    throw InputError(msg.str());
  }
  for (int i = 0; i < variable_count(); ++i) {
    if (!std::isfinite(q[i])) {
      std::ostringstream msg;
      msg << "robot '" << name_ << "': configuration value " << i << " (joint '"
          << joint(variable_joint(i)).name << "') is " << q[i];
      throw InputError(msg.str());
    }
  }
}

void RobotModel::check_joint_range(int variable, double value, double tolerance) const {
  const Joint& j = joint(variable_joint(variable));
  const bool continuous = j.type == JointType::kContinuous;
  const bool inside = continuous ? std::abs(value) <= kMaxContinuousValue
                                 : value >= j.lower - tolerance && value <= j.upper + tolerance;
  if (inside) return;
  std::ostringstream msg;
  msg << "robot '" << name_ << "': joint '" << j.name << "' (configuration value " << variable
      << ") is " << value;
  if (continuous) {
    msg << ", beyond the +-" << kMaxContinuousValue << " rad accepted for a continuous joint";
  } else {
    msg << ", outside its limits [" << j.lower << ", " << j.upper << "] by more than " << tolerance;
  }
  throw InputError(msg.str());
}

void RobotModel::check_joint_ranges(const Eigen::Ref<const Eigen::VectorXd>& q,
                                    double tolerance) const {
  check_configuration(q);
  for (int i = 0; i < variable_count(); ++i) check_joint_range(i, q[i], tolerance);
}

void RobotModel::compute_link_poses(const Eigen::Ref<const Eigen::VectorXd>& q,
                                    std::vector<Eigen::Isometry3d>& link_poses) const {
  check_configuration(q);
  if (link_poses.size() != links_.size()) link_poses.resize(links_.size());
  compute_link_poses_unchecked(q.data(), link_poses.data());
}

void RobotModel::compute_link_poses_unchecked(const double* q,
                                              Eigen::Isometry3d* link_poses) const {
  for (const KinematicStep& step : steps_) {
    Eigen::Isometry3d& pose = link_poses[step.link];
    if (step.anchor < 0) {
      pose.linear() = step.offset_rotation;
      pose.translation() = step.offset_translation;
    } else {
      const Eigen::Isometry3d& a = link_poses[step.anchor];
      pose.linear().noalias() = a.linear() * step.offset_rotation;
      pose.translation().noalias() = a.linear() * step.offset_translation;
      pose.translation() += a.translation();
    }
    if (step.type == JointType::kFixed) continue;
    const double value = step.multiplier * q[step.variable] + step.offset;
    auto r = pose.linear();
    if (step.type == JointType::kPrismatic) {
      pose.translation().noalias() += (value * r) * step.axis;
      continue;
    }
    // Revolute: pose.linear() <- pose.linear() * Rot(axis, value).
    if (step.axis_index >= 0) {
      const double angle = step.axis_sign * value;
      const double c = std::cos(angle);
      const double s = std::sin(angle);
      const int i = (step.axis_index + 1) % 3;
      const int j = (step.axis_index + 2) % 3;
      const Eigen::Vector3d ci = r.col(i);
      const Eigen::Vector3d cj = r.col(j);
      r.col(i) = c * ci + s * cj;
      r.col(j) = c * cj - s * ci;
    } else {
      const Eigen::Matrix3d rot = Eigen::AngleAxisd(value, step.axis).toRotationMatrix();
      const Eigen::Matrix3d before = r;
      r.noalias() = before * rot;
    }
  }
}

}  // namespace hullcheck
