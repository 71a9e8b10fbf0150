#!/usr/bin/env bash
# End-to-end checks of the `hullcheck` command-line program: outputs, exit codes, errors.
# Usage: test_cli.sh PATH_TO_HULLCHECK REPOSITORY_ROOT   (run by ctest as `cli`)
set -uo pipefail
bin="$1"
root="$2"
arm="$root/robots/hullcheck_arm"
urdf="$arm/urdf/hullcheck_arm.urdf"
srdf="$arm/srdf/hullcheck_arm.srdf"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
failures=0

# expect NAME EXPECTED_EXIT PATTERN_STDOUT PATTERN_STDERR -- COMMAND...   (exact exit status)
expect() {
  local name="$1" want_exit="$2" out_pattern="$3" err_pattern="$4"
  shift 5
  "$@" >"$tmp/out" 2>"$tmp/err"
  local got=$?
  local ok=1
  [ "$got" != "$want_exit" ] && ok=0
  [ -n "$out_pattern" ] && ! grep -Eq -- "$out_pattern" "$tmp/out" && ok=0
  [ -n "$err_pattern" ] && ! grep -Eq -- "$err_pattern" "$tmp/err" && ok=0
  if [ "$ok" = 1 ]; then
    echo "ok   $name"
  else
    echo "FAIL $name (exit $got)"
    cut -c1-300 "$tmp/out" | sed 's/^/  stdout: /' | head -20
    cut -c1-300 "$tmp/err" | sed 's/^/  stderr: /' | head -20
    failures=$((failures + 1))
  fi
}

expect "inspect lists joints and shapes" 0 "8 configuration values" "" -- \
  "$bin" inspect --robot "$urdf"
expect "inspect shows the continuous joint" 0 "joint7 +continuous" "" -- \
  "$bin" inspect --robot "$urdf"
expect "inspect shows the mimic joint" 0 "finger_joint2 +prismatic +mimics finger_joint1" "" -- \
  "$bin" inspect --robot "$urdf"
expect "inspect shows mesh hulls" 0 "hull [0-9]+ vertices \(mesh [0-9]+ vertices, link5_mm.stl\)" "" -- \
  "$bin" inspect --robot "$urdf" --mesh-geometry hull
expect "inspect shows convex pieces" 0 \
  "[0-9]+ convex pieces \(mesh [0-9]+ vertices, link5_mm.stl, within [0-9.]+ mm of it\)" "" -- \
  "$bin" inspect --robot "$urdf" --cache-dir "$tmp/cache"
expect "decompose fills the cache and writes a URDF of pieces" 0 \
  "wrote .*pieces.urdf \([0-9]+ piece meshes" "" -- \
  "$bin" decompose --robot "$urdf" --cache-dir "$tmp/cache" --write-urdf "$tmp/pieces.urdf"
expect "decompose lists the pieces per link" 0 "link5 +link5_mm.stl +[0-9]+ pieces +within" "" -- \
  "$bin" decompose --robot "$urdf" --cache-dir "$tmp/cache"
expect "the URDF of pieces loads, one hull per piece" 0 "hull [0-9]+ vertices \(mesh [0-9]+ vertices, link5_0_piece1.stl\)" "" -- \
  "$bin" inspect --robot "$tmp/pieces.urdf" --mesh-geometry hull --package "hullcheck_arm=$arm"
expect "decompose: bad tolerance" 1 "" "tolerance" -- \
  "$bin" decompose --robot "$urdf" --tolerance 0
expect "inspect shows links without geometry" 0 "no collision geometry" "" -- \
  "$bin" inspect --robot "$urdf"
expect "inspect --state: free pose" 0 "self-collision .*: free" "" -- \
  "$bin" inspect --robot "$urdf" --srdf "$srdf" --state 0,0.3,0,-1.6,0,1.2416,0,0.02
expect "inspect --state: link poses" 0 "tcp +xyz +0.48726 +-?0.00000 +0.35505" "" -- \
  "$bin" inspect --robot "$urdf" --srdf "$srdf" --state 0,0.3,0,-1.6,0,1.2416,0,0.02
