// `hullcheck plan`: plan one problem with any OMPL geometric planner.
#pragma once

#include <CLI/CLI.hpp>

namespace hullcheck::cli {

/// Registers the subcommand on `app`; it runs when parsed.
void add_plan_command(CLI::App& app);

}  // namespace hullcheck::cli
