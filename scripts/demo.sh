#!/usr/bin/env bash
# The main job: install what is missing, build (Release) and run the demo: proximity queries on
# every kind of shape, then the project's own robot inspected at its "ready" pose (link poses,
# self-collision verdict and closest link pair).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DHULLCHECK_BUILD_TESTS=OFF >/dev/null
cmake --build build/release -j"$(nproc)" --target hullcheck_shapes_demo hullcheck_cli
./build/release/planners/hullcheck_shapes_demo "$@"
echo
echo "== hullcheck inspect: robots/hullcheck_arm at its 'ready' pose"
./build/release/planners/hullcheck inspect --robot robots/hullcheck_arm/urdf/hullcheck_arm.urdf \
  --srdf robots/hullcheck_arm/srdf/hullcheck_arm.srdf --state 0,0.3,0,-1.6,0,1.2416,0,0.02
