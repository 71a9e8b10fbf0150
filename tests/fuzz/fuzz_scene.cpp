// libFuzzer target: MoveIt PlanningScene YAML -> PlanningScene for the own arm.
#include <hullcheck/scene/planning_scene.hpp>

#include "fuzz_support.hpp"

// One input: a scene YAML document.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hullcheck;
  const RobotModel& model = fuzz::arm();
  fuzz::expect_input_errors_only(
      [&] { parse_planning_scene(fuzz::as_string(data, size), model, "<fuzz>"); });
  return 0;
}
