// `hullcheck decompose`: decomposes a robot's collision meshes into convex pieces ahead of time
// (filling the cache) and can write a URDF whose links use the pieces as separate meshes.
#pragma once

#include <CLI/CLI.hpp>

namespace hullcheck::cli {

/// Registers the subcommand on `app`; it runs when parsed.
void add_decompose_command(CLI::App& app);

}  // namespace hullcheck::cli
