// The benchmark programs' command lines: their own flags, the ../shared directory, and Google
// Benchmark's flags with the programs' defaults filled in.
#pragma once

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#ifndef HULLCHECK_SHARED_DIR
#define HULLCHECK_SHARED_DIR "../shared"
#endif

namespace hullcheck::bench {

/// The test-data directory: $HULLCHECK_SHARED_DIR when set and not empty, else the build's
/// default (HULLCHECK_SHARED_DIR).
inline std::string shared_dir() {
  const char* env = std::getenv("HULLCHECK_SHARED_DIR");
  return env != nullptr && *env != '\0' ? env : HULLCHECK_SHARED_DIR;
}

/// Takes a program's own flags out of argv, leaving the others (Google Benchmark's) in order
/// for initialize_benchmark. `take(arg)` returns true when it consumed `arg`; --help or -h
/// prints `usage` and the shared-directory default, then exits.
template <class Take>
void take_program_flags(int& argc, char** argv, const std::string& usage, Take take) {
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << usage << " (default " << HULLCHECK_SHARED_DIR << ")\n";
      std::exit(0);
    }
    if (!take(arg)) argv[kept++] = argv[i];
  }
  argc = kept;
}

/// Initializes Google Benchmark from argc/argv, adding --benchmark_min_time (quick_min_time s
/// in quick mode, else 0.2 s) and, unless quick, --benchmark_repetitions=full_repetitions where
/// the caller gave none. Returns false when an argument is not recognised (after reporting it).
inline bool initialize_benchmark(int argc, char** argv, bool quick, double quick_min_time,
                                 int full_repetitions) {
  static std::vector<std::string> added;  // the argv entries must outlive the run
  bool has_min_time = false, has_repetitions = false;
  for (int i = 1; i < argc; ++i) {
    has_min_time |= std::strncmp(argv[i], "--benchmark_min_time", 20) == 0;
    has_repetitions |= std::strncmp(argv[i], "--benchmark_repetitions", 23) == 0;
  }
  if (!has_min_time) {
    added.push_back("--benchmark_min_time=" + std::to_string(quick ? quick_min_time : 0.2));
  }
  if (!quick && !has_repetitions) {
    added.push_back("--benchmark_repetitions=" + std::to_string(full_repetitions));
  }
  static std::vector<char*> args;
  args.assign(argv, argv + argc);
  for (std::string& a : added) args.push_back(a.data());
  int bench_argc = static_cast<int>(args.size());
  benchmark::Initialize(&bench_argc, args.data());
  return !benchmark::ReportUnrecognizedArguments(bench_argc, args.data());
}

}  // namespace hullcheck::bench
