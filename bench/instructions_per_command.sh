#!/usr/bin/env bash
# User-space instructions per command of rigsimd, per protocol: a repeatable figure where CPU
# time is not (bench/README.md, "A repeatable instruction count"). For each protocol it runs
# rigsim_bench twice against rigsimd under callgrind, with SHORT and LONG timed round trips, and
# divides the difference of the two instruction counts by the difference of the commands sent
# (2 transports x (LONG - SHORT)): start-up, warm-up and shut-down cancel out.
# Usage: bench/instructions_per_command.sh [BUILD_DIR] [SHORT] [LONG]   (build/release 2000 12000)
set -euo pipefail
build=${1:-build/release}
short=${2:-2000}
long=${3:-12000}
command -v valgrind >/dev/null || { echo "instructions_per_command: valgrind is not installed" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/rigsimd" <<WRAP
#!/bin/sh
exec valgrind --tool=callgrind --callgrind-out-file="$work/cg.%p" "$(realpath "$build/rigsimd")" "\$@"
WRAP
chmod +x "$work/rigsimd"
count() {   # protocol iterations -> instructions of the daemon's whole run
  rm -f "$work"/cg.*
  "$build/bench/rigsim_bench" --daemon "$work/rigsimd" --protocol "$1" --iterations "$2" --idle-seconds 0 \
    >/dev/null 2>"$work/err" || { cat "$work/err" >&2; exit 1; }
  sed -n 's/^==[0-9]*== Collected : \([0-9]*\)$/\1/p' "$work/err" | tail -n 1
}
for protocol in mcs apt; do
  a=$(count "$protocol" "$short")
  b=$(count "$protocol" "$long")
  echo "$protocol $(( (b - a) / (2 * (long - short)) )) instructions per command ($a at $short, $b at $long round trips)"
done
