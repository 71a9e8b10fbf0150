#!/usr/bin/env bash
# Clearance optimization benchmark: every MotionBenchMaker Panda and UR5 problem in
# ../shared/benchmarks/mbm: RRTConnect + simplify, then optimize_clearance, against RRT* and
# BIT* with OMPL's MaximizeMinClearanceObjective given the same total time
# (tests/benchmarks/bench_clearance_optimization.cpp). Not part of CI. Writes per-shard CSVs and
# logs to build-bench/optimization/ and the tables to tests/benchmarks/results/optimization.md.
#
# Usage: scripts/optimization_benchmark.sh [--time S] [--margin M] [--jobs N] [--per-family N]
#                                          [--shared DIR]
#   --time S        RRTConnect time limit per problem (default 5 s)
#   --margin M      the optimizer's margin and the clearance scope's, m (default 0.05); the
#                   tables go to results/optimization.md at the default, else to
#                   results/optimization_margin_M.md
#   --jobs N        parallel processes, each a shard of both robots' problems (default 1: the
#                   optimizer's and the peers' times are measured on an otherwise idle core)
#   --per-family N  only the first N problems of each family (a quick sample)
#   --shared DIR    folder holding benchmarks/mbm (default ../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
time_limit=5
margin=0.05
jobs=1
per_family=0
shared=../shared
while (($#)); do
  case "$1" in
    --time) time_limit="$2"; shift 2 ;;
    --margin) margin="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --per-family) per_family="$2"; shift 2 ;;
    --shared) shared="$2"; shift 2 ;;
    *) echo "optimization_benchmark.sh: unknown argument '$1'" >&2; exit 1 ;;
  esac
done
mbm="$shared/benchmarks/mbm"
[ -d "$mbm/panda" ] && [ -d "$mbm/ur5" ] || { echo "no MotionBenchMaker problems in $mbm" >&2; exit 1; }

scripts/install-deps.sh
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DHULLCHECK_BUILD_BENCHMARKS=ON \
  -DHULLCHECK_BUILD_TESTS=OFF >/dev/null
cmake --build build-bench -j"$(nproc)" --target bench_clearance_optimization
bench=build-bench/tests/benchmarks/bench_clearance_optimization
out=build-bench/optimization
rm -rf "$out"
mkdir -p "$out"
table=tests/benchmarks/results/optimization.md
[ "$margin" = 0.05 ] || table="tests/benchmarks/results/optimization_margin_$margin.md"
commit="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"

start=$SECONDS
for ((i = 0; i < jobs; ++i)); do
  (
    for robot in panda ur5; do
      case "$robot" in
        panda) urdf="$mbm/robots/panda_obj/panda.urdf" srdf="$mbm/robots/panda_obj/panda.srdf" ;;
        ur5) urdf="$mbm/robots/ur5_robotiq85/ur5.urdf" srdf="$mbm/robots/ur5_robotiq85/ur5.srdf" ;;
      esac
      "$bench" run --robot "$urdf" --srdf "$srdf" --problems "$mbm/$robot" --time "$time_limit" \
        --margin "$margin" --shard "$i/$jobs" --per-family "$per_family" --out "$out/$robot-$i.csv" \
        2>"$out/$robot-$i.log"
    done
  ) &
done
wait
elapsed=$((SECONDS - start))
"$bench" summarize "$out"/*.csv --table "$table" --margin "$margin" --title \
"# Clearance optimization on MotionBenchMaker problems

Command: \`scripts/optimization_benchmark.sh --time $time_limit$( [ "$margin" = 0.05 ] || echo " --margin $margin") --jobs $jobs$( ((per_family)) && echo " --per-family $per_family")\` (Release build, commit $commit). \
$(nproc) cores, $(date -u +%Y-%m-%d). The whole run took $elapsed s ($jobs process(es)).

Every planner checks motions with the guaranteed (certified) validator; the clearance scope is \
optimization_scope at the margin ($margin m): obstacles and the self pairs the group moves and \
can take clear of it. Clearance is the minimum obstacle clearance over the middle 80% of \
the path (201 states evenly spaced in arc length from 10% to 90%). The optimizer runs with its \
defaults (length weight 0.1, budget 0.1 s) and margin $margin m on the RRTConnect + simplify path; \
its time is its own. RRT* and BIT* get, per problem, the time RRTConnect, the simplifier and \
the optimizer took together; they optimise OMPL's MaximizeMinClearanceObjective on the same \
scoped clearance; an unsolved run counts as not solved. Ratios are medians of per-problem \
ratios against RRTConnect + simplify on the same problem. The second table compares, problem by \
problem, the optimized path with each peer's where the peer solved."
echo "optimization benchmark: $elapsed s; tables in $table"
