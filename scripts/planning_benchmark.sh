#!/usr/bin/env bash
# Planning benchmark: every MotionBenchMaker Panda and UR5 problem in
# ../shared/benchmarks/mbm, RRTConnect with hullcheck's validity checker and with an FCL-based
# checker on the same shapes, in the same run (tests/benchmarks/bench_planning.cpp). Not part of
# CI. Writes per-shard CSVs and logs to build-bench/planning/ and the tables to
# tests/benchmarks/results/planning.md.
#
# Usage: scripts/planning_benchmark.sh [--time S] [--jobs N] [--per-family N] [--shared DIR]
#   --time S        solve time limit per attempt (default 10 s)
#   --jobs N        parallel processes, each a shard of both robots' problems (default: nproc;
#                   on a 2-core machine 2 shards share the cores evenly)
#   --per-family N  only the first N problems of each family (a quick sample)
#   --shared DIR    folder holding benchmarks/mbm (default ../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
time_limit=10
jobs="$(nproc)"
per_family=0
shared=../shared
while (($#)); do
  case "$1" in
    --time) time_limit="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --per-family) per_family="$2"; shift 2 ;;
    --shared) shared="$2"; shift 2 ;;
    *) echo "planning_benchmark.sh: unknown argument '$1'" >&2; exit 1 ;;
  esac
done
mbm="$shared/benchmarks/mbm"
[ -d "$mbm/panda" ] && [ -d "$mbm/ur5" ] || { echo "no MotionBenchMaker problems in $mbm" >&2; exit 1; }

scripts/install-deps.sh
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DHULLCHECK_BUILD_BENCHMARKS=ON \
  -DHULLCHECK_BUILD_TESTS=OFF >/dev/null
cmake --build build-bench -j"$(nproc)" --target bench_planning
bench=build-bench/tests/benchmarks/bench_planning
out=build-bench/planning
rm -rf "$out"
mkdir -p "$out"

start=$SECONDS
for ((i = 0; i < jobs; ++i)); do
  (
    for robot in panda ur5; do
      case "$robot" in
        panda) urdf="$mbm/robots/panda_obj/panda.urdf" srdf="$mbm/robots/panda_obj/panda.srdf" ;;
        ur5) urdf="$mbm/robots/ur5_robotiq85/ur5.urdf" srdf="$mbm/robots/ur5_robotiq85/ur5.srdf" ;;
      esac
      "$bench" run --robot "$urdf" --srdf "$srdf" --problems "$mbm/$robot" --time "$time_limit" \
        --shard "$i/$jobs" --per-family "$per_family" --guaranteed --compare-hull \
        --out "$out/$robot-$i.csv" \
        2>"$out/$robot-$i.log"
    done
  ) &
done
wait
elapsed=$((SECONDS - start))
"$bench" summarize "$out"/*.csv --table tests/benchmarks/results/planning.md --title \
"# RRTConnect on MotionBenchMaker problems: hullcheck vs an FCL-based checker

Command: \`scripts/planning_benchmark.sh --time $time_limit --jobs $jobs$( ((per_family)) && echo " --per-family $per_family")\` (Release build). \
$(nproc) cores, $(date -u +%Y-%m-%d). The whole run took $elapsed s ($jobs processes in parallel).

Solve times are medians over problems with a valid start and goal, an unsolved attempt counted \
at the time it took (the limit, $time_limit s); both checkers use OMPL's discrete motion \
validator at the same resolution. Every solution is re-checked with hullcheck's guaranteed \
motion validator; a third attempt plans with that validator itself (same random sequence)."
echo "planning benchmark: $elapsed s; tables in tests/benchmarks/results/planning.md"
