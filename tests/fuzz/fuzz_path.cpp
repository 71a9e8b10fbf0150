// libFuzzer target: the CLI's path file reader (planners/cli/path_file.cpp), fed every input
// both as CSV and as JSON (it picks the format by extension), then the joint names looked up in
// the own arm as `hullcheck validate --path` does.
#include <path_file.hpp>
#include <string>

#include "fuzz_support.hpp"

namespace {

// Reads `file` and resolves its joint names against the arm.
void read_one(const std::string& file) {
  const hullcheck::RobotModel& model = hullcheck::fuzz::arm();
  hullcheck::fuzz::expect_input_errors_only([&] {
    const hullcheck::cli::JointPath path = hullcheck::cli::read_joint_path(file);
    for (const std::string& name : path.joint_names) model.variable_index(name);
  });
}

}  // namespace

// One input: a path file's bytes.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hullcheck;
  static const std::string csv = fuzz::temp_path(".csv");
  static const std::string json = fuzz::temp_path(".json");
  fuzz::write_file(csv, data, size);
  read_one(csv);
  fuzz::write_file(json, data, size);
  read_one(json);
  return 0;
}
