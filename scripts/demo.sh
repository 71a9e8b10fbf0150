#!/usr/bin/env bash
# The main job: install what is missing, build (Release) and run the demo.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DHULLCHECK_BUILD_TESTS=OFF >/dev/null
cmake --build build/release -j"$(nproc)" --target hullcheck_shapes_demo
./build/release/planners/hullcheck_shapes_demo "$@"
