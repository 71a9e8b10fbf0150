// `hullcheck benchmark`: OMPL benchmarks over MotionBenchMaker problems, in OMPL's log format.
#pragma once

#include <CLI/CLI.hpp>

namespace hullcheck::cli {

/// Registers the subcommand on `app`; it runs when parsed.
void add_benchmark_command(CLI::App& app);

}  // namespace hullcheck::cli
