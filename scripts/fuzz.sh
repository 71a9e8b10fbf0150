#!/usr/bin/env bash
# Fuzzes hullcheck's readers with libFuzzer (clang, ASan + UBSan):
#   scripts/fuzz.sh [--seconds N] [--rss-mb M] [--keep-going] [target...]
# Targets: urdf srdf scene request path mesh (default: all; "fuzz_urdf" works too). Builds
# build/fuzz with clang, replays tests/fuzz/regressions/<target>/ (see KNOWN there), then
# fuzzes each target for N seconds (default 600) with -rss_limit_mb=M (default 2048) and
# -timeout=10. Seeds: the
# checked-in tests/fuzz/seeds/<target>/ plus matching files of robots/ and ../shared (when
# present), copied into build/fuzz/seeds/<target>/ at each run; new inputs accumulate in
# build/fuzz/corpus/<target>/. Crashes, timeouts, OOMs and leaks go to
# build/fuzz/findings/<target>/. Prints one summary line per target; exits 1 when anything was
# found (or a regression input fails), 2 on usage errors. --keep-going: libFuzzer's fork mode
# (-fork=1 -ignore_crashes/timeouts/ooms), which goes on after a finding and collects them all
# (peak RSS is then the largest process's, measured by /usr/bin/time). CI: scripts/fuzz.sh --seconds 5
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
shared="$root/../shared"
build="${FUZZ_BUILD_DIR:-$root/build/fuzz}"  # FUZZ_BUILD_DIR: another build folder
seconds=600
rss_mb=2048
keep_going=0
targets=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --rss-mb) rss_mb="$2"; shift 2 ;;
    --keep-going) keep_going=1; shift ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) targets+=("${1#fuzz_}"); shift ;;
  esac
done
all=(urdf srdf scene request path mesh)
[[ ${#targets[@]} -gt 0 ]] || targets=("${all[@]}")
for t in "${targets[@]}"; do
  [[ " ${all[*]} " == *" $t "* ]] || { echo "fuzz.sh: unknown target $t" >&2; exit 2; }
done

# Build (ccache when present; the instrumented library is separate from the gcc builds).
source scripts/compiler_cache.sh
# FUZZ_CXX_FLAGS: optimisation and debug flags (default -O1 -g1; CI uses -O0, about three
# times faster to compile, for its few seconds per target).
CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="${FUZZ_CXX_FLAGS:--O1 -g1}" -DHULLCHECK_BUILD_FUZZERS=ON \
  -DHULLCHECK_BUILD_TESTS=OFF -DHULLCHECK_BUILD_PYTHON=OFF "${launcher[@]}" >/dev/null
cmake --build "$build" -j"${FUZZ_BUILD_JOBS:-2}" --target "${targets[@]/#/fuzz_}"

# Copies the files found under $1 matching the find(1) tests after it into $dest, at most
# $cap bytes each and $limit files per folder (names made unique by a counter).
copy_seeds() {
  local dir="$1"; shift
  [[ -d "$dir" ]] || return 0
  local n=0
  declare -A per_dir=()
  while IFS= read -r -d '' f; do
    local d; d="$(dirname "$f")"
    per_dir[$d]=$(( ${per_dir[$d]:-0} + 1 ))
    [[ ${per_dir[$d]} -le $limit ]] || continue
    n=$((n + 1))
    cp "$f" "$dest/$(basename "$(dirname "$f")")_${n}_$(basename "$f")"
  done < <(find -L "$dir" -type f -size -"$cap"c "$@" -print0 | sort -z)
}

# The seed corpus of target $1 in build/fuzz/seeds/$1.
make_seeds() {
  dest="$build/seeds/$1"
  rm -rf "$dest"; mkdir -p "$dest"
  cp "$root/tests/fuzz/seeds/$1/"* "$dest/" 2>/dev/null || true
  limit=1000000
  case "$1" in
    urdf) cap=65536; copy_seeds "$root/robots" -name '*.urdf'
          copy_seeds "$shared/robots" -name '*.urdf'
          copy_seeds "$shared/benchmarks/mbm/robots" -name '*.urdf' ;;
    srdf) cap=65536; copy_seeds "$root/robots" -name '*.srdf'
          copy_seeds "$shared/robots" -name '*.srdf'
          copy_seeds "$shared/benchmarks/mbm/robots" -name '*.srdf' ;;
    scene) cap=16384; copy_seeds "$root/robots" -name '*.yaml' ! -name 'request*'
           limit=4; copy_seeds "$shared/benchmarks/mbm" -name 'scene*.yaml' ;;
    request) cap=16384; copy_seeds "$root/robots" -name 'request*.yaml'
             limit=4; copy_seeds "$shared/benchmarks/mbm" -name 'request*.yaml' ;;
    path) ;;  # tests write their path files at run time: the checked-in seeds only
    mesh) cap=65536; limit=6
          copy_seeds "$root/robots" \( -iname '*.stl' -o -iname '*.obj' -o -iname '*.dae' \)
          copy_seeds "$shared/robots" \( -iname '*.stl' -o -iname '*.obj' -o -iname '*.dae' \) ;;
  esac
}

