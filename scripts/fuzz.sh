#!/usr/bin/env bash
# Run the libFuzzer targets of tests/fuzz (docs/reliability.md):
#   scripts/fuzz.sh [--time SECONDS] [--runs N] [--jobs N] [--timeout SECONDS] [--max-len BYTES]
#                   [--fast] [--build DIR] [--no-build] [TARGET...]
# Builds the fuzz programs in the sanitizer build (build/asan, configured as scripts/test.sh
# configures it: clang, ASan + UBSan, RIGSIM_FUZZ=ON) unless --no-build, generates the seed corpus
# from the source tree (tests/fuzz/make_corpus.py), and runs each TARGET (default: all; names as
# in tests/fuzz/fuzz_<name>.cpp: mcs_session, apt_framer, ...) for SECONDS (default 30) or until
# it has run N inputs (--runs; with --runs and no --time, no time limit), N at a time (--jobs,
# default 2), with its dictionary, a per-input time limit (--timeout, default 10 s: a slower
# input is a finding), a memory limit of 2 GiB and leak detection; --max-len caps an input's
# size (libFuzzer's default: 4096 bytes, or the largest seed).
# --fast: the long-run build instead (build/fuzz-fast: -O2, UBSan's checks as traps, no ASan, so
# no leak detection; 3 to 13 times the executions per second), and afterwards each target's
# grown corpus replayed once through the sanitizer build's program (build/asan, when it has
# been built), so that a memory error the fast build ran past is still reported.
# Prints, per target, the executions, executions per second, coverage (libFuzzer's cov: and
# ft:) and corpus size. Exits 1 when any target found a crash, a leak, undefined behaviour, a
# slow input or memory exhaustion; the input is kept in DIR/fuzz/findings/<target>/ (crash-*,
# leak-*, timeout-*, oom-*), to be replayed with DIR/tests/fuzz/fuzz_<target> FILE. The corpus
# each run grows is kept in DIR/fuzz/corpus/<target>/ for the next run; the logs in DIR/fuzz/logs/.
set -euo pipefail
cd "$(dirname "$0")/.."

time_s=30
time_given=0
runs=""
max_len=""
fast=0
build_given=""
jobs=2
timeout_s=10
build=build/asan
do_build=1
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --time) time_s=$2; time_given=1; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --max-len) max_len=$2; shift 2 ;;
    --fast) fast=1; shift ;;
    --jobs) jobs=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --build) build_given=$2; shift 2 ;;
    --no-build) do_build=0; shift ;;
    -h|--help) sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
if [ "$fast" = 1 ]; then build=build/fuzz-fast; fi
if [ -n "$build_given" ]; then build=$build_given; fi
if [ ${#targets[@]} -eq 0 ]; then
  for f in tests/fuzz/fuzz_*.cpp; do
    n=${f##*/fuzz_}
    targets+=("${n%.cpp}")
  done
fi
for t in "${targets[@]}"; do
  [ -f "tests/fuzz/fuzz_$t.cpp" ] || { echo "fuzz.sh: no target $t (tests/fuzz/fuzz_$t.cpp)" >&2; exit 2; }
done

if [ "$do_build" = 1 ] && [ "$fast" = 1 ]; then
  bash scripts/configure.sh "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
    "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -gline-tables-only -fsanitize=undefined -fsanitize-trap=undefined" \
    -DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld -DRIGSIM_SANITIZE=OFF -DRIGSIM_WERROR=ON -DRIGSIM_BENCH=OFF \
    -DRIGSIM_FUZZ=ON
  cmake --build "$build" -j"$jobs" --target "${targets[@]/#/fuzz_}"
elif [ "$do_build" = 1 ]; then
  bash scripts/configure.sh "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG=-gline-tables-only -DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld \
    -DRIGSIM_SANITIZE=ON -DRIGSIM_WERROR=ON -DRIGSIM_BENCH=OFF -DRIGSIM_FUZZ=ON
  cmake --build "$build" -j"$jobs" --target "${targets[@]/#/fuzz_}"
fi

work=$build/fuzz
rm -rf "$work/seeds"
/usr/bin/python3 tests/fuzz/make_corpus.py --out "$work/seeds" >/dev/null
mkdir -p "$work/logs"

dict_of() {
  case "$1" in
    mcs2_*) echo tests/fuzz/mcs2.dict ;;
    mcs_*) echo tests/fuzz/mcs.dict ;;
    apt_*|tap_*) echo tests/fuzz/apt.dict ;;
    control_*) echo tests/fuzz/http.dict ;;
    *) echo tests/fuzz/json.dict ;;
  esac
}