expect "inspect --state: colliding pose" 0 "IN COLLISION" "" -- \
  "$bin" inspect --robot "$urdf" --srdf "$srdf" --state 0,2.0,0,2.0,0,2.0,0,0
expect "inspect --state: colliding pair named" 0 "link1 - link3" "" -- \
  "$bin" inspect --robot "$urdf" --srdf "$srdf" --state 0,2.0,0,2.0,0,2.0,0,0
expect "inspect --padding" 0 "padding 0.01" "" -- \
  "$bin" inspect --robot "$urdf" --padding 0.01
expect "explicit --package" 0 "8 configuration values" "" -- \
  "$bin" inspect --robot "$urdf" --package "hullcheck_arm=$arm"

expect "wrong state length" 1 "" "configuration has 2 values, expected 8" -- \
  "$bin" inspect --robot "$urdf" --state 1,2
expect "non-numeric state" 1 "" "item 1 \('x'\) is not a number" -- \
  "$bin" inspect --robot "$urdf" --state 0,x,0,0,0,0,0,0
expect "NaN state" 1 "" "joint 'joint3'" -- \
  "$bin" inspect --robot "$urdf" --state 0,0,nan,0,0,0,0,0
expect "missing URDF" 1 "" "cannot open file" -- \
  "$bin" inspect --robot "$tmp/none.urdf"
expect "malformed --package" 1 "" "expected NAME=DIR" -- \
  "$bin" inspect --robot "$urdf" --package nonsense
expect "--package with a folder that does not exist" 1 "" \
  "package 'hullcheck_arm' maps to '$tmp/no_such_folder', which is not a folder" -- \
  "$bin" inspect --robot "$urdf" --package "hullcheck_arm=$tmp/no_such_folder"
expect "missing SRDF" 1 "" "SRDF .*cannot open" -- \
  "$bin" inspect --robot "$urdf" --srdf "$tmp/none.srdf" --state 0,0,0,0,0,0,0,0
printf '<robot name="x"><link name="a"></robot>' >"$tmp/bad.urdf"
expect "malformed URDF" 1 "" "malformed XML" -- "$bin" inspect --robot "$tmp/bad.urdf"
expect "no subcommand" 1 "" "" -- "$bin"

expect "srdf writes a collision matrix" 0 'disable_collisions link1="base_link" link2="link1" reason="Adjacent"' \
  "adjacent" -- "$bin" srdf --robot "$urdf" --samples 300
expect "srdf finds Never pairs" 0 'reason="Never"' "" -- "$bin" srdf --robot "$urdf" --samples 300
expect "srdf keeps groups of --srdf" 0 '<group_state name="ready" group="arm">' "" -- \
  "$bin" srdf --robot "$urdf" --srdf "$srdf" --samples 300
expect "srdf rejects zero samples" 1 "" "--samples: must be an integer in \\[1, " -- \
  "$bin" srdf --robot "$urdf" --samples 0

scene="$arm/scenes/table_wall.yaml"
world=(--robot "$urdf" --srdf "$srdf" --scene "$scene")
expect "plan solves left -> right" 0 "solved in" "" -- \
  "$bin" plan "${world[@]}" --group arm --start left --goal right --simplify --out "$tmp/path.csv"
expect "plan wrote a CSV path" 0 "^joint1,joint2,joint3,joint4,joint5,joint6,joint7$" "" -- \
  sed -n 2p "$tmp/path.csv"
expect "the path file holds the gripper at its planned value" 0 "^# held: finger_joint1=0$" "" -- \
  head -1 "$tmp/path.csv"
expect "validate accepts the planned path" 0 "path VALID" "" -- \
  "$bin" validate "${world[@]}" --path "$tmp/path.csv" --plot "$tmp/clearance.svg"
