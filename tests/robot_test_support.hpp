// Robots the tests load: the project's own (always present) and the shared test data (tests
// skip those cleanly when ../shared is absent).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <hullcheck/robot/robot_model.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace hullcheck::test {

/// Load options with every mesh as one convex hull (MeshGeometry::kHull), for tests of the
/// hull itself.
inline RobotLoadOptions hull_options() {
  RobotLoadOptions options;
  options.mesh_geometry = MeshGeometry::kHull;
  return options;
}

/// A robot description on disk.
struct RobotFile {
  std::string id;    // short name for test output
  std::string urdf;  // path to the URDF
  std::string srdf;  // path to the SRDF, or empty
};

inline std::string robots_dir() { return HULLCHECK_ROBOTS_DIR; }

/// The project's own robot (robots/hullcheck_arm).
inline RobotFile own_arm() {
  const std::string root = robots_dir() + "/hullcheck_arm";
  return {"hullcheck_arm", root + "/urdf/hullcheck_arm.urdf", root + "/srdf/hullcheck_arm.srdf"};
}

/// Every robot of ../shared/robots and ../shared/benchmarks/mbm/robots whose URDF exists
/// (empty when ../shared is absent).
inline std::vector<RobotFile> shared_robots() {
  const std::string s = shared_dir();
  const std::vector<RobotFile> all = {
      {"panda", s + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf",
       s + "/robots/panda/srdf/panda.srdf"},
      {"ur5e", s + "/robots/ur5e/ur_description/urdf/ur5e.urdf", s + "/robots/ur5e/srdf/ur5e.srdf"},
      {"abb_irb2400", s + "/robots/abb_irb2400/abb_irb2400_support/urdf/irb2400.urdf",
       s + "/robots/abb_irb2400/srdf/abb_irb2400.srdf"},
      {"baxter", s + "/robots/baxter/example-robot-data/robots/baxter_description/urdf/baxter.urdf",
       ""},
      {"mbm_panda", s + "/benchmarks/mbm/robots/panda_obj/panda.urdf",
       s + "/benchmarks/mbm/robots/panda_obj/panda.srdf"},
      {"mbm_panda_spherized", s + "/benchmarks/mbm/robots/panda_obj/panda_spherized.urdf", ""},
      {"mbm_ur5", s + "/benchmarks/mbm/robots/ur5_robotiq85/ur5.urdf",
       s + "/benchmarks/mbm/robots/ur5_robotiq85/ur5.srdf"},
      {"mbm_ur5_spherized", s + "/benchmarks/mbm/robots/ur5_robotiq85/ur5_spherized.urdf", ""},
  };
  std::vector<RobotFile> present;
  for (const RobotFile& r : all) {
    if (std::filesystem::exists(r.urdf)) present.push_back(r);
  }
  return present;
}

/// The own robot followed by the shared ones present.
inline std::vector<RobotFile> all_robots() {
  std::vector<RobotFile> out{own_arm()};
  for (const RobotFile& r : shared_robots()) out.push_back(r);
  return out;
}

/// Every robot id all_robots() can return (shared ones only when ../shared is present), for
/// parameterised tests over robots.
inline const std::vector<std::string>& robot_ids() {
  static const std::vector<std::string> ids = {
      "hullcheck_arm",       "panda",   "ur5e",
      "abb_irb2400",         "baxter",  "mbm_panda",
      "mbm_panda_spherized", "mbm_ur5", "mbm_ur5_spherized"};
  return ids;
}

inline std::optional<RobotFile> find_robot(const std::string& id) {
  for (const RobotFile& r : all_robots()) {
    if (r.id == id) return r;
  }
  return std::nullopt;
}

/// Test names of robot-parameterised tests: the robot id.
inline std::string robot_name_for_test(const testing::TestParamInfo<std::string>& info) {
  return info.param;
}

/// A file's whole content (fails the test when it cannot be read).
inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Uniform in the limits of `variables` (continuous joints in [-pi, pi]); the other values
/// from `base`.
inline Eigen::VectorXd random_configuration(const RobotModel& model, const Eigen::VectorXd& base,
                                            const std::vector<int>& variables,
                                            std::mt19937_64& rng) {
  const Eigen::VectorXd lo = model.lower_limits();
  const Eigen::VectorXd hi = model.upper_limits();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::VectorXd q = base;
  for (int i : variables) {
    const double a = std::isfinite(lo[i]) ? lo[i] : -M_PI;
    const double b = std::isfinite(hi[i]) ? hi[i] : M_PI;
    q[i] = a + (b - a) * unit(rng);
  }
  return q;
}

/// Every configuration value's index.
inline std::vector<int> all_variables(const RobotModel& model) {
  std::vector<int> v(static_cast<std::size_t>(model.variable_count()));
  for (int i = 0; i < model.variable_count(); ++i) v[static_cast<std::size_t>(i)] = i;
  return v;
}

/// Uniform in the joint limits (continuous joints in [-pi, pi]), every value drawn.
inline Eigen::VectorXd random_configuration(const RobotModel& model, std::mt19937_64& rng) {
  return random_configuration(model, Eigen::VectorXd::Zero(model.variable_count()),
                              all_variables(model), rng);
}

}  // namespace hullcheck::test

/// In a robot-parameterised test: the RobotFile named by GetParam() as `var`, or a skip when
/// that robot is absent (no ../shared).
#define HULLCHECK_GET_ROBOT_OR_SKIP(var)                                                \
  const std::optional<::hullcheck::test::RobotFile> var##_opt =                         \
      ::hullcheck::test::find_robot(GetParam());                                        \
  if (!var##_opt) GTEST_SKIP() << "robot '" << GetParam() << "' absent (no ../shared)"; \
  const ::hullcheck::test::RobotFile& var = *var##_opt
