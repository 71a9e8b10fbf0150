#!/usr/bin/env bash
# CI smoke run of bench_planning: the first Panda problem of each MotionBenchMaker family with
# both checkers (and guaranteed motions), then the summary tables. Skipped (exit 77) without
# the shared data.
# Usage: bench_planning_smoke.sh BENCH_PLANNING SHARED_DIR OUT_DIR
set -euo pipefail
bench="$1" mbm="$2/benchmarks/mbm" out="$3"
if [ ! -d "$mbm/panda" ]; then
  echo "no MotionBenchMaker problems in $mbm: skipped"
  exit 77
fi
mkdir -p "$out"
"$bench" run --robot "$mbm/robots/panda_obj/panda.urdf" --srdf "$mbm/robots/panda_obj/panda.srdf" \
  --problems "$mbm/panda" --per-family 1 --time 2 --guaranteed --out "$out/smoke.csv"
lines=$(wc -l <"$out/smoke.csv")
[ "$lines" -eq 22 ] || { echo "expected 21 result lines + header, got $lines" >&2; exit 1; }
"$bench" summarize "$out/smoke.csv" --table "$out/smoke.md" | tee /dev/stderr | grep -q "^| panda | 7 |"