expect "validate wrote an SVG plot" 0 "<svg" "" -- head -1 "$tmp/clearance.svg"
expect "validate reports the minimum obstacle clearance" 0 \
  "^  obstacles +[0-9.]+ m  [a-z0-9_]+ - (table|wall|bottles|lamp)" "" -- \
  "$bin" validate "${world[@]}" --path "$tmp/path.csv"
expect "validate reports the minimum self clearance" 0 "^  self +[0-9.]+ m  link[0-9] - " "" -- \
  "$bin" validate "${world[@]}" --path "$tmp/path.csv"
printf 'name: empty\n' >"$tmp/empty_scene.yaml"
expect "validate in a scene without obstacles: no obstacle pair" 0 "^  obstacles +none checked" \
  "" -- "$bin" validate --robot "$urdf" --srdf "$srdf" --scene "$tmp/empty_scene.yaml" \
  --path "$tmp/path.csv"
# Tick labels are round: evenly spaced by 1, 2 or 5 times a power of ten, printed with the
# decimals of that step (not 0.0201, 0.0167, ...).
expect "the plot's tick labels are round" 0 "^round$" "" -- python3 -c "
import math, re, sys
svg = open(sys.argv[1]).read()
for anchor in ('end', 'middle'):
    labels = re.findall(r'text-anchor=\"' + anchor + r'\">(-?[0-9.]+)</text>', svg)
    values = [float(v) for v in labels]
    steps = {round(b - a, 12) for a, b in zip(values, values[1:])}
    assert len(labels) >= 3 and len(steps) == 1, (anchor, labels)
    step = steps.pop()
    mantissa = step / 10 ** math.floor(math.log10(step) + 1e-9)
    assert min(abs(mantissa - m) for m in (1, 2, 5)) < 1e-9, (anchor, labels)
    decimals = max(0, -math.floor(math.log10(step) + 1e-9))
    assert all(len(v.split('.')[1]) == decimals if '.' in v else decimals == 0 for v in labels), labels
print('round')" "$tmp/clearance.svg"

# Joints the path neither moves nor holds: from --request's start state. The request starts
# the gripper at 0.02 (the scene leaves it at the default, 0): the planned path holds it at 0.02
# and validates with or without the request; a path holding another value contradicts it.
problem=(--robot "$urdf" --srdf "$srdf" --scene "$arm/problems/table_wall/scene0001.yaml")
request="$arm/problems/table_wall/request0001.yaml"
expect "plan --request holds the request's gripper value" 0 "solved in" "" -- \
  "$bin" plan "${problem[@]}" --request "$request" --out "$tmp/request_path.csv"
expect "... written in the path file" 0 "^# held: finger_joint1=0.02$" "" -- \
  head -1 "$tmp/request_path.csv"
expect "validate uses the held value" 0 "path VALID" "" -- \
  "$bin" validate "${problem[@]}" --path "$tmp/request_path.csv"
expect "validate --request agrees with it" 0 "path VALID" "" -- \
  "$bin" validate "${problem[@]}" --request "$request" --path "$tmp/request_path.csv"
sed '1s/.*/# held: finger_joint1=0.01/' "$tmp/request_path.csv" >"$tmp/other_held.csv"
expect "validate --request: a held value the request contradicts" 1 "" \
  "holds 'finger_joint1' at 0.010000, request '.*request0001.yaml' starts it at 0.020000" -- \
  "$bin" validate "${problem[@]}" --request "$request" --path "$tmp/other_held.csv"
tail -n +2 "$tmp/request_path.csv" >"$tmp/group_only.csv"
expect "validate --request fills the joints a path file does not hold" 0 "path VALID" "" -- \
  "$bin" validate "${problem[@]}" --request "$request" --path "$tmp/group_only.csv"
sed '1s/.*/# held: no_such_joint=0/' "$tmp/request_path.csv" >"$tmp/bad_held.csv"
expect "validate: a held joint the robot lacks" 1 "" \
  "held joint 'no_such_joint' is not an active joint of robot 'hullcheck_arm'" -- \
  "$bin" validate "${problem[@]}" --path "$tmp/bad_held.csv"
