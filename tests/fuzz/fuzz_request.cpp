// libFuzzer target: MoveIt MotionPlanRequest YAML -> MotionPlanRequest for the own arm.
#include <hullcheck/scene/motion_plan_request.hpp>

#include "fuzz_support.hpp"

// One input: a request YAML document.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hullcheck;
  const RobotModel& model = fuzz::arm();
  fuzz::expect_input_errors_only(
      [&] { parse_motion_plan_request(fuzz::as_string(data, size), model, "<fuzz>"); });
  return 0;
}
