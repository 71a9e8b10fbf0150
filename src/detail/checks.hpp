// Input validation helpers shared by the sources (not installed).
#pragma once

#include <cmath>
#include <hullcheck/errors.hpp>
#include <string>

namespace hullcheck::detail {

/// Throws InputError "<what> must be finite and >= 0 (got <value>)" unless value is.
inline void require_non_negative(double value, const char* what) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw InputError(std::string(what) + " must be finite and >= 0 (got " + std::to_string(value) +
                     ")");
  }
}

}  // namespace hullcheck::detail