sed '1s/.*/# held: finger_joint1=open/' "$tmp/request_path.csv" >"$tmp/bad_value.csv"
expect "validate: a held value that is not a number" 1 "" \
  "line 1: held joint 'finger_joint1=open': expected NAME=VALUE" -- \
  "$bin" validate "${problem[@]}" --path "$tmp/bad_value.csv"
sed '1s/.*/# held: joint1=0/' "$tmp/request_path.csv" >"$tmp/held_twice.csv"
expect "validate: a held joint also in the header" 1 "" "held joint 'joint1' is named twice" -- \
  "$bin" validate "${problem[@]}" --path "$tmp/held_twice.csv"
expect "plan --out .json holds the gripper too" 0 '"held": \{"finger_joint1": 0.02' "" -- bash -c \
  "'$bin' plan ${problem[*]} --request '$request' --out '$tmp/request_path.json' >/dev/null &&
   cat '$tmp/request_path.json'"
expect "validate reads the JSON path's held joints" 0 "path VALID" "" -- \
  "$bin" validate "${problem[@]}" --request "$request" --path "$tmp/request_path.json"
expect "plan writes the HTML viewer" 0 "viewer written to" "" -- \
  "$bin" plan "${world[@]}" --group arm --start left --goal right --viewer "$tmp/view.html"
expect "viewer holds the data and three.js" 0 '"frames": \[\[\[' "" -- \
  grep -o '"frames": \[\[\[' "$tmp/view.html"
expect "viewer is self-contained (no remote scripts)" 1 "" "" -- \
  grep -Eo '<(script|link)[^>]+(src|href)=' "$tmp/view.html"
expect "plan writes JSON by extension" 0 "solved" "" -- \
  "$bin" plan "${world[@]}" --group arm --start left --goal right --planner kpiece1 --time 10 \
  --objective clearance --out "$tmp/path.json"
expect "JSON path parses back" 0 "path VALID" "" -- \
  "$bin" validate "${world[@]}" --path "$tmp/path.json"
# The clearance optimizer on the demo problem (the shelf): before/after per scope, a plot with
# both profiles, a viewer with both paths, and a path that validates.
shelf=(--robot "$urdf" --srdf "$srdf" --scene "$arm/scenes/shelf.yaml")
# The group states' values (from the SRDF), straight from one to the other.
expect "the demo problem needs a search: its straight motion hits the shelf" 2 \
  "motion 0 -> 1: INVALID" "" -- "$bin" validate "${shelf[@]}" --path <(
  printf 'joint1,joint2,joint3,joint4,joint5,joint6,joint7\n'
  grep -A7 -E 'name="shelf_(low|high)"' "$srdf" | sed -n 's/.*value="\([^"]*\)".*/\1/p' |
    paste -sd, | awk -F, '{ for (i = 1; i <= 14; ++i) printf "%s%s", $i, (i == 7 || i == 14) ? "\n" : "," }')
expect "plan --optimize clearance reports before -> after per scope" 0 \
  "^  min obstacles clearance [0-9.]+ -> [0-9.]+ m" "" -- \
  "$bin" plan "${shelf[@]}" --group arm --start shelf_low --goal shelf_high --simplify \
  --optimize clearance --margin 0.05 --out "$tmp/optimized.csv" --plot "$tmp/before_after.svg" \
  --viewer "$tmp/both.html"
cp "$tmp/out" "$tmp/optimize_out"
expect "... the optimizer's line names its scope, margin and weight" 0 \
  "optimized for clearance \(scope auto, margin 0.05 m, length weight 0.1\) in [0-9.]+ s: path (replaced|kept)" \
  "" -- cat "$tmp/optimize_out"
for curve in "obstacles before" "obstacles after" "self before" "self after"; do
  expect "the plot has the curve '$curve'" 0 ">$curve<" "" -- grep -o ">$curve<" "$tmp/before_after.svg"
done
expect "the viewer holds both paths" 0 '"before": \[\[\[' "" -- \
  grep -o '"before": \[\[\[' "$tmp/both.html"
