// `hullcheck validate`: check a path's waypoints and motions, with a clearance profile.
#pragma once

#include <CLI/CLI.hpp>

namespace hullcheck::cli {

/// Registers the subcommand on `app`; it runs when parsed.
void add_validate_command(CLI::App& app);

}  // namespace hullcheck::cli
