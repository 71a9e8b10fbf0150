#!/usr/bin/env bash
# Builds and tests hullcheck against OMPL 2.0.2 (Debian ships 1.5.2, which scripts/test.sh uses).
#  1. OMPL 2.0.2 from ../shared/ompl/ompl-2.0.2.tar.gz, built once per machine into a cache
#     outside the clone (HULLCHECK_OMPL2_CACHE, default ~/.cache/hullcheck/ompl-2.0.2): later runs
#     find the installed prefix and skip this step;
#  2. hullcheck (library, OMPL-layer tests, CLI, planning example, Python package; no
#     benchmarks) in build/ci-ompl2 against that OMPL, then the OMPL-layer GoogleTest suite, the
#     planning example, the CLI test (with OMPL 2's ompl_benchmark_statistics reading the
#     benchmark logs), the Python planning tests, and a consumer of the installed package.
# Skips cleanly (exit 0, a message) when ../shared/ompl is absent.
# Usage: scripts/ompl2.sh [--build-only]   (--build-only: step 1 alone)
set -euo pipefail
cd "$(dirname "$0")/.."
tarball="../shared/ompl/ompl-2.0.2.tar.gz"
if [ ! -f "$tarball" ]; then
  echo "ompl2.sh: $tarball not found: the OMPL 2.0.2 stage is skipped"
  exit 0
fi
cache="${HULLCHECK_OMPL2_CACHE:-$HOME/.cache/hullcheck/ompl-2.0.2}"
prefix="$cache/prefix"
jobs="$(nproc)"
if [ ! -f "$prefix/.hullcheck-built" ]; then
  echo "ompl2.sh: building OMPL 2.0.2 into $cache (once per machine)"
  rm -rf "$cache/src" "$cache/build" "$prefix"
  mkdir -p "$cache/src"
  tar xzf "$tarball" -C "$cache/src"
  # Only the library: no VAMP or nanobind (their submodules are not in the archive), no Python,
  # tests or demos.
  cmake -S "$cache/src/ompl-2.0.2" -B "$cache/build" -DCMAKE_BUILD_TYPE=Release \
    -DOMPL_BUILD_VAMP=OFF -DOMPL_BUILD_PYTHON_BINDINGS=OFF -DOMPL_BUILD_TESTS=OFF \
    -DOMPL_BUILD_DEMOS=OFF -DCMAKE_INSTALL_PREFIX="$prefix" >/dev/null
  cmake --build "$cache/build" -j"$jobs"
  cmake --install "$cache/build" >/dev/null
  touch "$prefix/.hullcheck-built"
  rm -rf "$cache/build" "$cache/src"
fi
# The CLI test reads benchmark logs with ompl_benchmark_statistics (Debian's name for it). OMPL
# 2 installs it as ompl_benchmark_statistics.py, which reads logs with its Python package's
# ompl.tools: pure Python, taken from the archive (the compiled bindings are not built here).
ln -sf ompl_benchmark_statistics.py "$prefix/bin/ompl_benchmark_statistics"
if [ ! -f "$prefix/python/ompl/tools.py" ]; then
  mkdir -p "$prefix/python"
  tar xzf "$tarball" -C "$prefix/python" --strip-components=2 ompl-2.0.2/py-bindings/ompl
fi
echo "ompl2.sh: OMPL 2.0.2 at $prefix"
[ "${1:-}" = "--build-only" ] && exit 0

ompl_config="$(dirname "$(find "$prefix" -name omplConfig.cmake -print -quit)")"
build=build/ci-ompl2
# ccache when present: the layers below OMPL compile as in the test script's Release build.
source scripts/compiler_cache.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -Dompl_DIR="$ompl_config" \
  -DHULLCHECK_BUILD_BENCHMARKS=OFF "${launcher[@]}" >"$build.configure.log"
# Built against OMPL 2.0.2, not the system's 1.5.2.
grep "hullcheck: OMPL 2.0.2 from $ompl_config" "$build.configure.log"
cmake --build "$build" -j"$jobs" --target hullcheck_ompl_tests hullcheck_cli \
  hullcheck_plan_example hullcheck_python hullcheck_python_reference
"$build/tests/hullcheck_ompl_tests" --gtest_brief=1
arm=robots/hullcheck_arm
"$build/planners/hullcheck_plan_example" "$arm/urdf/hullcheck_arm.urdf" \
  "$arm/srdf/hullcheck_arm.srdf" arm "$arm/scenes/table_wall.yaml" left right 10
PATH="$prefix/bin:$PATH" PYTHONPATH="$prefix/python" bash tests/cli/test_cli.sh "$build/planners/hullcheck" "$PWD"
python="$(sed -n 's/^Python_EXECUTABLE:FILEPATH=//p' "$build/CMakeCache.txt")"
PYTHONPATH="$build/python" HULLCHECK_PYTHON_REFERENCE="$build/tests/hullcheck_python_reference" \
  "$python" -m pytest -q -p no:cacheprovider tests/python/test_planning.py \
  tests/python/test_examples.py
# Installed, hullcheck's package config finds the OMPL it was built with (here ompl::ompl of
# 2.0.2, not the system's 1.5.2) for a consumer of every layer.
install_prefix="$(mktemp -d)"
cmake --install "$build" --prefix "$install_prefix" >/dev/null
cmake -S tests/install_consumer -B "$build-consumer" -DCMAKE_PREFIX_PATH="$install_prefix" \
  >/dev/null
cmake --build "$build-consumer" -j"$jobs"
"$build-consumer/hullcheck_consumer"
rm -rf "$install_prefix"
echo "ompl2.sh: hullcheck against OMPL 2.0.2 passed"
