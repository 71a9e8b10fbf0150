// Robots the tests load: the project's own (always present) and the shared test data (tests
// skip those cleanly when ../shared is absent).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace hullcheck::test {

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

}  // namespace hullcheck::test
