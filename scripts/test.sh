#!/usr/bin/env bash
# The whole test suite: install what is missing, then
#  1. formatting check (clang-format) of the project's sources,
#  2. Release build with warnings as errors: GoogleTest suites, benchmark smoke runs and the
#     Python package's pytest suites (ctest),
#  3. the same tests built with AddressSanitizer + UndefinedBehaviorSanitizer,
#  4. multi-threaded planning (OmplThreads.*) built with ThreadSanitizer,
#  5. install into a temporary prefix and build two consumers with find_package(hullcheck):
#     one of every layer, one of hullcheck::core alone (no OMPL on its include path); install
#     the Python package into the interpreter's site-packages and import it from elsewhere,
#  6. the libFuzzer targets of the readers (clang, ASan + UBSan): every regression input
#     replayed, then a few seconds of fuzzing each (scripts/fuzz.sh; long runs: see README),
#  7. when ../shared/ompl is present: the library, CLI, OMPL-layer tests and Python planning
#     tests built and run against OMPL 2.0.2 (scripts/ompl2.sh; OMPL built once per machine).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs="$(nproc)"
# ccache when present (scripts/compiler_cache.sh).
source scripts/compiler_cache.sh
stage_start=$SECONDS
# Prints how long the previous stage took (CI budget: the whole script in 15 minutes on 2 cores).
stage() {
  echo "   ($((SECONDS - stage_start)) s)"
  stage_start=$SECONDS
  echo "== $1"
}

# Prints how long the current stage has run so far (its build, before its tests).
lap() {
  echo "   ($1 after $((SECONDS - stage_start)) s)"
}

stage "clang-format"
git ls-files '*.hpp' '*.cpp' | xargs clang-format --dry-run --Werror

stage "Release build and tests"
cmake -S . -B build/ci-release -DCMAKE_BUILD_TYPE=Release -DHULLCHECK_BUILD_BENCHMARKS=ON \
  "${launcher[@]}" >/dev/null
cmake --build build/ci-release -j"$jobs"
lap "built"
(cd build/ci-release && ctest --output-on-failure -j"$jobs")

stage "AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
# -O1 -g1 (ASan's recommended optimisation, line tables only): about 3x faster to compile than
# RelWithDebInfo's -O2 -g, with the same findings and file:line in every report.
sanitizer_flags="-O1 -g1 -DNDEBUG"
cmake -S . -B build/ci-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$sanitizer_flags" -DHULLCHECK_SANITIZE=ON \
  -DHULLCHECK_BUILD_PYTHON=OFF "${launcher[@]}" >/dev/null
cmake --build build/ci-sanitize -j"$jobs" --target hullcheck_tests
lap "built"
# The program's end-to-end test (`cli`) runs in the Release stage only: this stage builds the
# test binaries, not the program.
(cd build/ci-sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --output-on-failure -j"$jobs" -E '^cli$')

stage "ThreadSanitizer build and multi-threaded planning tests"
# OMPL's parallel planners (ParallelPlan of PRMs and RRTConnects) and plain threads sharing one
# checker, validity checker and motion validator. libompl itself is not instrumented (its
# internal accesses are invisible to TSan); no suppressions are needed.
cmake -S . -B build/ci-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$sanitizer_flags" -DCMAKE_CXX_FLAGS=-fsanitize=thread \
  -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread -DHULLCHECK_BUILD_BENCHMARKS=OFF \
  -DHULLCHECK_BUILD_PYTHON=OFF "${launcher[@]}" >/dev/null
cmake --build build/ci-tsan -j"$jobs" --target hullcheck_thread_tests
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
  build/ci-tsan/tests/hullcheck_thread_tests --gtest_filter='OmplThreads.*'

stage "Install: find_package(hullcheck) from consumers, import hullcheck in Python"
prefix="$(mktemp -d)"
cmake --install build/ci-release --prefix "$prefix" >/dev/null
cmake -S tests/install_consumer -B build/ci-consumer -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build build/ci-consumer -j"$jobs"
./build/ci-consumer/hullcheck_consumer
# hullcheck::core alone: no OMPL (nor loader) packages looked for, no OMPL header reachable.
cmake -S tests/install_consumer/core_only -B build/ci-core-consumer -DCMAKE_PREFIX_PATH="$prefix" \
  >/dev/null
cmake --build build/ci-core-consumer -j"$jobs"
./build/ci-core-consumer/hullcheck_core_consumer
rm -rf "$prefix"
# The Python package into the interpreter's site-packages (the README's commands do the same),
# then imported from outside the repository.
cmake --install build/ci-release --component python
python="$(sed -n 's/^Python_EXECUTABLE:FILEPATH=//p' build/ci-release/CMakeCache.txt)"
(cd / && "$python" -c "import hullcheck, sys; print('import hullcheck:', hullcheck.__file__)")

stage "libFuzzer targets: regressions replayed, then 5 s of fuzzing each"
# Its own build folder at -O0 (three times faster to compile than the long runs' -O1 -g1).
FUZZ_BUILD_DIR=build/ci-fuzz FUZZ_CXX_FLAGS=-O0 scripts/fuzz.sh --seconds 5

stage "OMPL 2.0.2: library, CLI, OMPL-layer and Python planning tests"
scripts/ompl2.sh
stage "all checks passed in $SECONDS s"
