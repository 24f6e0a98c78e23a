#!/usr/bin/env bash
# Configure a build directory: scripts/configure.sh DIR [cmake arguments...]
# The generator is the one DIR was configured with before, else Ninja where it is installed
# (Debian's ninja-build, which scripts/deps.sh installs: it starts each compile as soon as its
# inputs exist, where Make waits for whole libraries), else Unix Makefiles. Used by run.sh,
# test.sh and bench.sh, so that they share build/release whichever made it first.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$1
shift
generator=""
if [ -f "$dir/CMakeCache.txt" ]; then
  generator=$(sed -n 's/^CMAKE_GENERATOR:INTERNAL=//p' "$dir/CMakeCache.txt")
fi
if [ -z "$generator" ]; then
  if command -v ninja >/dev/null; then generator=Ninja; else generator="Unix Makefiles"; fi
fi
exec cmake -G "$generator" -S . -B "$dir" "$@" >/dev/null
