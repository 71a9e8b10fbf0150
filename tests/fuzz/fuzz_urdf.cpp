// libFuzzer target: URDF text -> RobotModel, then forward kinematics at the default
// configuration. Relative and package://hullcheck_arm/ meshes resolve to the own arm's meshes.
#include <Eigen/Geometry>
#include <hullcheck/robot/robot_model.hpp>
#include <vector>

#include "fuzz_support.hpp"

// One input: a URDF document.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hullcheck;
  static const RobotLoadOptions options = fuzz::arm_options();
  static const std::string base_dir = fuzz::arm_dir() + "/urdf";
  fuzz::expect_input_errors_only([&] {
    const RobotModel model =
        RobotModel::from_urdf_string(fuzz::as_string(data, size), base_dir, options, "<fuzz>");
    std::vector<Eigen::Isometry3d> poses;
    model.compute_link_poses(model.default_configuration(), poses);
  });
  return 0;
}
