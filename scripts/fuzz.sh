#!/usr/bin/env bash
# Run the libFuzzer targets of tests/fuzz (docs/reliability.md):
#   scripts/fuzz.sh [--time SECONDS] [--jobs N] [--timeout SECONDS] [--build DIR] [--no-build] [TARGET...]
# Builds the fuzz programs in the sanitizer build (build/asan, configured as scripts/test.sh
# configures it: clang, ASan + UBSan, RIGSIM_FUZZ=ON) unless --no-build, generates the seed corpus
# from the source tree (tests/fuzz/make_corpus.py), and runs each TARGET (default: all; names as
# in tests/fuzz/fuzz_<name>.cpp: mcs_session, apt_framer, ...) for SECONDS (default 30), N at a
# time (default 2), with its dictionary, a per-input time limit (--timeout, default 10 s: a
# slower input is a finding), a memory limit of 2 GiB and leak detection. Prints, per target, the
# executions, executions per second, coverage (libFuzzer's cov: and ft:) and corpus size.
# Exits 1 when any target found a crash, a leak, undefined behaviour, a slow input or memory
# exhaustion; the input is kept in DIR/fuzz/findings/<target>/ (crash-*, leak-*, timeout-*,
# oom-*), to be replayed with DIR/tests/fuzz/fuzz_<target> FILE. The corpus each run grows is
# kept in DIR/fuzz/corpus/<target>/ for the next run; the logs in DIR/fuzz/logs/.
set -euo pipefail
cd "$(dirname "$0")/.."

time_s=30
jobs=2
timeout_s=10
build=build/asan
do_build=1
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --time) time_s=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    --no-build) do_build=0; shift ;;
    -h|--help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
if [ ${#targets[@]} -eq 0 ]; then
  for f in tests/fuzz/fuzz_*.cpp; do
    n=${f##*/fuzz_}
    targets+=("${n%.cpp}")
  done
fi
for t in "${targets[@]}"; do
  [ -f "tests/fuzz/fuzz_$t.cpp" ] || { echo "fuzz.sh: no target $t (tests/fuzz/fuzz_$t.cpp)" >&2; exit 2; }
done

if [ "$do_build" = 1 ]; then
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
    mcs_*) echo tests/fuzz/mcs.dict ;;
    apt_*) echo tests/fuzz/apt.dict ;;
    control_*) echo tests/fuzz/http.dict ;;
    *) echo tests/fuzz/json.dict ;;
  esac
}

# -entropic=0: libFuzzer's default input scheduling (entropic) recomputes every input's energy
# over the features the rigsim targets reach (10^5): apt_session spent a whole 30 s run reading
# its 850 seeds with it (21 exec/s), 276 exec/s without it.
# One target: its own corpus, findings folder and temporary directory (the state-file target
# writes its file there).
run_one() {
  local t=$1
  rm -rf "$work/findings/$t"   # a finding of an earlier run is replayed, not reported again
  mkdir -p "$work/corpus/$t" "$work/findings/$t" "$work/tmp/$t" "$work/seeds/$t"
  TMPDIR=$PWD/$work/tmp/$t \
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/tests/fuzz/fuzz_$t" -max_total_time="$time_s" -timeout="$timeout_s" -rss_limit_mb=2048 -detect_leaks=1 \
      -dict="$(dict_of "$t")" -entropic=0 -print_final_stats=1 -artifact_prefix="$work/findings/$t/" \
      "$work/corpus/$t" "$work/seeds/$t" >"$work/logs/$t.log" 2>&1 && echo ok >"$work/logs/$t.status" \
    || echo "FAILED (exit $?)" >"$work/logs/$t.status"
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
  [ "$result" = ok ] || failed=1
  log=$work/logs/$t.log
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+.*cov: [0-9]+' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  corpus=$(find "$work/corpus/$t" -type f | wc -l)
  printf '%-14s %12s %9s %7s %8s %8s  %s\n' "$t" "${execs:--}" "${rate:--}" "${cov:--}" "${ft:--}" "$corpus" \
    "$result"
  if [ "$result" != ok ]; then
    grep -E 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:|SUMMARY:' "$log" | head -5 | sed 's/^/    /' || true
    find "$work/findings/$t" -type f | sed 's/^/    input: /'
    echo "    log: $log"
  fi
done
echo "fuzz.sh: ${#targets[@]} targets, ${time_s} s each, $jobs at a time: $((SECONDS - start)) s"
exit $failed
