// Exceptions thrown by hullcheck for bad input.
#pragma once

#include <stdexcept>
#include <string>

namespace hullcheck {

/// Thrown when an argument is unusable: a NaN or infinite coordinate, an empty point set, a
/// negative radius, a non-rigid pose. The message names the argument and the problem.
/// Queries never return a silent wrong answer for such input: they throw this instead.
class InputError : public std::invalid_argument {
 public:
  explicit InputError(const std::string& what) : std::invalid_argument(what) {}
};

}  // namespace hullcheck
