// `hullcheck inspect`: a robot's joints, links and shapes; with --state, link poses and the
// self-collision verdict.
#pragma once

#include <CLI/CLI.hpp>

namespace hullcheck::cli {

/// Registers the subcommand on `app`; it runs when parsed.
void add_inspect_command(CLI::App& app);

}  // namespace hullcheck::cli
