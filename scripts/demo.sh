#!/usr/bin/env bash
# The main job: install what is missing, build (Release) and run the planning demo on the
# project's own robot and scene (robots/hullcheck_arm): plan from the "left" to the "right"
# group state over the wall on the table (RRTConnect, guaranteed motion checks, objective-aware
# simplification), then validate the path and plot its clearance profile.
# Outputs: build/demo/path.csv (the path) and build/demo/clearance.svg (its clearance profile).
# Also builds the Python package and installs it into the interpreter's site-packages (the
# component `python` alone: `import hullcheck` then works from anywhere).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DHULLCHECK_BUILD_TESTS=OFF >/dev/null
cmake --build build/release -j"$(nproc)" --target hullcheck_cli hullcheck_python
cmake --install build/release --component python
python="$(sed -n 's/^Python_EXECUTABLE:FILEPATH=//p' build/release/CMakeCache.txt)"
echo "Python package installed for $python: $python -c 'import hullcheck'"
path_python="$(python3 -c 'import sys; print(sys.executable)' 2>/dev/null || true)"
if [ -n "$path_python" ] && [ "$(realpath "$path_python")" != "$(realpath "$python")" ]; then
  echo "note: python3 on PATH is $path_python, not the interpreter hullcheck was built for (the first python3 with numpy): use $python"
fi
arm=robots/hullcheck_arm
world=(--robot "$arm/urdf/hullcheck_arm.urdf" --srdf "$arm/srdf/hullcheck_arm.srdf"
  --scene "$arm/scenes/table_wall.yaml")
mkdir -p build/demo
echo "== hullcheck plan: hullcheck_arm, scene table_wall, group arm, left -> right"
./build/release/planners/hullcheck plan "${world[@]}" --group arm --start left --goal right \
  --objective length+clearance --simplify --time 10 --out build/demo/path.csv "$@"
echo
echo "== hullcheck validate: every waypoint and every motion of the path"
./build/release/planners/hullcheck validate "${world[@]}" --path build/demo/path.csv \
  --plot build/demo/clearance.svg
echo
echo "path: build/demo/path.csv   clearance profile: build/demo/clearance.svg"
