#!/usr/bin/env bash
# Builds the Release tree and runs the benchmark; arguments go to rigsim_bench
# (--iterations N, --idle-seconds S, --pin same|split|none, --daemon PATH).
# See bench/README.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/configure.sh build/release -DCMAKE_BUILD_TYPE=Release -DRIGSIM_BENCH=ON
cmake --build build/release -j2 --target rigsim_bench
exec build/release/bench/rigsim_bench "$@"
