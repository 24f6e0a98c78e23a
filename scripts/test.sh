#!/usr/bin/env bash
# Build and run the whole test suite (installing Debian packages if missing):
#  1. Release build, warnings as errors: unit, device and e2e tests.
#  2. AddressSanitizer + UndefinedBehaviorSanitizer build: unit, device and e2e tests (the
#     e2e tests start the sanitized daemon, so a memory error in it fails the test; the e2e
#     client and Catch2's runner are built plain, see tests/CMakeLists.txt).
# CI runs exactly this (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
start=$SECONDS

echo "== release build (-Werror)"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DRIGSIM_WERROR=ON >/dev/null
cmake --build build/release -j"$jobs"
echo "== release tests: unit, device, e2e"
ctest --test-dir build/release -j"$jobs" --output-on-failure --no-tests=error

echo "== sanitizer build (ASan + UBSan)"
cmake -S . -B build/asan -DCMAKE_BUILD_TYPE=Debug -DRIGSIM_SANITIZE=ON -DRIGSIM_WERROR=ON \
  -DRIGSIM_BENCH=OFF >/dev/null
cmake --build build/asan -j"$jobs" --target unit_tests device_tests rigsimd e2e_tests rigsim_modemlines
echo "== sanitizer tests: unit, device, e2e"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build/asan -j"$jobs" --output-on-failure --no-tests=error -L 'unit|device|e2e'

echo "== all tests passed in $((SECONDS - start)) s"