expect "the optimized path validates" 0 "path VALID" "" -- \
  "$bin" validate "${shelf[@]}" --path "$tmp/optimized.csv"
expect "plan --clearance-scope obstacles" 0 "scope obstacles" "" -- \
  "$bin" plan "${shelf[@]}" --group arm --start shelf_low --goal shelf_high \
  --optimize clearance --clearance-scope obstacles
expect "plan: unknown --clearance-scope" 1 "" "--clearance-scope" -- \
  "$bin" plan "${shelf[@]}" --group arm --start shelf_low --goal shelf_high \
  --optimize clearance --clearance-scope wrists
expect "plan: --margin 0 is a usage error" 1 "" "--margin" -- \
  "$bin" plan "${shelf[@]}" --group arm --start shelf_low --goal shelf_high \
  --optimize clearance --margin 0
expect "plan: --optimize other than clearance" 1 "" "--optimize" -- \
  "$bin" plan "${shelf[@]}" --group arm --start shelf_low --goal shelf_high --optimize length
printf 'joint1,joint2,joint3,joint4,joint5,joint6,joint7\n0.5,0.5,0,-1.3,0,1,0\n-0.5,0.5,0,-1.3,0,1,0\n' \
  >"$tmp/through_wall.csv"
expect "validate rejects a motion through the wall" 2 "motion 0 -> 1: INVALID" "" -- \
  "$bin" validate "${world[@]}" --path "$tmp/through_wall.csv"
expect "plan reports a colliding start with its pair" 2 "start state is in collision: [a-z0-9_]+ - [a-z0-9_/]+ \\(signed distance -" "" -- \
  "$bin" plan "${world[@]}" --group arm --start 0,2.0,0,2.0,0,2.0,0 --goal right
expect "plan: unknown planner" 1 "" "unknown planner 'NoSuch'" -- \
  "$bin" plan "${world[@]}" --group arm --start left --goal right --planner NoSuch
expect "plan: unknown group" 1 "" "no planning group 'legs'" -- \
  "$bin" plan "${world[@]}" --group legs --start left --goal right
expect "plan: wrong goal length" 1 "" "2 values given, the group has 7 joints" -- \
  "$bin" plan "${world[@]}" --group arm --start left --goal 1,2
expect "plan: missing scene" 1 "" "scene .*cannot open" -- \
  "$bin" plan --robot "$urdf" --srdf "$srdf" --scene "$tmp/none.yaml" --group arm --start left --goal right
printf 'joint1,nosuch\n0,0\n' >"$tmp/bad_path.csv"
expect "validate: unknown joint in path" 1 "" "'nosuch' is not an active joint" -- \
  "$bin" validate "${world[@]}" --path "$tmp/bad_path.csv"
printf 'joint1,joint2\n0,abc\n' >"$tmp/bad_value.csv"
expect "validate: bad number in path" 1 "" "line 2, joint 'joint2': 'abc' is not a finite number" -- \
  "$bin" validate "${world[@]}" --path "$tmp/bad_value.csv"

# ---- Adversarial input ("Truthful under attack"): exit 1 fast with one clear message ----
# once NAME PATTERN: the last command's stderr holds PATTERN exactly once.
once() {
  local n
  n=$(grep -oE -- "$2" "$tmp/err" | wc -l)
  if [ "$n" = 1 ]; then
    echo "ok   $1"
  else
    echo "FAIL $1 ('$2' found $n times)"
    cut -c1-300 "$tmp/err" | sed 's/^/  stderr: /' | head -5
    failures=$((failures + 1))
  fi
}
for bad in nan -1 0 inf abc; do
  expect "plan --time $bad is a usage error" 1 "" "--time: must be a finite number in \\(0, " -- \
    "$bin" plan "${world[@]}" --group arm --start left --goal right --time "$bad"
done
expect "benchmark --runs 0 is a usage error" 1 "" "--runs: must be an integer" -- \
  "$bin" benchmark --robot "$urdf" --problems "$arm/problems" --log "$tmp/x.log" --runs 0
