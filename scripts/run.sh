#!/usr/bin/env bash
# Build rigsimd in Release (installing Debian packages if missing) and run it.
# Without arguments it runs the built-in default rig; arguments go to rigsimd
# (e.g. scripts/run.sh --config config/examples/three_axis_stack.json).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
bash scripts/configure.sh build/release -DCMAKE_BUILD_TYPE=Release
# rigsimctl and the RTS/DTR shim (librigsim_modemlines.so, for serial clients that toggle
# RTS/DTR: docs/cli.md) beside the daemon.
cmake --build build/release -j"$jobs" --target rigsimd rigsim_modemlines
exec build/release/rigsimd "$@"
