#!/usr/bin/env bash
# Build and run the whole test suite (installing Debian packages if missing):
#  1. Release build with GCC, warnings as errors: the daemon users run, rigsim-tap and the e2e
#     client, and the e2e, Python, docs and browser tests against them (the live view in Debian's
#     headless Chromium). The unit and device tests are not
#     compiled here: they test the libraries' code, which the sanitizer pass builds and runs them
#     against with the sanitizers watching; compiling them twice was 250 of the 1,400 CPU seconds
#     of a CI run (docs/architecture.md#build-options). `cmake --build build/release` builds them
#     for a developer. Nor are the benchmarks (bench/ measures, it is not a test; scripts/bench.sh
#     builds them).
#  2. AddressSanitizer + UndefinedBehaviorSanitizer build with clang, warnings as errors: unit,
#     device, e2e and Python tests against the sanitized daemon (a memory error or undefined
#     behaviour in it fails the test; the e2e client and Catch2's runner are built plain, see
#     tests/CMakeLists.txt). Clang compiles this pass in half GCC's time (docs/architecture.md,
#     "Build options") and is a second compiler's warnings on every file. The same objects are
#     instrumented for libFuzzer (RIGSIM_FUZZ), so that the fuzz programs of tests/fuzz link
#     against them: the libraries are built once for both.
#  3. Fuzzing: every target of tests/fuzz for 20 s (scripts/fuzz.sh, all of them at once: each
#     still runs 20 s on its share of the cores, the stage one round of wall time), from seeds
#     generated from the golden transcripts and test inputs; any crash,
#     leak, undefined behaviour, slow input or memory exhaustion fails the run
#     (docs/reliability.md).
# CI runs exactly this (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
mark() { echo "== $1 ($((SECONDS - start)) s)"; }
mark "Debian packages"
bash scripts/deps.sh --test
jobs=$(nproc 2>/dev/null || echo 2)

mark "release build (GCC, -Werror)"
bash scripts/configure.sh build/release -DCMAKE_BUILD_TYPE=Release -DRIGSIM_WERROR=ON -DRIGSIM_BENCH=OFF
cmake --build build/release -j"$jobs" --target rigsimd rigsim-tap rigsim_modemlines e2e_tests
# The tests wait on sockets, ptys and child processes more than they compute: twice as many at
# once as there are cores keeps the cores busy (release: 21 s against 31 s at -j2).
mark "release tests: e2e, python, docs, browser"
ctest --test-dir build/release -j"$((jobs * 2))" --output-on-failure --no-tests=error -L 'e2e|python|docs|browser'

# Line tables are all a sanitizer report needs to name every frame's file and line (15 % less
# compile time than full -g on the largest batch); lld links the sanitized programs in a fifth of
# GNU ld's time (device_tests: 0.9 s against 4.7 s).
mark "sanitizer build (clang, ASan + UBSan, -Werror)"
bash scripts/configure.sh build/asan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG=-gline-tables-only -DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld \
  -DRIGSIM_SANITIZE=ON -DRIGSIM_WERROR=ON -DRIGSIM_BENCH=OFF -DRIGSIM_FUZZ=ON
cmake --build build/asan -j"$jobs" --target unit_tests device_tests rigsimd rigsim-tap e2e_tests rigsim_modemlines rigsim_fuzz
mark "sanitizer tests: unit, device, e2e, fuzz regressions"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build/asan -j"$((jobs * 2))" --output-on-failure --no-tests=error -L 'unit|device|e2e|fuzz'

mark "fuzzing: every target 20 s"
# One round of 20 s, however many targets: all of them at once, sharing the cores.
fuzz_targets=$(ls tests/fuzz/fuzz_*.cpp | wc -l)
bash scripts/fuzz.sh --no-build --time 20 --jobs "$fuzz_targets"

mark "all tests passed"