expect "benchmark --time nan is a usage error" 1 "" "--time: must be a finite number" -- \
  "$bin" benchmark --robot "$urdf" --problems "$arm/problems" --log "$tmp/x.log" --time nan
expect "benchmark --jobs -2 is a usage error" 1 "" "--jobs: must be an integer" -- \
  "$bin" benchmark --robot "$urdf" --problems "$arm/problems" --log "$tmp/x.log" --jobs -2
expect "benchmark --memory -5 is a usage error" 1 "" "--memory: must be a finite number" -- \
  "$bin" benchmark --robot "$urdf" --problems "$arm/problems" --log "$tmp/x.log" --memory -5
expect "srdf --always-fraction nan is a usage error" 1 "" "--always-fraction: must be a finite" -- \
  "$bin" srdf --robot "$urdf" --always-fraction nan
expect "srdf --seed -1 is a usage error" 1 "" "--seed: must be an integer in \\[0, " -- \
  "$bin" srdf --robot "$urdf" --seed -1 --samples 1
expect "--padding nan is a usage error" 1 "" "--padding: must be a finite number" -- \
  "$bin" inspect --robot "$urdf" --padding nan
printf 'joint1,joint2,joint3,joint4,joint5,joint6,joint7\n0,0,0,-1.3,0,1,0\n1e308,0,0,-1.3,0,1,0\n' \
  >"$tmp/huge.csv"
start_s=$(date +%s)
expect "validate: a joint value of 1e308 is rejected before motion checks" 1 "" \
  "path '.*huge.csv': waypoint 1: robot '[a-z_]+': joint 'joint1' .*is 1e\\+308, outside its limits" -- \
  "$bin" validate "${world[@]}" --path "$tmp/huge.csv"
elapsed=$(($(date +%s) - start_s))
if [ "$elapsed" -le 5 ]; then echo "ok   ... and fast (${elapsed} s)"; else
  echo "FAIL validate 1e308 took ${elapsed} s"; failures=$((failures + 1)); fi
printf '{"joint_names": ["joint1", "joint2"], "waypoints": [[0, 0], [0, .nan]]}\n' >"$tmp/nan.json"
expect "validate: NaN in a JSON path names waypoint and joint" 1 "" \
  "path '.*nan.json': waypoint 1, joint 'joint2': '.nan' is not a finite number" -- \
  "$bin" validate "${world[@]}" --path "$tmp/nan.json"
printf '{"joint_names": ["joint1", "joint2"], "waypoints": [[0, 0], [0, NaN]]}\n' >"$tmp/nan2.json"
expect "validate: bare NaN in a JSON path is rejected" 1 "" "path '.*nan2.json'" -- \
  "$bin" validate "${world[@]}" --path "$tmp/nan2.json"
printf 'joint1,joint2,joint1\n0,0,0\n' >"$tmp/dup.csv"
expect "validate: a duplicated joint column names the file and the joint" 1 "" \
  "path '.*dup.csv': joint 'joint1' is named twice in the header" -- \
  "$bin" validate "${world[@]}" --path "$tmp/dup.csv"
once "... once" "named twice"
printf '<robot name="huge"><link name="base"><collision><geometry><box size="1e300 1 1"/></geometry></collision></link><link name="arm"><collision><geometry><sphere radius="0.1"/></geometry></collision></link><joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint></robot>\n' \
  >"$tmp/huge_box.urdf"
expect "inspect: a 1e300 m box names the URDF, link and element" 1 "" \
  "URDF '.*huge_box.urdf': link 'base': <box size> x: must be finite and at most 1e\\+06 m" -- \
  "$bin" inspect --robot "$tmp/huge_box.urdf" --state 0
once "... once, and no range_check" "URDF '"
printf '<robot name="c"><link name="root"/><link name="a"/><link name="b"/><link name="c"/>\n<joint name="ra" type="fixed"><parent link="root"/><child link="a"/></joint>\n<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>\n<joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint>\n<joint name="ca" type="fixed"><parent link="c"/><child link="a"/></joint></robot>\n' \
  >"$tmp/cycle.urdf"
