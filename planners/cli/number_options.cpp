#include "number_options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace hullcheck::cli {
namespace {

std::string range_text(double low, double high, bool open_low) {
  std::ostringstream out;
  out << (open_low ? "(" : "[") << low << ", " << high << "]";
  return out.str();
}

}  // namespace

CLI::Validator finite_in(double low, double high, bool open_low) {
  const std::string range = range_text(low, high, open_low);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        const bool parsed = !text.empty() && end != nullptr && *end == '\0';
        const bool inside = open_low ? x > low : x >= low;
        if (parsed && std::isfinite(x) && inside && x <= high) return "";
        return "must be a finite number in " + range + " (got '" + text + "')";
      },
      "NUMBER in " + range);
}

CLI::Validator integer_in(long long low, long long high) {
  const std::string range = "[" + std::to_string(low) + ", " + std::to_string(high) + "]";
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const long long n = std::strtoll(text.c_str(), &end, 10);
        const bool parsed = !text.empty() && end != nullptr && *end == '\0' && errno == 0;
        if (parsed && n >= low && n <= high) return "";
        return "must be an integer in " + range + " (got '" + text + "')";
      },
      "INT in " + range);
}

CLI::Validator unsigned_64() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const bool digits =
            !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        if (digits) std::strtoull(text.c_str(), &end, 10);
        if (digits && errno == 0) return "";
        return "must be an integer in [0, 18446744073709551615] (got '" + text + "')";
      },
      "UINT64");
}

}  // namespace hullcheck::cli
