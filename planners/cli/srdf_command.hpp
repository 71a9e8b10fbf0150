// `hullcheck srdf`: generates a robot's allowed-collision matrix and writes it as an SRDF.
#pragma once

#include <CLI/CLI.hpp>

namespace hullcheck::cli {

/// Registers the subcommand on `app`; it runs when parsed.
void add_srdf_command(CLI::App& app);

}  // namespace hullcheck::cli
