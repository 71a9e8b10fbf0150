// libFuzzer target: SRDF text -> Srdf, then applied to the own arm: allowed collision matrix,
// every group's variables and every group state's configuration.
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/planning_group.hpp>
#include <hullcheck/robot/srdf.hpp>
#include <string>
#include <vector>

#include "fuzz_support.hpp"

// One input: an SRDF document for the own arm.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hullcheck;
  const RobotModel& model = fuzz::arm();
  Srdf srdf;
  fuzz::expect_input_errors_only([&] { srdf = parse_srdf(fuzz::as_string(data, size), "<fuzz>"); });
  std::vector<std::string> warnings;
  AllowedCollisionMatrix::from_srdf(model, srdf, &warnings);
  for (const SrdfGroup& group : srdf.groups) {
    fuzz::expect_input_errors_only([&] { group_variables(model, srdf, group.name); });
  }
  for (const SrdfGroupState& state : srdf.group_states) {
    fuzz::expect_input_errors_only([&] {
      group_state_configuration(model, srdf, state.group, state.name,
                                model.default_configuration());
    });
  }
  // The writer's output must read back.
  parse_srdf(write_srdf(srdf), "<fuzz round trip>");
  return 0;
}
