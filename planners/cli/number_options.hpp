// Validators for numeric command-line options: finite values within a range, so that a NaN,
// an infinity or a negative time limit is a usage error (exit 1), never a silent result.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace hullcheck::cli {

/// Accepts a finite number x with low <= x <= high (or low < x when `open_low`); otherwise
/// CLI11 reports "--option: must be a finite number in [low, high] (got 'text')".
CLI::Validator finite_in(double low, double high, bool open_low = false);

/// Accepts an integer n with low <= n <= high.
CLI::Validator integer_in(long long low, long long high);

/// Accepts a non-negative integer that fits 64 bits (digits only: "-1" would wrap silently).
CLI::Validator unsigned_64();

}  // namespace hullcheck::cli