expect "inspect: a joint cycle is an error, not an endless load" 1 "" \
  "link 'a' is the child of two joints, 'ra' and 'ca'" -- timeout 20 "$bin" inspect --robot "$tmp/cycle.urdf"
printf 'name: s\nworld:\n  collision_objects:\n    - id: o\n      primitives:\n        - {type: box, dimensions: [1, 1]}\n      primitive_poses:\n        - {position: [0, 0, 0]}\n' \
  >"$tmp/short_box.yaml"
expect "scene errors carry their prefix once" 1 "" \
  "scene '.*short_box.yaml': object 'o': box needs 3 dimensions" -- \
  "$bin" plan --robot "$urdf" --srdf "$srdf" --scene "$tmp/short_box.yaml" --group arm --start left --goal right
once "... once" "scene '"
# srdf on 20000 links (every 100th with geometry): near-linear, seconds not hours.
awk 'BEGIN {
  n = 20000; print "<robot name=\"chain\">";
  for (i = 0; i < n; ++i) {
    if (i % 100 == 0) printf "<link name=\"l%d\"><collision><geometry><sphere radius=\"0.1\"/></geometry></collision></link>\n", i;
    else printf "<link name=\"l%d\"/>\n", i;
  }
  for (i = 1; i < n; ++i)
    printf "<joint name=\"j%d\" type=\"revolute\"><parent link=\"l%d\"/><child link=\"l%d\"/><origin xyz=\"0 0 1\"/><axis xyz=\"1 0 0\"/><limit lower=\"-0.01\" upper=\"0.01\" effort=\"1\" velocity=\"1\"/></joint>\n", i, i - 1, i;
  print "</robot>";
}' >"$tmp/chain.urdf"
start_s=$(date +%s)
expect "srdf on a 20000-link chain" 0 'disable_collisions link1="l0" link2="l100" reason="Adjacent"' "" -- \
  timeout 60 "$bin" srdf --robot "$tmp/chain.urdf" --samples 100
elapsed=$(($(date +%s) - start_s))
if [ "$elapsed" -le 30 ]; then echo "ok   ... in ${elapsed} s"; else
  echo "FAIL srdf on 20000 links took ${elapsed} s"; failures=$((failures + 1)); fi

problems="$arm/problems"
expect "benchmark writes an OMPL log" 0 "benchmark: 8 runs, 8 solved" "\\[2/2 problems\\]" -- \
  "$bin" benchmark --robot "$urdf" --srdf "$srdf" --problems "$problems" \
  --planners RRTConnect,PRM --runs 2 --time 5 --jobs 2 --log "$tmp/bench.log"
expect "benchmark log header" 0 "^Experiment hullcheck_hullcheck_arm_2_problems$" "" -- \
  head -2 "$tmp/bench.log"
if command -v ompl_benchmark_statistics >/dev/null && command -v python3 >/dev/null; then
  expect "ompl_benchmark_statistics reads the log" 0 "" "" -- \
    ompl_benchmark_statistics "$tmp/bench.log" -d "$tmp/bench.db"
  expect "database holds the planners and runs" 0 \
    "^geometric_PRM 4 4,geometric_RRTConnect 4 4,$" "" -- \
    python3 -c "import sqlite3, sys; c = sqlite3.connect(sys.argv[1]); print(''.join(
      f'{n} {r} {s},' for n, r, s in c.execute('select p.name, count(*), sum(r.solved) from runs r '
      'join plannerConfigs p on r.plannerid = p.id group by p.name order by p.name')))" "$tmp/bench.db"
else
  echo "FAIL ompl_benchmark_statistics or python3 missing (scripts/install-deps.sh installs ompl-demos)"
  failures=$((failures + 1))
fi
expect "benchmark shard 1/2 runs one problem" 0 "benchmark: 1 runs" "" -- \
  "$bin" benchmark --robot "$urdf" --srdf "$srdf" --problems "$problems" --shard 1/2 --time 5 \
  --log "$tmp/shard.log"
