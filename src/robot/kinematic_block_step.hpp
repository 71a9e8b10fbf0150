// One step of forward kinematics in plain form, for the SIMD kernel of
// RobotModel::compute_link_poses_block (forward_kinematics_block.cpp): the same data as
// RobotModel's private KinematicStep, without Eigen types.
#pragma once

namespace hullcheck::detail {

struct KinematicBlockStep {
  enum Type { kFixed, kRevolute, kPrismatic };
  int link = 0;
  int anchor = -1;                 // -1: the model frame
  double offset_rotation[9] = {};  // row by row
  double offset_translation[3] = {};
  Type type = kFixed;   // continuous joints are kRevolute
  int axis_index = -1;  // 0/1/2 when the axis is +-x/y/z, else -1
  double axis_sign = 1.0;
  double axis[3] = {1.0, 0.0, 0.0};
  int variable = -1;
  double multiplier = 1.0;
  double offset = 0.0;
};

}  // namespace hullcheck::detail
