// Exit codes of the hullcheck program, and an exception that carries one.
#pragma once

namespace hullcheck::cli {

constexpr int kExitOk = 0;
constexpr int kExitError = 1;           ///< Bad input (message on stderr).
constexpr int kExitInvalidProblem = 2;  ///< plan: start or goal in collision; validate: invalid
                                        ///< path.
constexpr int kExitNotSolved = 3;       ///< plan: no exact solution within the time limit.

/// Thrown by a subcommand that finished its report and wants a non-zero exit status.
struct ExitWith {
  int code;
};

}  // namespace hullcheck::cli