expect "benchmark: bad shard" 1 "" "--shard '2/2': expected i/n" -- \
  "$bin" benchmark --robot "$urdf" --problems "$problems" --shard 2/2 --log "$tmp/x.log"
expect "benchmark: no problems" 1 "" "no sceneNNNN.yaml/requestNNNN.yaml pairs found" -- \
  "$bin" benchmark --robot "$urdf" --problems "$arm/meshes" --log "$tmp/x.log"

# MotionBenchMaker problems (real robots with package:// meshes), when ../shared is present:
# plan from a request, validate the path, benchmark a list of problems for two robots' worth.
mbm="${HULLCHECK_SHARED_DIR:-$root/../shared}/benchmarks/mbm"
if [ -d "$mbm/panda/box_panda" ] && [ -d "$mbm/ur5/table_pick_ur5" ]; then
  panda=(--robot "$mbm/robots/panda_obj/panda.urdf" --srdf "$mbm/robots/panda_obj/panda.srdf")
  expect "MBM Panda: plan from a MotionPlanRequest" 0 "solved in" "" -- \
    "$bin" plan "${panda[@]}" --scene "$mbm/panda/box_panda/scene0001.yaml" \
    --request "$mbm/panda/box_panda/request0001.yaml" --time 10 --simplify --out "$tmp/mbm.csv"
  expect "MBM Panda: validate the planned path" 0 "path VALID" "" -- \
    "$bin" validate "${panda[@]}" --scene "$mbm/panda/box_panda/scene0001.yaml" \
    --path "$tmp/mbm.csv"
  # Plan, optimize for clearance, validate: VALID on every request of this subset.
  ur5=(--robot "$mbm/robots/ur5_robotiq85/ur5.urdf" --srdf "$mbm/robots/ur5_robotiq85/ur5.srdf")
  for problem in panda/box_panda ur5/table_pick_ur5 ur5/box_ur5; do
    if [ "${problem%%/*}" = panda ]; then robot=("${panda[@]}"); else robot=("${ur5[@]}"); fi
    files=(--scene "$mbm/$problem/scene0001.yaml" --request "$mbm/$problem/request0001.yaml")
    expect "MBM $problem: plan --optimize clearance" 0 "optimized for clearance" "" -- \
      "$bin" plan "${robot[@]}" "${files[@]}" --time 10 --simplify --optimize clearance \
      --out "$tmp/optimized_mbm.csv"
    expect "MBM $problem: the optimized path validates" 0 "path VALID" "" -- \
      "$bin" validate "${robot[@]}" "${files[@]}" --path "$tmp/optimized_mbm.csv"
  done
  printf '# two UR5 problems\n%s %s\n%s %s\n' \
    "$mbm/ur5/table_pick_ur5/scene0001.yaml" "$mbm/ur5/table_pick_ur5/request0001.yaml" \
    "$mbm/ur5/box_ur5/scene0001.yaml" "$mbm/ur5/box_ur5/request0001.yaml" >"$tmp/ur5.list"
  expect "MBM UR5: benchmark a problem list" 0 "benchmark: 2 runs, 2 solved" "\\[2/2 problems\\]" -- \
    "$bin" benchmark --robot "$mbm/robots/ur5_robotiq85/ur5.urdf" \
    --srdf "$mbm/robots/ur5_robotiq85/ur5.srdf" --problems "$tmp/ur5.list" --time 10 \
    --log "$tmp/ur5.log"
  if command -v ompl_benchmark_statistics >/dev/null; then
    expect "MBM UR5: ompl_benchmark_statistics reads the log" 0 "" "" -- \
      ompl_benchmark_statistics "$tmp/ur5.log" -d "$tmp/ur5.db"
  fi
else
  echo "skip MotionBenchMaker checks (no $mbm)"
fi

if [ "$failures" != 0 ]; then
  echo "$failures CLI check(s) failed"
  exit 1
fi
echo "all CLI checks passed"