# -entropic=0: libFuzzer's default input scheduling (entropic) recomputes every input's energy
# over the features the rigsim targets reach (10^5): apt_session spent a whole 30 s run reading
# its 850 seeds with it (21 exec/s), 276 exec/s without it.
# One target: its own corpus, findings folder and temporary directory (the state-file target
# writes its file there).
# The limits of one run: time, inputs or both.
limits=()
if [ -n "$runs" ]; then limits+=(-runs="$runs"); fi
if [ -z "$runs" ] || [ "$time_given" = 1 ]; then limits+=(-max_total_time="$time_s"); fi
if [ -n "$max_len" ]; then limits+=(-max_len="$max_len"); fi
leaks=1
if [ "$fast" = 1 ]; then leaks=0; fi   # no LeakSanitizer without ASan

run_one() {
  local t=$1
  rm -rf "$work/findings/$t"   # a finding of an earlier run is replayed, not reported again
  mkdir -p "$work/corpus/$t" "$work/findings/$t" "$work/tmp/$t" "$work/seeds/$t"
  TMPDIR=$PWD/$work/tmp/$t \
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/tests/fuzz/fuzz_$t" "${limits[@]}" -timeout="$timeout_s" -rss_limit_mb=2048 -detect_leaks=$leaks \
      -dict="$(dict_of "$t")" -entropic=0 -print_final_stats=1 -artifact_prefix="$work/findings/$t/" \
      "$work/corpus/$t" "$work/seeds/$t" >"$work/logs/$t.log" 2>&1 && echo ok >"$work/logs/$t.status" \
    || { echo "FAILED (exit $?)" >"$work/logs/$t.status"; return; }
  # The fast build has no ASan: every input of the grown corpus once more under it.
  local checked=build/asan/tests/fuzz/fuzz_$t
  if [ "$fast" = 1 ] && [ -x "$checked" ]; then
    mkdir -p "$work/asan-findings/$t"
    TMPDIR=$PWD/$work/tmp/$t ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      "$checked" -runs=0 -timeout="$((timeout_s * 6))" -rss_limit_mb=2048 -detect_leaks=1 \
        -artifact_prefix="$work/asan-findings/$t/" "$work/corpus/$t" >"$work/logs/$t.asan.log" 2>&1 \
      && echo "ok, corpus replayed under ASan" >"$work/logs/$t.status" \
      || echo "FAILED under ASan replay (exit $?): $work/logs/$t.asan.log" >"$work/logs/$t.status"
  fi
}

start=$SECONDS
for t in "${targets[@]}"; do
  rm -f "$work/logs/$t.status"
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do
    wait -n || true
  done
  run_one "$t" &
done
wait

printf '%-14s %12s %9s %7s %8s %8s  %s\n' target executions "exec/s" cov ft corpus result
failed=0
for t in "${targets[@]}"; do
  result=$(cat "$work/logs/$t.status" 2>/dev/null || echo "FAILED (no status)")
  case "$result" in ok*) ;; *) failed=1 ;; esac
  log=$work/logs/$t.log
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+.*cov: [0-9]+' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  corpus=$(find "$work/corpus/$t" -type f | wc -l)
  printf '%-14s %12s %9s %7s %8s %8s  %s\n' "$t" "${execs:--}" "${rate:--}" "${cov:--}" "${ft:--}" "$corpus" \
    "$result"
  if [ "${result#ok}" = "$result" ]; then
    grep -E 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:|SUMMARY:' "$log" | head -5 | sed 's/^/    /' || true
    find "$work/findings/$t" -type f | sed 's/^/    input: /'
    echo "    log: $log"
  fi
done
echo "fuzz.sh: ${#targets[@]} targets, ${limits[*]} each, $jobs at a time: $((SECONDS - start)) s"
exit $failed
