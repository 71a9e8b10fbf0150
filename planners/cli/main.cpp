// hullcheck: command-line front end of the library (robot inspection, collision matrices).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "benchmark_command.hpp"
#include "decompose_command.hpp"
#include "exit_codes.hpp"
#include "inspect_command.hpp"
#include "plan_command.hpp"
#include "srdf_command.hpp"
#include "validate_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"hullcheck: exact collision and distance queries for robots"};
  app.require_subcommand(1);
  hullcheck::cli::add_inspect_command(app);
  hullcheck::cli::add_srdf_command(app);
  hullcheck::cli::add_decompose_command(app);
  hullcheck::cli::add_plan_command(app);
  hullcheck::cli::add_validate_command(app);
  hullcheck::cli::add_benchmark_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Help and version exit 0; every usage error (unknown option, a value failing its check)
    // exits kExitError like any other bad input.
    return app.exit(e) == 0 ? hullcheck::cli::kExitOk : hullcheck::cli::kExitError;
  } catch (const hullcheck::cli::ExitWith& e) {
    return e.code;
  } catch (const std::exception& e) {
    std::cerr << "hullcheck: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
