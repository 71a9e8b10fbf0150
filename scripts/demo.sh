#!/usr/bin/env bash
# The main job: install what is missing, build (Release) and run the planning demo on the
# project's own robot and scene (robots/hullcheck_arm, scene shelf.yaml): move the tool from the
# shelf's lower compartment (group state "shelf_low") to its upper one ("shelf_high") -- out of
# one compartment, past the middle board and into the other, a search -- with RRTConnect and
# guaranteed motion checks, simplify the path, optimize it for clearance (obstacles and the self
# pairs the arm moves, a 5 cm margin; every motion certified), then validate it again.
# Outputs: build/demo/path.csv (the optimized path), build/demo/clearance.svg (clearance
# profiles per scope, before and after the optimizer) and build/demo/path.html (both paths
# animated in 3D). Extra arguments go to `hullcheck plan` (e.g. --margin 0.08).
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
  --scene "$arm/scenes/shelf.yaml")
mkdir -p build/demo
echo "== hullcheck plan: hullcheck_arm, scene shelf, group arm, shelf_low -> shelf_high"
./build/release/planners/hullcheck plan "${world[@]}" --group arm --start shelf_low \
  --goal shelf_high --simplify --optimize clearance --margin 0.05 --time 10 \
  --out build/demo/path.csv --plot build/demo/clearance.svg --viewer build/demo/path.html "$@"
echo
echo "== hullcheck validate: every waypoint and every motion of the optimized path"
./build/release/planners/hullcheck validate "${world[@]}" --path build/demo/path.csv |
  grep -v -e '^ *[0-9]* *valid ' -e '^ *# *state'
echo
echo "path: build/demo/path.csv   clearance before/after: build/demo/clearance.svg   3D: build/demo/path.html"
