#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/length_checks.hpp>
#include <sstream>

namespace hullcheck {

void check_length(double value, const std::string& what) {
  if (std::isfinite(value) && std::abs(value) <= kMaxLoadedLength) return;
  std::ostringstream msg;
  msg << what << ": must be finite and at most " << kMaxLoadedLength << " m in magnitude (got "
      << value << ")";
  throw InputError(msg.str());
}

void check_joint_value(double value, const std::string& what, const char* unit) {
  if (std::isfinite(value) && std::abs(value) <= kMaxJointValue) return;
  std::ostringstream msg;
  msg << what << ": must be finite and at most " << kMaxJointValue << (*unit != '\0' ? " " : "")
      << unit << " in magnitude (got " << value << ")";
  throw InputError(msg.str());
}

void check_lengths(const Eigen::Vector3d& v, const std::string& what) {
  static const char* const kAxis[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) check_length(v[i], what + " " + kAxis[i]);
}

}  // namespace hullcheck
