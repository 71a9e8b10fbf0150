// Shared pieces of the libFuzzer targets: the fixed robot, per-process temp files, and the
// rule for which exceptions count as the expected answer to bad input.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <string>

namespace hullcheck::fuzz {

/// The project's own arm (robots/hullcheck_arm), where the URDF seeds' meshes resolve.
inline std::string arm_dir() { return HULLCHECK_FUZZ_ARM_DIR; }

/// Load options that resolve package://hullcheck_arm/ without ROS_PACKAGE_PATH.
inline RobotLoadOptions arm_options() {
  RobotLoadOptions options;
  options.packages["hullcheck_arm"] = arm_dir();
  // One hull per mesh: a fuzzed URDF's mesh scales would each start a decomposition (about a
  // second) and a cache entry; decomposition is fuzzed on its own in fuzz_mesh.
  options.mesh_geometry = MeshGeometry::kHull;
  options.use_decomposition_cache = false;
  return options;
}

/// The fixed robot the SRDF, scene, request and path targets read their input against; loaded
/// once per process (not part of what is fuzzed).
inline const RobotModel& arm() {
  static const RobotModel model =
      RobotModel::from_urdf_file(arm_dir() + "/urdf/hullcheck_arm.urdf", arm_options());
  return model;
}

/// The fuzz input as a string (may hold NUL bytes).
inline std::string as_string(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// A per-process file name in $TMPDIR (else /tmp) ending in `extension`, for readers that
/// only take paths. The same name is reused on every run of the process.
inline std::string temp_path(const std::string& extension) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir != nullptr && *dir != '\0' ? dir : "/tmp") + "/hullcheck_fuzz_" +
         std::to_string(::getpid()) + extension;
}

/// Writes `bytes` to `path` (truncating); aborts when that fails, since the run then tests
/// nothing.
inline void write_file(const std::string& path, const std::uint8_t* bytes, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

/// Runs `body`; hullcheck's documented answer to bad input (InputError) is the expected
/// outcome. Any other exception escapes to libFuzzer, which reports it as a finding.
template <typename Body>
void expect_input_errors_only(Body&& body) {
  try {
    body();
  } catch (const InputError&) {
  }
}

}  // namespace hullcheck::fuzz