# Per-target input size limit (bytes): a little above the largest real file of its kind.
max_len() {
  case "$1" in
    urdf|srdf|mesh) echo 65536 ;;
    scene) echo 16384 ;;
    request) echo 8192 ;;
    path) echo 4096 ;;
  esac
}

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$root/tests/fuzz/lsan.supp:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
summary=()
for t in "${targets[@]}"; do
  bin="$build/tests/fuzz/fuzz_$t"
  findings="$build/findings/$t"
  corpus="$build/corpus/$t"
  log="$build/logs/$t.log"
  mkdir -p "$findings" "$corpus" "$(dirname "$log")"
  make_seeds "$t"
  mode=()
  [[ $keep_going -eq 0 ]] || mode=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  dict=()
  [[ -f "$root/tests/fuzz/dicts/$t.dict" ]] && dict=(-dict="$root/tests/fuzz/dicts/$t.dict")
  # Every regression input must run clean (libFuzzer executes files given as arguments), except
  # those listed in tests/fuzz/regressions/KNOWN (bugs being fixed): they are replayed and
  # reported, and one that passes asks to be taken off the list.
  replay="none"
  ok=0; failed=(); open_bugs=0; fixed=()
  : >"$build/logs/$t.regressions.log"
  for input in "$root/tests/fuzz/regressions/$t"/*; do
    [[ -f "$input" ]] || continue
    name="$t/$(basename "$input")"
    known=0
    grep -qxF "$name" "$root/tests/fuzz/regressions/KNOWN" 2>/dev/null && known=1
    if "$bin" -timeout=10 -rss_limit_mb="$rss_mb" "$input" >>"$build/logs/$t.regressions.log" 2>&1
    then
      ok=$((ok + 1)); [[ $known -eq 0 ]] || fixed+=("$name")
    elif [[ $known -eq 1 ]]; then
      open_bugs=$((open_bugs + 1))
    else
      failed+=("$name")
    fi
  done
  if [[ $((ok + open_bugs + ${#failed[@]})) -gt 0 ]]; then
    replay="$ok ok, $open_bugs known open, ${#failed[@]} failed"
    [[ ${#failed[@]} -eq 0 ]] || { status=1; echo "   regression failed: ${failed[*]}"; }
    [[ ${#fixed[@]} -eq 0 ]] || echo "   known bug now passes (remove from KNOWN): ${fixed[*]}"
  fi
  before=$(find "$findings" -type f | wc -l)
  echo "== fuzz_$t: ${seconds} s, -rss_limit_mb=$rss_mb, log $log"
  set +e
  timer=()
  [[ ! -x /usr/bin/time ]] || timer=(/usr/bin/time -o "$build/logs/$t.maxrss" -f '%M')
  "${timer[@]}" timeout --kill-after=30 $((seconds + 300)) "$bin" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb="$rss_mb" -max_len="$(max_len "$t")" -print_final_stats=1 \
    -artifact_prefix="$findings/" "${mode[@]}" "${dict[@]}" "$corpus" "$build/seeds/$t" >"$log" 2>&1
  rc=$?
  set -e
  after=$(find "$findings" -type f | wc -l)
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  [[ -n "$execs" ]] || execs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#' || true)
  peak=$(grep -o 'stat::peak_rss_mb: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  if [[ -z "$peak" && -s "$build/logs/$t.maxrss" ]]; then
    peak=$(( $(tail -1 "$build/logs/$t.maxrss" | grep -o '^[0-9]*') / 1024 ))
  fi
  new=$((after - before))
  if [[ $rc -ne 0 || $new -ne 0 ]]; then
    status=1
    grep -m1 -E '^==[0-9]+==ERROR|runtime error|ERROR: libFuzzer|uncaught exception|terminate called' \
      "$log" | sed 's/^/   /' || true
  fi
  units=$(grep -o 'corp: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || true)
  line=$(printf 'fuzz_%-8s execs %-9s corpus %-5s peak_rss %5s MB  findings %d (exit %d)  regressions %s' \
    "$t" "${execs:-?}" "${units:-?}" "${peak:-?}" "$new" "$rc" "$replay")
  echo "$line"
  summary+=("$line")
done
echo "== summary (${seconds} s per target, -rss_limit_mb=$rss_mb, -timeout=10; findings in $build/findings)"
printf '%s\n' "${summary[@]}"
exit $status
